#pragma once
/// The MCAP recorder: a Bridge that writes every Bus topic to an MCAP file in the `ros2`
/// profile (CDR messages, `ros2msg` schemas), zstd-compressed chunks with message indexes and a
/// summary, so Foxglove and other indexed readers can seek (docs/recording.md).
///
/// Message records: log_time = sim time when the message was published on the Bus;
/// publish_time = its header stamp (the log time for unstamped messages); sequence = a
/// per-channel count from 1, assigned on the simulation thread (so drops show as gaps).
/// Serialising and compressing happen on the recorder's own thread. Lossless mode (lockstep
/// runs) blocks the simulation thread when the queue is full, which keeps recordings
/// deterministic; otherwise (realtime runs) the oldest queued message is dropped and counted.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bridges/mcap/compression.h"
#include "bridges/mcap/mcap_records.h"
#include "bridges/mcap/mcap_writer.h"
#include "bus/bridge.h"

namespace rescuesim {

/// Settings of the recorder.
struct McapOptions {
  std::filesystem::path path;                          ///< the recording; PATH.part until stop() finishes it
  mcap::Compression compression = mcap::Compression::zstd;
  int compression_level = 3;                           ///< zstd level
  std::size_t chunk_size = std::size_t(1) << 20;       ///< uncompressed bytes per chunk
  /// Sim-time budget of a chunk (s, 0 off): a chunk is written once it spans this much log time,
  /// so a killed run loses at most about this much sim time (`rescuesim recover` saves the rest).
  double chunk_seconds = 1.0;
  /// Wall-time budget of a chunk (s, 0 off), for bounded (realtime) recordings only: lossless
  /// (lockstep) recordings ignore it, so they stay byte-identical per seed.
  double chunk_wall_seconds = 1.0;
  bool lossless = true;                                ///< block the simulation thread rather than drop (lockstep)
  std::size_t queue_size = 1024;                       ///< messages waiting for the recorder thread
  std::string library = "rescuesim";                   ///< Header.library, e.g. "rescuesim 0.1.0"
  std::vector<mcap::Metadata> metadata;                ///< written first (rescuesim writes the run's description)
  std::vector<mcap::Attachment> attachments;           ///< written first (scenario.yaml, world.svg)
};

/// What a recording cost and produced.
struct McapRecordingStats {
  mcap::WriterStats writer;       ///< messages, chunks, bytes before and after compression
  std::uint64_t dropped = 0;      ///< messages dropped (queue full in realtime mode, or after a write error)
  double busy_seconds = 0;        ///< recorder thread time spent serialising, compressing and writing
  std::string error;              ///< the first write error, "" when none
};

/// The recorder bridge (see the file comment).
class McapRecorder : public Bridge {
 public:
  explicit McapRecorder(McapOptions options);
  ~McapRecorder() override;
  std::string name() const override { return "mcap"; }
  /// Creates PATH.part, writes the header, the run's metadata and attachments and one channel
  /// per Bus topic, subscribes to every topic and starts the recorder thread. Throws Error
  /// naming the file when it cannot be created.
  void start(BridgeHost& host) override;
  /// Writes what is queued, the summary and the footer, and renames PATH.part to PATH.
  void stop() override;
  BridgeStats stats() const override;
  McapRecordingStats recording() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The recorder as a Bridge.
std::unique_ptr<Bridge> make_mcap_recorder(const McapOptions& options);

/// `offered_qos_profiles` of a channel in the ros2 profile, as rosbag2 writes it (YAML):
/// reliable, volatile, keep-last; latched topics (/tf_static) transient-local with depth 1.
std::string offered_qos_profiles(bool latched);

}  // namespace rescuesim
