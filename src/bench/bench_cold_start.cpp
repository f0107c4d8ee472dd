#include "bench/bench_cold_start.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/data_dir.h"
#include "bench/bench_figures.h"

namespace rescuesim::bench {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

/// The standard output of a shell command, or nothing when it could not be started.
std::string output_of(const std::string& command) {
  std::string out;
  FILE* p = ::popen(command.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  ::pclose(p);
  return out;
}

/// A path in single quotes for the shell.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

json bench_cold_start(int runs) {
  // the CLI users start, beside this program (rescuesim-bench is installed and built next to it)
  const fs::path cli = app::sibling_program("rescuesim");
  std::error_code ec;
  if (cli.empty() || !fs::exists(cli, ec)) return {{"error", "no rescuesim beside rescuesim-bench (" + cli.string() + ")"}};
  const std::string exe = quoted(cli.string());
  const fs::path out = fs::temp_directory_path() / ("rescuesim-cold-" + std::to_string(::getpid()));
  json report;
  const double bare = median_seconds(runs, [&] { output_of(exe + " --version"); });
  for (const bool cameras : {true, false}) {
    std::vector<double> first;
    std::string error;
    for (int k = 0; k < runs; ++k) {
      const std::string text =
          output_of(exe + " run --duration 0.5 -q --out " + quoted(out.string()) + (cameras ? "" : " --no-cameras") + " 2>&1");
      const std::size_t at = text.find("cold start: first scan");
      double s = -1;
      if (at == std::string::npos || std::sscanf(text.c_str() + text.find(')', at) + 1, " %lf", &s) != 1) {
        error = "no cold start line in the run's output";
        continue;
      }
      first.push_back(s);
    }
    json fig = ratio_figure(median(first), "s from exec to the first /scan", bare,
                            "rescuesim --version from exec to exit (loading the binary and its libraries), this bench run");
    fig["target_s"] = 1.0;
    fig["meets_target"] = !first.empty() && median(first) < 1.0;
    fig["runs"] = first;
    if (!error.empty()) fig["error"] = error;
    report[cameras ? "default_scenario" : "default_scenario_no_cameras"] = fig;
  }
  fs::remove_all(out, ec);
  return report;
}

}  // namespace rescuesim::bench
