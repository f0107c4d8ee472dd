// rescuesim recover: turns the FILE.mcap.part a killed recording left behind into an indexed
// FILE.mcap, up to its last complete chunk (bridges/mcap/mcap_recover.h).

#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "core/error.h"
#ifdef RESCUESIM_HAS_MCAP
#include "bridges/mcap/mcap_recover.h"
#endif

namespace rescuesim::app {

namespace {

struct RecoverCommand {
  std::string input;
  std::string output;
  bool force = false;
};

/// FILE.mcap for FILE.mcap.part; FILE.recovered.mcap for anything else.
std::filesystem::path default_output(const std::filesystem::path& input) {
  if (input.extension() == ".part") return input.parent_path() / input.stem();
  std::filesystem::path out = input.parent_path() / input.stem();
  out += ".recovered.mcap";
  return out;
}

int recover(const RecoverCommand& c) {
#ifdef RESCUESIM_HAS_MCAP
  namespace fs = std::filesystem;
  const fs::path in = c.input;
  const fs::path out = c.output.empty() ? default_output(in) : fs::path(c.output);
  std::error_code ec;
  if (fs::exists(out, ec) && fs::equivalent(in, out, ec)) throw Error({out.string(), 0, "-o"}, "the output would overwrite the input");
  if (fs::exists(out, ec) && !c.force) throw Error({out.string(), 0, "-o"}, "the output exists already (--force replaces it)");
  const mcap::RecoveryReport r = mcap::recover_mcap(in, out);

  std::printf("recovered %s -> %s\n", in.string().c_str(), out.string().c_str());
  std::printf("  saved         %llu messages on %llu channels (%llu schemas) from %llu complete chunks, %llu metadata, %llu attachments\n",
              static_cast<unsigned long long>(r.messages), static_cast<unsigned long long>(r.channels),
              static_cast<unsigned long long>(r.schemas), static_cast<unsigned long long>(r.chunks_read),
              static_cast<unsigned long long>(r.metadata), static_cast<unsigned long long>(r.attachments));
  if (r.messages > 0) {
    std::printf("  time range    %.3f .. %.3f s of log (sim) time\n", 1e-9 * static_cast<double>(r.start_time),
                1e-9 * static_cast<double>(r.end_time));
  }
  for (const auto& [topic, n] : r.messages_per_topic) std::printf("    %-32s %8llu\n", topic.c_str(), static_cast<unsigned long long>(n));
  if (r.finished) {
    std::printf("  dropped       nothing: the recording was finished (its data section is copied and indexed again)\n");
  } else {
    std::printf("  dropped       %llu of %llu bytes: %s\n", static_cast<unsigned long long>(r.dropped_bytes()),
                static_cast<unsigned long long>(r.input_bytes), r.dropped_reason.c_str());
  }
  return kExitOk;
#else
  (void)c;
  throw Error("recover: this rescuesim was built without MCAP support (libzstd/liblz4 not found at build time; "
              "run scripts/install-deps.sh and rebuild)");
#endif
}

}  // namespace

void add_recover_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<RecoverCommand>();
  CLI::App* cmd = app.add_subcommand("recover", "Make an indexed MCAP file of a killed recording (FILE.mcap.part)");
  cmd->footer(
      "A run killed while recording (kill -9, a crash, power loss) leaves FILE.mcap.part: its\n"
      "chunks are complete up to the last one written (one per second of sim time, or of wall\n"
      "time in realtime runs, by default; see --record-chunk-seconds on 'run'), then a torn tail,\n"
      "and no summary, so indexed readers (Foxglove, rescuesim replay) refuse it. recover reads\n"
      "it up to its last complete chunk (each chunk's CRC checked), drops the torn tail and\n"
      "writes FILE.mcap with chunk indexes, statistics and summary, atomically. It prints what it\n"
      "saved (messages, channels, time range) and what it dropped. (docs/recording.md)\n\n"
      "Examples:\n"
      "  rescuesim recover runs/default.mcap.part                 writes runs/default.mcap\n"
      "  rescuesim recover killed.mcap.part -o saved.mcap && rescuesim replay saved.mcap --foxglove");
  cmd->add_option("file", c->input, "the recording to recover (FILE.mcap.part; a finished file is copied and indexed again)")->required();
  cmd->add_option("--out,-o", c->output, "where to write it (default: FILE.mcap for FILE.mcap.part, else FILE.recovered.mcap)");
  cmd->add_flag("--force", c->force, "replace the output if it exists");
  cmd->final_callback([c, &action] { action = [c] { return recover(*c); }; });
}

}  // namespace rescuesim::app
