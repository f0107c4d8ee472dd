// Batch trials: the results.jsonl line format and how corrupt lines are told apart, the
// results file (append, resume, lock), shards and seeds, trials that fail (a bad world, a
// crashing process), summaries and merging.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "robots/rescue_robot.h"
#include "batch/batch_results.h"
#include "batch/batch_runner.h"
#include "batch/batch_summary.h"
#include "batch/batch_trial.h"
#include "support/command.h"

namespace rescuesim {
namespace {

// a 3 x 3 maze: a trial is a fraction of a second
const char* kTinyYaml =
    "name: tiny\n"
    "seed: 11\n"
    "duration: 4\n"
    "world:\n"
    "  maze: {cols: 3, rows: 3, cell_size: 1.5, loop_fraction: 0.2, rubble: 1, raised_fraction: 0, victims: 2, start_cell: [0, 0]}\n";

TrialRecord sample_record(int trial) {
  TrialRecord r;
  r.trial = trial;
  r.seed = 100 + static_cast<std::uint64_t>(trial);
  r.batch = "rs1-0123456789abcdef";
  r.scenario = "tiny";
  r.success = true;
  r.success_time = 12.5;
  r.stop_reason = "all victims found";
  r.victims_total = 2;
  r.victims_found = 2;
  r.victims = {{"victim_1", true, 3.25}, {"victim_2", true, 12.5}};
  r.coverage = 0.4123456789012345;
  r.distance = 7.1;
  r.collisions = 3;
  r.sim_time = 12.5;
  r.wall_time = 0.3;
  r.real_time_factor = 41.6;
  r.state_hash = "00ff00ff00ff00ff";
  r.host = "node7";
  return r;
}

TEST(BatchRecord, ALineRoundTripsExactly) {
  TrialRecord r = sample_record(3);
  r.victims[1] = {"victim_2", false, -1};
  r.success = false;
  r.success_time = -1;
  const std::string line = to_json_line(r);
  ASSERT_EQ(line.back(), '\n');
  EXPECT_EQ(line.find('\n'), line.size() - 1) << "one line";
  const TrialRecord back = parse_trial_line(line);
  EXPECT_TRUE(same_outcome(r, back));
  EXPECT_EQ(back.coverage, r.coverage);  // doubles survive bit for bit
  EXPECT_EQ(back.host, "node7");
  EXPECT_EQ(back.victims[1].time, -1);
  const auto j = nlohmann::json::parse(line);
  EXPECT_TRUE(j["success_time_s"].is_null());
  EXPECT_TRUE(j["error"].is_null());
}

TEST(BatchRecord, SameOutcomeIgnoresOnlyMachineFigures) {
  const TrialRecord a = sample_record(1);
  TrialRecord b = a;
  b.wall_time = 99;
  b.real_time_factor = 1;
  b.host = "elsewhere";
  EXPECT_TRUE(same_outcome(a, b));
  b.collisions = 4;
  EXPECT_FALSE(same_outcome(a, b));
  b = a;
  b.state_hash = "1111111111111111";
  EXPECT_FALSE(same_outcome(a, b));
}

TEST(BatchRecord, CorruptLinesSayWhatIsWrong) {
  const auto error_of = [](const std::string& line) {
    try {
      parse_trial_line(line);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(error_of("{\"trial\": 1, \"seed\"").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("not a JSON object"), std::string::npos);
  // a number beyond double's range (found by the batch_record fuzz target)
  EXPECT_NE(error_of("{\"trial\": 7E888}").find("not valid JSON"), std::string::npos);
  std::string line = to_json_line(sample_record(2));
  EXPECT_NE(error_of(std::string(line).replace(line.find("\"collisions\""), 12, "\"collision\"")).find("\"collisions\" is missing"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(line).replace(line.find("\"trial\":2"), 9, "\"trial\":\"2\"")).find("\"trial\" should be an integer"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(line).replace(line.find("\"status\":\"ok\""), 13, "\"status\":\"meh\"")).find("status"),
            std::string::npos);
}

TEST(BatchResults, TornDuplicateAndCorruptLinesAreReported) {
  std::string text = to_json_line(sample_record(0)) + "garbage\n" + to_json_line(sample_record(1)) + to_json_line(sample_record(0));
  const std::string torn = to_json_line(sample_record(2));
  text += torn.substr(0, torn.size() / 2);
  const LoadedResults r = parse_results(text, "results.jsonl");
  ASSERT_EQ(r.records.size(), 2u);
  EXPECT_TRUE(r.records.count(0) && r.records.count(1));
  EXPECT_EQ(r.duplicates, 1);
  ASSERT_EQ(r.rejected.size(), 2u);
  ASSERT_EQ(r.notices.size(), 3u);
  EXPECT_NE(r.notices[0].find("results.jsonl:2: corrupt line"), std::string::npos) << r.notices[0];
  EXPECT_NE(r.notices[1].find("results.jsonl:4: trial 0 again"), std::string::npos) << r.notices[1];
  EXPECT_NE(r.notices[2].find("results.jsonl:5: incomplete last line"), std::string::npos) << r.notices[2];
}

TEST(BatchResults, AppendLoadAndSetCorruptLinesAside) {
  const auto dir = testing::temp_dir("batch-results");
  {
    ResultsFile f(dir);
    f.append(sample_record(0));
    f.append(sample_record(1));
  }
  // a crash while writing leaves half a line behind
  {
    std::ofstream out(dir / "results.jsonl", std::ios::app);
    out << "{\"trial\": 2, \"se";
  }
  ResultsFile f(dir);
  const LoadedResults r = f.load();
  EXPECT_EQ(r.records.size(), 2u);
  EXPECT_EQ(r.rejected.size(), 1u);
  // the torn line went aside and the file is clean again, so appending starts on a new line
  EXPECT_EQ(testing::slurp(dir / "results.rejected.jsonl"), "{\"trial\": 2, \"se\n");
  f.append(sample_record(2));
  const LoadedResults again = parse_results(testing::slurp(dir / "results.jsonl"), "results.jsonl");
  EXPECT_EQ(again.records.size(), 3u);
  EXPECT_TRUE(again.notices.empty());
}

TEST(BatchResults, AFolderIsWrittenByOneBatchAtATime) {
  const auto dir = testing::temp_dir("batch-lock");
  ResultsFile f(dir);
  // in this process
  EXPECT_THROW(ResultsFile{dir}, Error);
  // and from another one
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      ResultsFile other(dir);
    } catch (const Error& e) {
      ::_exit(std::string(e.what()).find("another batch") != std::string::npos ? 7 : 8);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(WEXITSTATUS(status), 7);
}

TEST(BatchResults, ResumingRefusesAnotherBatchOrAnotherSeed) {
  LoadedResults r;
  r.records.emplace(1, sample_record(1));  // seed 101: base seed 100
  EXPECT_NO_THROW(check_same_batch(r, "results.jsonl", "rs1-0123456789abcdef", 100));
  try {
    check_same_batch(r, "results.jsonl", "rs1-ffffffffffffffff", 100);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("recorded by another batch"), std::string::npos) << e.what();
  }
  try {
    check_same_batch(r, "results.jsonl", "rs1-0123456789abcdef", 7);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ran with seed 101"), std::string::npos) << e.what();
  }
}

TEST(BatchPlan, ShardsSplitTheTrialsExactly) {
  EXPECT_EQ(shard_trials(7, parse_shard("1/3")), (std::vector<int>{1, 4}));
  EXPECT_EQ(shard_trials(7, parse_shard("0/3")), (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(shard_trials(3, Shard{}), (std::vector<int>{0, 1, 2}));
  for (const char* bad : {"2/2", "-1/2", "1", "a/b", "1/0", "1/2x", "/2"}) {
    EXPECT_THROW(parse_shard(bad), Error) << bad;
  }
  EXPECT_EQ(trial_seed(100, 5), 105u);
}

TEST(BatchPlan, TheFingerprintFollowsScenarioAndOptions) {
  TrialOptions o;
  const std::string a = batch_fingerprint(kTinyYaml, o);
  EXPECT_EQ(a.rfind("rs1-", 0), 0u);
  EXPECT_EQ(a.size(), 20u);
  EXPECT_EQ(a, batch_fingerprint(kTinyYaml, o));
  TrialOptions longer = o;
  longer.duration = 30;
  TrialOptions cams = o;
  cams.cameras = true;
  TrialOptions full = o;
  full.stop_when_all_found = false;
  for (const auto& other : {longer, cams, full}) EXPECT_NE(a, batch_fingerprint(kTinyYaml, other));
  EXPECT_NE(a, batch_fingerprint(std::string(kTinyYaml) + "# edited\n", o));
}

// A terrain trial's line carries its counts in a "terrain" object, which reads back exactly;
// other lines leave the key out, and the fingerprint follows the terrain options.
TEST(BatchRecord, ATerrainTrialsLineRoundTripsAndIsSummarised) {
  std::map<int, TrialRecord> records;
  for (int i = 0; i < 3; ++i) {
    TrialRecord r;
    r.trial = i;
    r.seed = 1 + static_cast<std::uint64_t>(i);
    r.batch = "rs1-0123456789abcdef";
    r.scenario = "arena";
    r.sim_time = 30;
    r.terrain = TrialTerrain{"stairs", "stairs", "tracked_robot", "laps", 3, i == 0 ? 2 : 3, i == 0 ? 1 : 0, 0, 0, 12.5};
    r.success = r.terrain->repetitions == r.terrain->laps;
    records[i] = r;
  }
  const std::string line = to_json_line(records[0]);
  EXPECT_NE(line.find("\"terrain\":{\"lane\":\"stairs\",\"kind\":\"stairs\",\"robot\":\"tracked_robot\",\"pattern\":\"laps\",\"laps\":3,"
                      "\"repetitions\":2,\"falls\":1"),
            std::string::npos)
      << line;
  const TrialRecord back = parse_trial_line(line);
  ASSERT_TRUE(back.terrain);
  EXPECT_EQ(*back.terrain, *records[0].terrain);
  EXPECT_TRUE(same_outcome(back, records[0]));
  EXPECT_EQ(to_json_line(sample_record(0)).find("terrain"), std::string::npos);
  std::string bad = line;
  bad.replace(bad.find("\"repetitions\":2"), 16, "\"repetitions\":9");
  EXPECT_THROW(parse_trial_line(bad), Error);

  // two of three trials completed every repetition; 8 of 9 repetitions, one fall
  const nlohmann::json j = nlohmann::json::parse(batch_summary_json(records));
  EXPECT_DOUBLE_EQ(j["success_rate"].get<double>(), 2.0 / 3.0);
  EXPECT_EQ(j["terrain"]["repetitions"], 8);
  EXPECT_EQ(j["terrain"]["laps"], 9);
  EXPECT_EQ(j["terrain"]["falls"], 1);
  EXPECT_NEAR(j["terrain"]["repetition_rate"].get<double>(), 8.0 / 9.0, 1e-12);

  TrialOptions plain, terrain;
  terrain.terrain = TerrainTrialOptions{};
  terrain.terrain->lane = "stairs";
  TrialOptions more = terrain;
  more.terrain->laps = 5;
  TrialOptions back_and_forth = terrain;
  back_and_forth.terrain->pattern = TerrainPattern::back_and_forth;
  const std::string a = batch_fingerprint(kTinyYaml, terrain);
  EXPECT_NE(a, batch_fingerprint(kTinyYaml, plain));
  EXPECT_NE(a, batch_fingerprint(kTinyYaml, more));
  EXPECT_NE(a, batch_fingerprint(kTinyYaml, back_and_forth));
}

TEST(BatchTrial, ATrialReseedsTheMazeAndAppliesTheOptions) {
  const ModelMap models = builtin_models();
  const BatchScenario b = parse_batch_scenario(kTinyYaml, "tiny.yaml", models);
  TrialOptions o;
  o.duration = 2;
  o.controller = "wall_follower";
  const Scenario s = trial_scenario(b.scenario, 42, o, models);
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.maze->seed, 42u);
  EXPECT_EQ(s.duration, 2);
  EXPECT_TRUE(s.stop_when_all_found);
  ASSERT_EQ(s.robots.size(), 1u);
  EXPECT_EQ(s.robots[0].controller, "wall_follower");
}

TEST(BatchTrial, SameSeedSameOutcomeAndAnInvalidWorldIsAFailedTrial) {
  const ModelMap models = builtin_models();
  const BatchScenario b = parse_batch_scenario(kTinyYaml, "tiny.yaml", models);
  TrialOptions o;
  o.stop_when_all_found = false;
  const TrialRecord r1 = run_trial(b.scenario, models, 0, 5, o, "rs1-x");
  const TrialRecord r2 = run_trial(b.scenario, models, 0, 5, o, "rs1-x");
  EXPECT_EQ(r1.status, "ok") << r1.error;
  EXPECT_DOUBLE_EQ(r1.sim_time, 4.0);
  EXPECT_EQ(r1.victims_total, 2);
  EXPECT_EQ(r1.state_hash.size(), 16u);
  EXPECT_GT(r1.wall_time, 0);
  EXPECT_TRUE(same_outcome(r1, r2));
  EXPECT_FALSE(same_outcome(r1, run_trial(b.scenario, models, 0, 6, o, "rs1-x")));

  // the robot starts on the corner of the outer walls: validation refuses the world
  const BatchScenario bad =
      parse_batch_scenario(std::string(kTinyYaml) + "robots:\n  - name: robot\n    start: {x: 0, y: 0}\n", "bad.yaml", models);
  const TrialRecord f = run_trial(bad.scenario, models, 3, 14, o, "rs1-x");
  EXPECT_EQ(f.status, "failed");
  EXPECT_EQ(f.trial, 3);
  EXPECT_EQ(f.seed, 14u);
  EXPECT_FALSE(f.success);
  EXPECT_NE(f.error.find("clearance"), std::string::npos) << f.error;
}

TEST(BatchRunner, ACrashingTrialIsRecordedAndTheBatchGoesOn) {
  const ModelMap models = builtin_models();
  const BatchScenario b = parse_batch_scenario(kTinyYaml, "tiny.yaml", models);
  TrialOptions o;
  o.duration = 1;
  const auto dir = testing::temp_dir("batch-crash");
  ResultsFile results(dir);
  ::setenv(kCrashTrialVariable, "1", 1);
  BatchRunOptions ro;
  ro.jobs = 2;
  int reports = 0;
  ro.progress = [&](const BatchProgress& p) { reports += p.last != nullptr; };
  const BatchRunStats stats = run_batch_trials(b.scenario, models, {0, 1, 2}, 11, o, "rs1-crash", results, ro);
  ::unsetenv(kCrashTrialVariable);
  EXPECT_EQ(stats.recorded, 3);
  EXPECT_EQ(stats.failed, 1);
  EXPECT_FALSE(stats.interrupted);
  EXPECT_EQ(reports, 3);
  const LoadedResults r = results.load();
  ASSERT_EQ(r.records.size(), 3u);
  EXPECT_EQ(r.records.at(0).status, "ok");
  EXPECT_EQ(r.records.at(2).status, "ok");
  const TrialRecord& crashed = r.records.at(1);
  EXPECT_EQ(crashed.status, "failed");
  EXPECT_EQ(crashed.seed, 12u);
  EXPECT_NE(crashed.error.find("killed by signal 11"), std::string::npos) << crashed.error;
}

TEST(BatchRunner, ThreadsAndProcessesGiveTheSameRecords) {
  const ModelMap models = builtin_models();
  const BatchScenario b = parse_batch_scenario(kTinyYaml, "tiny.yaml", models);
  TrialOptions o;
  o.duration = 1.5;
  const auto run = [&](Isolation iso, int jobs) {
    const auto dir = testing::temp_dir(std::string("batch-iso-") + (iso == Isolation::thread ? "t" : "p") + std::to_string(jobs));
    ResultsFile results(dir);
    BatchRunOptions ro;
    ro.jobs = jobs;
    ro.isolation = iso;
    run_batch_trials(b.scenario, models, {0, 1, 2, 3}, 11, o, "rs1-iso", results, ro);
    return results.load().records;
  };
  const auto a = run(Isolation::process, 1);
  const auto t = run(Isolation::thread, 2);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(t.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_outcome(a.at(i), t.at(i))) << "trial " << i;
}

TEST(BatchSummary, StatisticsTableAndFigure) {
  const Stat s = stat_of({4, 1, 3, 2});
  EXPECT_EQ(s.n, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.min, 1);
  EXPECT_DOUBLE_EQ(s.max, 4);
  EXPECT_NEAR(s.stddev, 1.2909944, 1e-6);
  EXPECT_EQ(stat_of({}).n, 0);

  std::map<int, TrialRecord> records;
  for (int i = 0; i < 3; ++i) records.emplace(i, sample_record(i));
  records.at(1).success = false;
  records.at(1).success_time = -1;
  records.at(1).victims_found = 1;
  TrialRecord failed = sample_record(3);
  failed.status = "failed";
  failed.error = "boom, with a comma";
  failed.success = false;
  records.emplace(3, failed);
  const auto j = nlohmann::json::parse(batch_summary_json(records, {2, 4, 2.0}));
  EXPECT_EQ(j["trials"], 4);
  EXPECT_EQ(j["trials_failed"], 1);
  EXPECT_EQ(j["successes"], 2);
  EXPECT_DOUBLE_EQ(j["success_rate"].get<double>(), 0.5);
  EXPECT_EQ(j["victims_found"], 5);  // the failed trial does not count
  EXPECT_EQ(j["coverage"]["n"], 3);
  EXPECT_DOUBLE_EQ(j["run"]["trials_per_hour"].get<double>(), 7200.0);
  EXPECT_EQ(j["failures"][0]["error"], "boom, with a comma");
  EXPECT_EQ(j["base_seed"], 100);

  const std::string csv = batch_summary_csv(records);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_NE(csv.find("\"boom, with a comma\""), std::string::npos);
  const Canvas fig = batch_figure(records);
  EXPECT_EQ(fig.width(), 1200);
  EXPECT_GT(fig.height(), 600);
  EXPECT_EQ(batch_figure({}).width(), 1200);  // an empty batch still draws
}

TEST(BatchSummary, MissionScoresAreAggregatedPerSeed) {
  // scores 3, -0.5 and 2 over three trials: median 2, mean 1.5, min -0.5, max 3
  std::map<int, TrialRecord> records;
  const double scores[] = {3, -0.5, 2};
  for (int i = 0; i < 3; ++i) {
    TrialRecord r = sample_record(i);
    r.mission = TrialMission{scores[i], i + 1, i, 0.25 * (i + 1)};
    records.emplace(i, r);
  }
  records.emplace(3, sample_record(3));  // a trial without a mission is left out of them
  const auto j = nlohmann::json::parse(batch_summary_json(records, {}));
  EXPECT_EQ(j["mission"]["trials"], 3);
  EXPECT_DOUBLE_EQ(j["mission"]["score"]["median"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["mission"]["score"]["mean"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["mission"]["score"]["min"].get<double>(), -0.5);
  EXPECT_DOUBLE_EQ(j["mission"]["false_reports"]["max"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["mission"]["contact_fraction"]["mean"].get<double>(), 0.5);
  ASSERT_EQ(j["mission"]["per_seed"].size(), 3u);
  EXPECT_EQ(j["mission"]["per_seed"][1]["seed"], 101);
  EXPECT_EQ(j["mission"]["per_seed"][1]["score"], -0.5);
  EXPECT_FALSE(nlohmann::json::parse(batch_summary_json({{0, sample_record(0)}}, {})).contains("mission"));

  // the line keeps the mission; an older line without the key reads as no mission
  const TrialRecord back = parse_trial_line(to_json_line(records.at(1)));
  ASSERT_TRUE(back.mission.has_value());
  EXPECT_EQ(*back.mission, *records.at(1).mission);
  EXPECT_TRUE(same_outcome(back, records.at(1)));
  auto old = nlohmann::json::parse(to_json_line(sample_record(0)));
  old.erase("mission");
  EXPECT_FALSE(parse_trial_line(old.dump()).mission.has_value());
  const std::string csv = batch_summary_csv(records);
  EXPECT_NE(csv.find(",mission_score,victims_reported,false_reports\n"), std::string::npos);
  EXPECT_NE(csv.find(",-0.5,2,1\n"), std::string::npos) << csv;
}

TEST(BatchMerge, ShardsMergeAndOtherBatchesAreRefused) {
  const auto a = testing::temp_dir("merge-a"), b = testing::temp_dir("merge-b"), out = testing::temp_dir("merge-out");
  {
    ResultsFile fa(a), fb(b);
    fa.append(sample_record(0));
    fa.append(sample_record(2));
    fb.append(sample_record(1));
    fb.append(sample_record(2));  // overlap: the same trial, the same outcome
  }
  std::map<int, TrialRecord> merged;
  const auto notices = merge_results({a, b}, out, &merged);
  EXPECT_TRUE(notices.empty());
  ASSERT_EQ(merged.size(), 3u);
  const LoadedResults back = parse_results(testing::slurp(out / "results.jsonl"), "results.jsonl");
  EXPECT_EQ(back.records.size(), 3u);
  EXPECT_EQ(back.records.begin()->first, 0);

  const auto c = testing::temp_dir("merge-c");
  {
    ResultsFile fc(c);
    TrialRecord other = sample_record(5);
    other.batch = "rs1-ffffffffffffffff";
    fc.append(other);
  }
  try {
    merge_results({a, c}, testing::temp_dir("merge-out2"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("only shards of one batch"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
