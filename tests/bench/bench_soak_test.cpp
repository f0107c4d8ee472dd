// `rescuesim bench --soak`, short: the default scenario with cameras and every bridge built,
// sampled every sim minute. 0.02 sim hours (72 s) gives samples at 0, at the first step past
// 60 s and at the end; Ctrl-C after the first minute ends it early and the files are still
// written. Counts and times only, no speed.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "support/command.h"

namespace rescuesim {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Row {
  double sim_s = 0, resident_mb = 0, heap_mb = 0;
  std::uint64_t messages = 0, nans = 0;
};

/// soak.csv's rows, after checking its header.
std::vector<Row> read_csv(const fs::path& csv) {
  std::istringstream in(testing::slurp(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "sim_s,wall_s,rtf,resident_mb,peak_mb,heap_mb,arena_mb,arena_free_mb,messages,nans,recorded_bytes");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    if (f.size() != 11) {
      ADD_FAILURE() << "row '" << line << "' has " << f.size() << " fields";
      continue;
    }
    // the arenas' free part is part of them
    EXPECT_LE(std::stod(f[7]), std::stod(f[6])) << line;
    rows.push_back({std::stod(f[0]), std::stod(f[3]), std::stod(f[5]), std::stoull(f[8]), std::stoull(f[9])});
  }
  return rows;
}

TEST(BenchSoak, SamplesEverySimMinuteAndChecksEveryMessage) {
  const fs::path dir = testing::temp_dir("bench-soak");
  const testing::CommandResult r = testing::rescuesim("bench --soak --soak-hours 0.02 --out '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(testing::slurp(dir / "soak.json"));
  EXPECT_NEAR(j["sim_hours"].get<double>(), 0.02, 1e-6);
  EXPECT_EQ(j["stop_reason"], "duration");
  EXPECT_EQ(j["nan"]["count"], 0);
  EXPECT_TRUE(fs::exists(dir / "soak.png"));

  const std::vector<Row> rows = read_csv(dir / "soak.csv");
  // 0 s, the first progress report at or past 60 s (reports come every 0.1 s of wall time), 72 s
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].sim_s, 0);
  EXPECT_EQ(rows[0].messages, 0u);
  EXPECT_GE(rows[1].sim_s, 60.0);
  EXPECT_LT(rows[1].sim_s, 72.0);
  EXPECT_NEAR(rows.back().sim_s, 72.0, 1e-9);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GE(rows[i].sim_s, rows[i - 1].sim_s);
    EXPECT_GE(rows[i].messages, rows[i - 1].messages);
    EXPECT_GT(rows[i].heap_mb, 0);
    EXPECT_GT(rows[i].resident_mb, 0);
    EXPECT_EQ(rows[i].nans, 0u);
  }
  // /clock alone is 200 messages a sim second
  EXPECT_GT(rows.back().messages, 200u * 72u);
  EXPECT_EQ(rows.back().messages, j["messages"].get<std::uint64_t>());
}

TEST(BenchSoak, CtrlCStopsEarlyAndStillWritesItsFiles) {
  const fs::path dir = testing::temp_dir("bench-soak-int");
  // an hour asked for; interrupted once the first sim minute has been sampled
  const std::string d = dir.string();
  testing::write_text(dir / "interrupt.sh", "'" RESCUESIM_EXE "' bench --soak --soak-hours 1 --out '" + d + "' > '" + d + "/out' 2> '" + d +
                                                "/err' &\n"
                                                "pid=$!\n"
                                                "until grep -q '1.0 min sim' '" + d + "/err'; do\n"
                                                "  kill -0 $pid 2>/dev/null || exit 99\n"
                                                "  sleep 0.2\n"
                                                "done\n"
                                                "kill -INT $pid\n"
                                                "wait $pid\n");
  const testing::CommandResult r = testing::run_command("timeout 600 bash '" + d + "/interrupt.sh'");
  ASSERT_EQ(r.exit_code, 0) << testing::slurp(dir / "err");
  const json j = json::parse(testing::slurp(dir / "soak.json"));
  EXPECT_EQ(j["stop_reason"], "interrupted");
  const double hours = j["sim_hours"].get<double>();
  EXPECT_GT(hours, 1.0 / 60);
  EXPECT_LT(hours, 1.0);
  const std::vector<Row> rows = read_csv(dir / "soak.csv");
  ASSERT_GE(rows.size(), 3u);
  EXPECT_NEAR(rows.back().sim_s, hours * 3600, 1e-6);
}

}  // namespace
}  // namespace rescuesim
