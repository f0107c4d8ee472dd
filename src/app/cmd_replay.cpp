// rescuesim replay: re-publishes an MCAP recording through the bridges (ROS 1, ROS 2,
// Foxglove, even another recording), at the recorded pace or scaled. The world is rebuilt from
// the recording, but nothing is simulated: bridges attach to a ReplayHost, a Bus and a clock
// without physics (bridges/mcap/mcap_player.h).

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <vector>

#include "app/bridge_flags.h"
#include "app/commands.h"
#include "core/error.h"
#include "robots/rescue_robot.h"
#ifdef RESCUESIM_HAS_MCAP
#include "bridges/mcap/mcap_player.h"
#include "run_record/run_record.h"
#endif

namespace rescuesim::app {

namespace {

std::atomic<bool> g_replay_interrupted{false};
extern "C" void on_replay_signal(int) { g_replay_interrupted.store(true); }

struct ReplayCommand {
  std::string file;
  double rate = 1.0;
  bool quiet = false;
  BridgeFlags bridges;
};

#ifdef RESCUESIM_HAS_MCAP

/// What the recording holds: where it came from, how long, which topics.
void print_recording(const McapPlayer& player, const RecordedRun& run) {
  const mcap::McapReader& r = player.reader();
  std::printf("recording %s (%.1f MB, %zu chunks, written by %s)\n", r.path().string().c_str(), static_cast<double>(r.file_size()) / 1e6,
              r.chunk_count(), r.header().library.c_str());
  std::printf("  scenario      %s (seed %llu), world %s\n", run.scenario.name.c_str(), static_cast<unsigned long long>(run.scenario.seed),
              run.spec.name.c_str());
  if (const auto& st = r.statistics()) {
    std::printf("  messages      %llu over %.1f s of sim time\n", static_cast<unsigned long long>(st->message_count),
                1e-9 * static_cast<double>(st->message_end_time - st->message_start_time));
    std::vector<std::pair<std::string, std::uint64_t>> topics;
    for (const auto& [id, n] : st->channel_message_counts) {
      const auto c = r.channels().find(id);
      if (c != r.channels().end()) topics.emplace_back(c->second.topic, n);
    }
    std::sort(topics.begin(), topics.end());
    for (const auto& [topic, n] : topics) std::printf("    %-32s %8llu\n", topic.c_str(), static_cast<unsigned long long>(n));
  }
}

int replay(const ReplayCommand& c) {
  const ModelMap models = builtin_models();
  RecordedRun run;
  McapPlayer player(c.file, rebuild_into(run, models));
  // a recording made of a replay is paced, so it is bounded (drop oldest) rather than lossless
  Scenario paced = run.scenario;
  paced.realtime = true;
  const auto cameras = std::find_if(run.info.begin(), run.info.end(), [](const auto& kv) { return kv.first == "cameras"; });
  auto bridges = make_bridges(c.bridges, {&paced, &run.spec, cameras == run.info.end() || cameras->second != "off"});
  print_recording(player, run);
  for (auto& b : bridges) {
    b->start(player.host());
    std::printf("  bridge        %s started\n", b->name().c_str());
  }
  if (bridges.empty()) {
    std::printf("  no bridge     (--ros1, --ros2, --foxglove or --record): messages are published in-process only, which\n"
                "                checks every chunk of the file\n");
  }
  std::printf("replaying at %gx\n", c.rate);
  std::fflush(stdout);

  g_replay_interrupted = false;
  std::signal(SIGINT, on_replay_signal);
  std::signal(SIGTERM, on_replay_signal);
  const bool tty = ::isatty(STDERR_FILENO);
  bool told_commands = false;
  double next_line = 0;
  const PlayResult r = player.play(c.rate, &g_replay_interrupted, [&](const PlayProgress& p) {
    // nothing is simulated: the host discards the commands that bridges take in
    for (const auto& b : bridges) {
      if (!told_commands && player.host().discarded() > 0 && b->stats().received > 0) {
        std::fprintf(stderr,
                     "%sreplay: commands received through %s are ignored (a replay re-publishes a recording; nothing is simulated)\n",
                     tty ? "\n" : "", b->name().c_str());
        told_commands = true;
      }
    }
    if (c.quiet || (!tty && p.log_time < next_line)) return;
    next_line = p.log_time + std::max(1.0, p.duration / 10);
    std::fprintf(stderr, "%s%7.1f/%.1f s of recording, %llu messages, %.1fx%s", tty ? "\r" : "", p.log_time, p.duration,
                 static_cast<unsigned long long>(p.messages), p.wall_time > 0 ? p.log_time / p.wall_time : 0.0, tty ? "  " : "\n");
    std::fflush(stderr);
  });
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!c.quiet && tty) std::fprintf(stderr, "\n");
  for (auto& b : bridges) {
    b->stop();
    const BridgeStats st = b->stats();
    std::printf("bridge %s: %llu messages sent, %llu dropped, %llu commands received (ignored)\n", b->name().c_str(),
                static_cast<unsigned long long>(st.sent), static_cast<unsigned long long>(st.dropped),
                static_cast<unsigned long long>(st.received));
  }
  std::printf("replayed %llu messages (%.1f s of recording) in %.1f s%s", static_cast<unsigned long long>(r.messages), r.duration,
              r.wall_time, r.interrupted ? "; interrupted" : "");
  if (r.skipped) std::printf("; %llu skipped (see the warnings)", static_cast<unsigned long long>(r.skipped));
  std::printf("\n");
  return kExitOk;
}

#else

int replay(const ReplayCommand&) {
  throw Error("replay: this rescuesim was built without MCAP support (libzstd/liblz4 not found at build time; "
              "run scripts/install-deps.sh and rebuild)");
}

#endif

}  // namespace

void add_replay_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<ReplayCommand>();
  CLI::App* cmd = app.add_subcommand("replay", "Re-publish an MCAP recording through the ROS, Foxglove or MCAP bridges");
  cmd->footer(
      "Plays a recording made with 'rescuesim run --record FILE.mcap' into the same bridges a run\n"
      "uses, at the recorded pace (--rate 2: twice as fast). Messages keep their recorded stamps;\n"
      "/clock and sim time follow the recording. The world is rebuilt from the recording (its\n"
      "scenario and world.svg) but nothing is simulated: cmd_vel sent during a replay is ignored.\n"
      "The file is checked first (magic, records, CRCs); a damaged file is an error (exit 2)\n"
      "naming the offset and record. See docs/recording.md.\n\n"
      "Examples:\n"
      "  rescuesim run --duration 60 --record runs/demo.mcap\n"
      "  rescuesim replay runs/demo.mcap --foxglove          then open ws://localhost:8765 in Foxglove\n"
      "  rescuesim replay runs/demo.mcap --ros2 --rate 2     as ROS 2 topics, twice as fast\n"
      "  roscore &  rescuesim replay runs/demo.mcap --ros1 --use-sim-time\n"
      "  rescuesim replay runs/demo.mcap --rate 100          no bridge: checks every chunk quickly\n"
      "(Foxglove can also open the .mcap file directly: File > Open local file.)");
  cmd->add_option("file", c->file, "the recording (.mcap)")->required();
  cmd->add_option("--rate", c->rate, "pace: recorded seconds per wall second (default 1)")->check(CLI::PositiveNumber);
  cmd->add_flag("--quiet,-q", c->quiet, "no progress line");
  add_bridge_flags(cmd, c->bridges);
  // a replay has no steps to take and no controllers to keep
  for (const char* name : {"--lockstep", "--keep-controllers"}) {
    if (CLI::Option* o = cmd->get_option_no_throw(name)) cmd->remove_option(o);
  }
  cmd->final_callback([c, &action] { action = [c] { return replay(*c); }; });
}

}  // namespace rescuesim::app
