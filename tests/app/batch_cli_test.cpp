// rescuesim batch as a user meets it: results do not depend on --jobs, a batch killed with
// SIGKILL resumes without losing or repeating a trial, shards merge into the whole batch, and
// bad input (corrupt result lines, invalid worlds, another batch's folder) is reported.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "batch/batch_results.h"
#include "support/command.h"

extern char** environ;

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::slurp;
using testing::temp_dir;
using testing::write_text;

namespace fs = std::filesystem;

// a 3 x 3 maze with two victims and 5 s trials: twenty trials take a few seconds
const char* kTinyYaml =
    "name: tiny\n"
    "seed: 11\n"
    "duration: 5\n"
    "world:\n"
    "  maze: {cols: 3, rows: 3, cell_size: 1.5, loop_fraction: 0.2, rubble: 1, raised_fraction: 0, victims: 2, start_cell: [0, 0]}\n";

class BatchCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    scenario_ = dir_ / "tiny.yaml";
    write_text(scenario_, kTinyYaml);
  }
  /// `rescuesim batch` on the tiny scenario into dir_/out with extra arguments.
  testing::CommandResult batch(const std::string& out, const std::string& args) {
    return rescuesim("batch '" + scenario_.string() + "' --out '" + (dir_ / out).string() + "' " + args);
  }
  std::map<int, TrialRecord> records(const std::string& out) {
    const LoadedResults r = parse_results(slurp(dir_ / out / "results.jsonl"), out);
    EXPECT_TRUE(r.notices.empty()) << r.notices.front();
    return r.records;
  }
  int lines(const std::string& out) {
    const std::string text = slurp(dir_ / out / "results.jsonl");
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  }
  /// Every trial in both, with the same outcome (all but wall time, real-time factor, host).
  void expect_same(const std::map<int, TrialRecord>& a, const std::map<int, TrialRecord>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [trial, r] : a) {
      ASSERT_TRUE(b.count(trial)) << "trial " << trial;
      EXPECT_TRUE(same_outcome(r, b.at(trial))) << "trial " << trial << "\n" << to_json_line(r) << to_json_line(b.at(trial));
    }
  }
  fs::path dir_, scenario_;
};

// Terrain trials in a batch: one results line per trial with the trial's counts, and the success
// rate over trials. The lane is a 3 cm curb 0.6 m deep, which the tracked robot crosses every time:
// 2 x 0.8 m of approach + 0.6 m at 0.5 m/s, about 4.4 s a lap.
TEST_F(BatchCli, TerrainTrialsAreRecordedOneLineEach) {
  const fs::path arena = dir_ / "curb.svg";
  write_text(arena,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"300cm\" height=\"600cm\" viewBox=\"0 0 300 600\">\n"
             "  <rect x=\"0\" y=\"0\" width=\"300\" height=\"600\" fill=\"none\" stroke=\"#000\" stroke-width=\"5\"/>\n"
             "  <rect id=\"low\" x=\"90\" y=\"270\" width=\"120\" height=\"60\" data-kind=\"curb\" data-height=\"3cm\" data-yaw=\"90\"/>\n"
             "  <circle cx=\"150\" cy=\"500\" r=\"30\" fill=\"#2ca02c\" data-yaw=\"90\"/>\n"
             "</svg>\n");
  const auto r =
      rescuesim("batch --trial-terrain '" + arena.string() +
                "' --lane curb --robot tracked_robot --laps 1 --speed 0.5 --trials 2 --jobs 2 --out '" + (dir_ / "curb").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 trials recorded: 2 completed every repetition (100%), 0 failed; repetitions 2/2"), std::string::npos) << r.out;
  EXPECT_EQ(lines("curb"), 2);
  const auto rec = records("curb");
  ASSERT_EQ(rec.size(), 2u);
  for (const auto& [trial, t] : rec) {
    EXPECT_EQ(t.status, "ok") << t.error;
    EXPECT_EQ(t.seed, 1u + static_cast<std::uint64_t>(trial));
    ASSERT_TRUE(t.terrain);
    EXPECT_EQ(t.terrain->lane, "low");
    EXPECT_EQ(t.terrain->kind, "curb");
    EXPECT_EQ(t.terrain->pattern, "laps");
    EXPECT_EQ(t.terrain->laps, 1);
    EXPECT_EQ(t.terrain->repetitions, 1);
    EXPECT_TRUE(t.success);
    EXPECT_GT(t.sim_time, 2.2 / 0.5);
    EXPECT_LT(t.sim_time, 2.2 / 0.5 + 1.5);
    EXPECT_EQ(t.state_hash.size(), 16u);  // the final State, as a scenario trial's
  }
  EXPECT_NE(rec.at(0).state_hash, rec.at(1).state_hash);  // two seeds, two starts
  const nlohmann::json summary = nlohmann::json::parse(slurp(dir_ / "curb" / "summary.json"));
  EXPECT_DOUBLE_EQ(summary["success_rate"].get<double>(), 1.0);
  EXPECT_EQ(summary["terrain"]["repetitions"], 2);

  // bad input is exit 2: a lane the arena lacks, a scenario and an arena at once
  const auto lane =
      rescuesim("batch --trial-terrain '" + arena.string() + "' --lane stairs --trials 1 --out '" + (dir_ / "x").string() + "'");
  EXPECT_EQ(lane.exit_code, 2);
  EXPECT_NE(lane.err.find("no lane 'stairs'"), std::string::npos) << lane.err;
  const auto both = rescuesim("batch '" + scenario_.string() + "' --trial-terrain '" + arena.string() + "' --lane curb --trials 1");
  EXPECT_EQ(both.exit_code, 2);
  // figure-eights on a curb: the batch refuses before its first trial, and so does trial-terrain
  const auto eight = rescuesim("batch --trial-terrain '" + arena.string() + "' --lane curb --pattern figure-eight --trials 1 --out '" +
                               (dir_ / "eight").string() + "'");
  EXPECT_EQ(eight.exit_code, 2);
  EXPECT_NE(eight.err.find("lane 'low' is curb: use --pattern laps or back-and-forth"), std::string::npos) << eight.err;
  EXPECT_FALSE(fs::exists(dir_ / "eight" / "results.jsonl"));
  const auto single =
      rescuesim("trial-terrain '" + arena.string() + "' --lane curb --pattern figure-eight --out '" + (dir_ / "eight1").string() + "'");
  EXPECT_EQ(single.exit_code, 2);
  EXPECT_NE(single.err.find("figure-eights are driven on stepfields and crossing ramps"), std::string::npos) << single.err;
}

TEST_F(BatchCli, JobsDoNotChangeTheResults) {
  const auto one = batch("one", "--trials 20 --jobs 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = batch("two", "--trials 20 --jobs 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const auto a = records("one"), b = records("two");
  ASSERT_EQ(a.size(), 20u);
  expect_same(a, b);
  // trial i ran with seed S + i, and trials differ
  EXPECT_EQ(a.at(0).seed, 11u);
  EXPECT_EQ(a.at(19).seed, 30u);
  EXPECT_NE(a.at(0).state_hash, a.at(2).state_hash);
  for (const char* f : {"summary.json", "summary.csv", "summary.png"}) EXPECT_TRUE(fs::exists(dir_ / "two" / f)) << f;
  const auto summary = nlohmann::json::parse(slurp(dir_ / "two" / "summary.json"));
  EXPECT_EQ(summary["trials"], 20);
  EXPECT_EQ(summary["run"]["jobs"], 2);
  const std::string csv = slurp(dir_ / "two" / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 21);
  EXPECT_NE(two.out.find("20 trials recorded"), std::string::npos) << two.out;
}

TEST_F(BatchCli, AKilledBatchResumesWithoutLosingOrRepeatingTrials) {
  const auto ref = batch("ref", "--trials 20 --jobs 1 -q");
  ASSERT_EQ(ref.exit_code, 0) << ref.err;

  // start the batch in the background and SIGKILL it once a few trials are recorded
  const std::string out = (dir_ / "killed").string();
  std::vector<std::string> args = {RESCUESIM_EXE, "batch", scenario_.string(), "--trials", "20", "--jobs", "2", "-q", "--out", out};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, RESCUESIM_EXE, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const auto t0 = std::chrono::steady_clock::now();
  while (lines("killed") < 4 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the batch finished before it could be killed";
  const int before = lines("killed");
  EXPECT_GE(before, 4);
  EXPECT_LT(before, 20);

  const auto again = batch("killed", "--trials 20 --jobs 2 -q");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find(std::to_string(before) + " already recorded"), std::string::npos) << again.out;
  EXPECT_EQ(lines("killed"), 20);  // no trial twice
  expect_same(records("ref"), records("killed"));
}

TEST_F(BatchCli, ShardsMergeIntoTheWholeBatch) {
  const auto whole = batch("whole", "--trials 20 --jobs 2 -q");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto s0 = batch("s0", "--trials 20 --jobs 1 -q --shard 0/2");
  const auto s1 = batch("s1", "--trials 20 --jobs 1 -q --shard 1/2");
  ASSERT_EQ(s0.exit_code, 0) << s0.err;
  ASSERT_EQ(s1.exit_code, 0) << s1.err;
  EXPECT_EQ(lines("s0"), 10);
  EXPECT_EQ(records("s1").begin()->first, 1);
  const auto m =
      rescuesim("batch merge '" + (dir_ / "s0").string() + "' '" + (dir_ / "s1").string() + "' --out '" + (dir_ / "merged").string() + "'");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  expect_same(records("whole"), records("merged"));
  EXPECT_TRUE(fs::exists(dir_ / "merged" / "summary.png"));
  // the merged file is in trial order
  const auto first =
      nlohmann::json::parse(slurp(dir_ / "merged" / "results.jsonl").substr(0, slurp(dir_ / "merged" / "results.jsonl").find('\n')));
  EXPECT_EQ(first["trial"], 0);
}

TEST_F(BatchCli, CorruptLinesAreReportedAndRunAgain) {
  ASSERT_EQ(batch("b", "--trials 6 --jobs 2 -q").exit_code, 0);
  const auto before = records("b");
  // spoil the second line and cut the last one in half, as a crash mid-write would
  const std::string text = slurp(dir_ / "b" / "results.jsonl");
  std::vector<std::string> ls;
  for (std::size_t p = 0, e; (e = text.find('\n', p)) != std::string::npos; p = e + 1) ls.push_back(text.substr(p, e - p));
  ASSERT_EQ(ls.size(), 6u);
  ls[1] = "{\"trial\": oops";
  std::string spoiled;
  for (std::size_t i = 0; i + 1 < ls.size(); ++i) spoiled += ls[i] + "\n";
  spoiled += ls.back().substr(0, ls.back().size() / 2);
  write_text(dir_ / "b" / "results.jsonl", spoiled);

  const auto again = batch("b", "--trials 6 --jobs 2 -q");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("results.jsonl:2: corrupt line: not valid JSON"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("results.jsonl:6: incomplete last line"), std::string::npos) << again.err;
  EXPECT_NE(again.out.find("2 to run"), std::string::npos) << again.out;
  EXPECT_EQ(lines("b"), 6);
  expect_same(before, records("b"));
  const std::string rejected = slurp(dir_ / "b" / "results.rejected.jsonl");
  EXPECT_EQ(std::count(rejected.begin(), rejected.end(), '\n'), 2);
}

TEST_F(BatchCli, AnInvalidWorldFailsItsTrialsNotTheBatch) {
  // the robot starts on the corner of the outer walls: validation refuses every trial's world
  write_text(scenario_, std::string(kTinyYaml) + "robots:\n  - name: robot\n    start: {x: 0, y: 0}\n");
  const auto r = batch("bad", "--trials 3 --jobs 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto recs = records("bad");
  ASSERT_EQ(recs.size(), 3u);
  for (const auto& [t, rec] : recs) {
    EXPECT_EQ(rec.status, "failed");
    EXPECT_NE(rec.error.find("clearance"), std::string::npos) << rec.error;
  }
  EXPECT_NE(r.err.find("FAILED"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "bad" / "summary.json"))["trials_failed"], 3);
}

TEST_F(BatchCli, ACrashedTrialIsRecordedAndCanBeRetried) {
  const auto r = rescuesim("batch '" + scenario_.string() + "' --out '" + (dir_ / "c").string() + "' --trials 4 --jobs 2 --duration 2",
                           {});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto crash = testing::run_command(std::string("RESCUESIM_BATCH_CRASH_TRIAL=5 '") + RESCUESIM_EXE + "' batch '" +
                                          scenario_.string() + "' --out '" + (dir_ / "c").string() + "' --trials 7 --jobs 2 --duration 2");
  EXPECT_EQ(crash.exit_code, 1) << crash.err;
  auto recs = records("c");
  ASSERT_EQ(recs.size(), 7u);
  EXPECT_EQ(recs.at(5).status, "failed");
  EXPECT_NE(recs.at(5).error.find("signal 11"), std::string::npos) << recs.at(5).error;
  EXPECT_EQ(recs.at(6).status, "ok");
  // a plain rerun keeps the failure; --retry-failed runs it again
  EXPECT_EQ(batch("c", "--trials 7 --duration 2 -q").exit_code, 1);
  const auto retry = batch("c", "--trials 7 --duration 2 -q --retry-failed");
  EXPECT_EQ(retry.exit_code, 0) << retry.err;
  EXPECT_EQ(records("c").at(5).status, "ok");
  EXPECT_EQ(lines("c"), 7);
}

TEST_F(BatchCli, AnotherBatchsFolderIsRefused) {
  ASSERT_EQ(batch("x", "--trials 2 -q").exit_code, 0);
  const auto longer = batch("x", "--trials 2 -q --duration 3");
  EXPECT_EQ(longer.exit_code, 2);
  EXPECT_NE(longer.err.find("recorded by another batch"), std::string::npos) << longer.err;
  const auto reseeded = batch("x", "--trials 2 -q --seed 99");
  EXPECT_EQ(reseeded.exit_code, 2);
  EXPECT_NE(reseeded.err.find("ran with seed 11"), std::string::npos) << reseeded.err;
  // nor can shards of different batches be merged
  ASSERT_EQ(batch("y", "--trials 2 -q --duration 3").exit_code, 0);
  const auto m =
      rescuesim("batch merge '" + (dir_ / "x").string() + "' '" + (dir_ / "y").string() + "' --out '" + (dir_ / "xy").string() + "'");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find("only shards of one batch"), std::string::npos) << m.err;
}

TEST_F(BatchCli, BadUsageIsExplained) {
  const auto no_trials = batch("u", "");
  EXPECT_EQ(no_trials.exit_code, 2);
  EXPECT_NE(no_trials.err.find("--trials"), std::string::npos) << no_trials.err;
  const auto shard = batch("u", "--trials 4 --shard 2/2");
  EXPECT_EQ(shard.exit_code, 2);
  EXPECT_NE(shard.err.find("0 <= K < M"), std::string::npos) << shard.err;
  const auto missing = rescuesim("batch '" + (dir_ / "nope.yaml").string() + "' --trials 2");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.yaml"), std::string::npos) << missing.err;
  EXPECT_EQ(rescuesim("batch merge --out '" + (dir_ / "m").string() + "'").exit_code, 2);
  const auto help = rescuesim("batch --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--shard"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim
