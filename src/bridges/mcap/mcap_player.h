#pragma once
/// Replay of a rescuesim recording: the run's world is rebuilt from the recording by the caller
/// (run_record/run_record.h rebuilds a rescuesim run's from its scenario and world.svg, so that
/// this transport parses no scenario) and put behind a ReplayHost (a Bus and a clock; no
/// physics, no ray scene); every recorded topic is advertised on that Bus; then the recorded messages are decoded and
/// published on it in file (= log-time) order, paced to the wall clock, so bridges attached to
/// the host (ROS 1, ROS 2, Foxglove, even a recorder) re-publish the recording as if it were
/// running. The host's clock is set to each message's log time before it is published, so
/// bridges that read sim time see replay time.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>

#include "bridges/mcap/mcap_reader.h"
#include "bridges/mcap/replay_host.h"
#include "msgs/serialize.h"
#include "world/world.h"

namespace rescuesim {

/// Where a replay is.
struct PlayProgress {
  double log_time = 0;        ///< s since the first message
  double duration = 0;        ///< s from the first to the last message (statistics)
  double wall_time = 0;       ///< s since play() began
  std::uint64_t messages = 0; ///< published so far
};

/// How a replay went.
struct PlayResult {
  std::uint64_t messages = 0;   ///< published on the Bus
  std::uint64_t skipped = 0;    ///< not published: a type rescuesim does not know, or bytes that did not decode
  double duration = 0;          ///< s of log time replayed
  double wall_time = 0;         ///< s it took
  bool interrupted = false;     ///< stopped by the caller
};

/// The world a recording's messages came from, and its run's seed: what the player's host needs.
struct ReplayWorld {
  World world;
  std::uint64_t seed = 0;
};

/// Rebuilds the world from the open recording (run_record.h's rebuild_run for a rescuesim
/// recording); throws Error when it cannot.
using RebuildWorld = std::function<ReplayWorld(const mcap::McapReader&)>;

class McapPlayer {
 public:
  /// Opens and checks the recording, rebuilds its world with `rebuild` and advertises its
  /// topics. Throws Error naming the file for a damaged file, or what `rebuild` throws.
  McapPlayer(const std::filesystem::path& path, const RebuildWorld& rebuild);
  ~McapPlayer();

  /// What bridges attach to (before play()): the Bus, the world, the replay clock.
  ReplayHost& host() { return *host_; }
  const mcap::McapReader& reader() const { return reader_; }
  const World& world() const { return replayed_.world; }

  /// Publishes every message, the one at log time t at wall time (t - t_first) / rate after
  /// the start (rate: sim seconds per wall second, > 0). Returns when done or once `stop` is
  /// set; `progress` is called about every 0.1 s of wall time.
  PlayResult play(double rate, const std::atomic<bool>* stop = nullptr,
                  const std::function<void(const PlayProgress&)>& progress = nullptr);

 private:
  struct Route {
    TopicId topic = kNoTopic;                 ///< Bus topic, kNoTopic: not replayed
    const msg::TypeSupport* type = nullptr;
  };
  const Route& route(const mcap::Channel& channel);

  mcap::McapReader reader_;
  ReplayWorld replayed_;
  std::unique_ptr<ReplayHost> host_;           ///< on replayed_.world
  std::map<std::uint16_t, Route> routes_;      ///< by channel id
};

}  // namespace rescuesim
