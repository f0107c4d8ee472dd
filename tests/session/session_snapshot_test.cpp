// Session::snapshot and restore with everything attached: the default scenario with its
// explorer and rendered cameras. Frames in flight at the snapshot are rendered again after a
// restore and the frames in flight at the restore are dropped, so the replay — images, clouds,
// victims found — is bitwise the first run.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "msgs/base64.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "session/session.h"
#include "team/team_datagrams.h"

namespace rescuesim {
namespace {

/// Every message published while stepping to `until`: (topic name, digest), in order.
std::vector<std::pair<std::string, std::uint64_t>> record(Session& session, SimTime until) {
  std::vector<std::pair<std::string, std::uint64_t>> out;
  bool live = false;  // not the latched messages subscribe replays
  const auto handle = session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    if (live) out.emplace_back(t.name, msg::digest(m));
  });
  live = true;
  session.step_until(until);
  session.sim().bus().unsubscribe(handle);
  return out;
}

TEST(SessionSnapshot, RestoreReplaysTheDefaultScenarioWithCamerasBitwise) {
  const ModelMap models = builtin_models();
  std::unique_ptr<Session> session;
  try {
    session = std::make_unique<Session>(default_scenario(models), models);
  } catch (const Error& e) {
    GTEST_SKIP() << "no headless OpenGL here: " << e.what();
  }
  ASSERT_FALSE(session->render_device().empty());
  // 1.05 s: cameras sampled at 1.0 s are still in flight (delivered one period later)
  session->step_until(SimTime::from_ms(1050));
  const SessionSnapshot snap = session->snapshot();
  const auto first = record(*session, SimTime::from_seconds(2.5));
  const std::uint64_t hash = state_hash(session->sim().state());
  std::map<std::string, int> count;
  for (const auto& [topic, d] : first) ++count[topic];
  // 10 Hz cameras delivered one period late: the frames of 1.0 s (in flight at the snapshot) to 2.4 s
  EXPECT_EQ(count["/camera/color/image_raw"], 15);
  EXPECT_EQ(count["/thermal/image_raw"], 15);
  // the explorer drove meanwhile
  EXPECT_GT(session->sim().state().robots[0].distance, snap.state.robots[0].distance + 0.1);

  // restore mid-frame: what is in flight now is dropped, the snapshot's frames come again
  session->step_until(SimTime::from_ms(2550));
  session->restore(snap);
  const auto again = record(*session, SimTime::from_seconds(2.5));
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(again[i], first[i]) << "message " << i << " on " << first[i].first;
  EXPECT_EQ(state_hash(session->sim().state()), hash);
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

/// A team of two explorers in a small maze with a WSS radio: what the mission adds to a run.
Scenario mission_scenario() {
  return parse_scenario(
      "name: team\nseed: 4\nduration: 60\n"
      "world:\n  maze: {cols: 4, rows: 4, victims: 3, start_cells: [[0, 0], [3, 3]]}\n"
      "robots:\n  - {name: a}\n  - {name: b}\n"
      "mission:\n  radio: {model: wss}\n",
      "team.yaml", builtin_models());
}

TEST(SessionMission, RestoreReplaysReportsScoreAndRadioBitwise) {
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  Session session(mission_scenario(), models, so);
  ASSERT_NE(session.mission(), nullptr);
  EXPECT_NE(session.sim().bus().find("/a/rescue/comms/status"), kNoTopic);
  EXPECT_NE(session.sim().bus().find("/rescue/score"), kNoTopic);
  session.step_until(SimTime::from_seconds(5));
  const SessionSnapshot snap = session.snapshot();
  // (topic, text) of every mission message while stepping (not the latched ones subscribe replays)
  const auto recorder = [&](std::vector<std::pair<std::string, std::string>>& out, bool& live) {
    return session.sim().bus().subscribe("", [&out, &live](const Topic& t, const msg::Message& m) {
      if (live && t.name.find("rescue") != std::string::npos) out.emplace_back(t.name, std::get<msg::String>(m).data);
    });
  };
  std::vector<std::pair<std::string, std::string>> first;
  {
    bool live = false;
    const auto h = recorder(first, live);
    live = true;
    session.step_until(SimTime::from_seconds(40));
    session.sim().bus().unsubscribe(h);
  }
  const MissionResult at_end = session.result().mission.value();
  session.restore(snap);
  std::vector<std::pair<std::string, std::string>> again;
  {
    bool live = false;
    const auto h = recorder(again, live);
    live = true;
    session.step_until(SimTime::from_seconds(40));
    session.sim().bus().unsubscribe(h);
  }
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(again[i], first[i]) << i;
  const MissionResult replay = session.result().mission.value();
  EXPECT_EQ(replay.score, at_end.score);
  EXPECT_EQ(replay.timeline.size(), at_end.timeline.size());
  EXPECT_EQ(replay.link_updates, at_end.link_updates);
  EXPECT_EQ(replay.contact_fraction, at_end.contact_fraction);
  // 35 s at 1 Hz for two robots, plus the latched score and the reports' answers
  int status = 0;
  for (const auto& [topic, d] : first) status += topic.find("comms/status") != std::string::npos;
  EXPECT_EQ(status, 2 * 35);
}

TEST(SessionMission, TeammatesTellEachOtherWhereTheyAreOverTheRadio) {
  // the team rule: every 2 s each built-in robot sends each teammate where it is and which
  // frontier it drives to; with an ideal radio, in 10 s b hears a at 0, 2, 4, 6 and 8 s (the
  // one sent at 10 s goes at the next link update, after the run)
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  Scenario s = mission_scenario();
  s.duration = 10;
  s.mission->radio.model = radio_model("ideal");
  Session session(s, models, so);
  const Vec2 start_a = session.sim().world().robots[0].X_W_start.p.head<2>();
  std::vector<nlohmann::json> heard;
  session.sim().bus().subscribe("/b/rescue/comms/inbox", [&](const Topic&, const msg::Message& m) {
    heard.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  session.run();
  // and every 6 s where its camera has looked: at 0 and 6 s
  std::vector<nlohmann::json> seen;
  std::erase_if(heard, [&](const nlohmann::json& d) {
    const auto body = nlohmann::json::parse(d["text"].get<std::string>());
    if (!body.contains("seen")) return false;
    seen.push_back(d);
    return true;
  });
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_NEAR(seen[0]["sent"].get<double>(), 0.0, 0.11);
  EXPECT_NEAR(seen[1]["sent"].get<double>(), 6.0, 0.11);
  {
    // the first: the 0.5 m square of the world holding a's start is seen (the robot's own
    // footprint, a disc of 0.41 m round it, covers every map cell of it)
    const auto sq = nlohmann::json::parse(seen[0]["text"].get<std::string>())["seen"];
    EXPECT_EQ(sq["cell"].get<double>(), 0.5);
    const int i = static_cast<int>(std::floor(start_a.x() / 0.5)) - sq["origin"][0].get<int>();
    const int j = static_cast<int>(std::floor(start_a.y() / 0.5)) - sq["origin"][1].get<int>();
    const int w = sq["size"][0].get<int>();
    ASSERT_TRUE(i >= 0 && j >= 0 && i < w && j < sq["size"][1].get<int>()) << sq;
    const std::string b64 = sq["bits"].get<std::string>();
    const auto bits = msg::decode_base64(b64);
    ASSERT_TRUE(bits.has_value());
    const int k = j * w + i;
    EXPECT_TRUE(((*bits)[static_cast<std::size_t>(k / 8)] >> (k % 8)) & 1) << sq;
  }
  // and as often what its laser has mapped, in 0.1 m squares of the world: at 0 and 6 s
  std::vector<nlohmann::json> mapped;
  std::erase_if(heard, [&](const nlohmann::json& d) {
    const auto body = nlohmann::json::parse(d["text"].get<std::string>());
    if (!body.contains("map")) return false;
    mapped.push_back(d);
    return true;
  });
  ASSERT_EQ(mapped.size(), 2u);
  EXPECT_NEAR(mapped[0]["sent"].get<double>(), 0.0, 0.11);
  EXPECT_NEAR(mapped[1]["sent"].get<double>(), 6.0, 0.11);
  {
    const std::string text = mapped[1]["text"].get<std::string>();
    const auto map = read_map_datagram(std::vector<std::uint8_t>(text.begin(), text.end()));
    ASSERT_TRUE(map.has_value());
    EXPECT_EQ(map->cell, 0.1);
    // the ground 0.6 m ahead of a's start is in the box, and free (the laser, 0.26 m ahead of
    // the robot's centre, swept it from the start)
    const Pose2 X_WA = session.sim().world().robots[0].X_W_start.to_pose2();
    const Vec2 ahead = X_WA.transform(Vec2(0.6, 0));
    const int i = static_cast<int>(std::floor(ahead.x() / 0.1)) - map->origin.first;
    const int j = static_cast<int>(std::floor(ahead.y() / 0.1)) - map->origin.second;
    ASSERT_TRUE(i >= 0 && j >= 0 && i < map->width && j < map->height);
    EXPECT_EQ(map->states[static_cast<std::size_t>(j * map->width + i)], MapSquares::free);
    // and it saw walls
    EXPECT_GT(std::count(map->states.begin(), map->states.end(), MapSquares::occupied), 100);
  }
  // b took it: its explorer knows cells from a's map
  const auto explorers = session.result().explorers;
  const auto b = std::find_if(explorers.begin(), explorers.end(), [](const auto& e) { return e.first == "b"; });
  ASSERT_NE(b, explorers.end());
  EXPECT_GT(b->second.team_mapped_cells, 1000);
  ASSERT_EQ(heard.size(), 5u);
  for (std::size_t i = 0; i < heard.size(); ++i) {
    EXPECT_EQ(heard[i]["from"], "a");
    EXPECT_NEAR(heard[i]["sent"].get<double>(), 2.0 * static_cast<double>(i), 0.11) << heard[i];
    const auto team = nlohmann::json::parse(heard[i]["text"].get<std::string>())["team"];
    ASSERT_TRUE(team["at"].is_array()) << heard[i];
    if (i == 0) {  // at the start: where a starts, in the world frame
      EXPECT_NEAR(team["at"][0].get<double>(), start_a.x(), 0.02);
      EXPECT_NEAR(team["at"][1].get<double>(), start_a.y(), 0.02);
    }
  }
  EXPECT_EQ(session.result().mission->datagrams_dropped, 0u);
}

TEST(SessionMission, TheBaseScoresTheMapsTheRobotsSendIt) {
  // each built-in robot sends its map to the base every 6 s, the first as soon as it has one
  // (after its first scan), which arrives at 0.2 s; the base submits the team's map when a new
  // one has come and 10 s have passed since its last: maps keep coming, so at 0.2, 10.2, 20.2 s
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  Scenario s = mission_scenario();
  s.duration = 25;
  s.mission->radio.model = radio_model("ideal");
  Session session(s, models, so);
  std::vector<nlohmann::json> scores;
  session.sim().bus().subscribe("/rescue/map_score", [&](const Topic&, const msg::Message& m) {
    scores.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  const RunResult r = session.run();
  ASSERT_EQ(scores.size(), 3u);
  EXPECT_NEAR(scores[0]["stamp"].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(scores[1]["stamp"].get<double>(), 10.2, 1e-9);
  EXPECT_NEAR(scores[2]["stamp"].get<double>(), 20.2, 1e-9);
  ASSERT_TRUE(r.mission->map.has_value());
  EXPECT_EQ(r.mission->map->maps, 3);
  // the team's map lies on the walls (most of its occupied squares are within a truth cell of
  // one), holds nearly every wall the lasers could have seen, and grows as the robots drive
  EXPECT_GT(r.mission->map->precision, 0.8);
  EXPECT_GT(r.mission->map->recall, 0.9);
  EXPECT_GT(scores[2]["map_occupied"].get<long>(), scores[0]["map_occupied"].get<long>());
}

TEST(SessionMission, TheFinderReportsWhatItSawWhereItBelievesItIs) {
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  Scenario s = mission_scenario();
  s.mission->radio.model = radio_model("ideal");
  Session session(s, models, so);
  const RunResult r = session.run();
  ASSERT_TRUE(r.mission.has_value());
  // every victim the robots saw early enough was reported (one report per 0.5 s per robot)
  int seen = 0, seen_early = 0;
  for (const auto& v : r.victims) {
    seen += v.found;
    seen_early += v.found && v.time < r.sim_time - 1.0;
  }
  EXPECT_GE(static_cast<int>(r.mission->counts.charged), seen_early);
  EXPECT_LE(static_cast<int>(r.mission->counts[ReportOutcome::accepted]), seen);
  EXPECT_GT(seen, 0) << "the explorers should see a victim of this small maze in 60 s";
  // each robot finds victims for itself (VictimState::seen_at) and reports those it saw, but
  // not one a teammate told it (by its team datagram, every 2 s) it had found already. So a
  // victim both saw is reported twice (a duplicate) only when the second saw it before the
  // first one's next team datagram could arrive: within 2 s plus a link update (0.1 s).
  int both = 0, close = 0;
  for (const VictimState& v : session.sim().state().victims) {
    if (!v.seen_by_robot(0) || !v.seen_by_robot(1)) continue;
    ++both;
    close += std::abs((v.seen_at[0] - v.seen_at[1]).seconds()) <= 2.1 + 1e-9;
  }
  EXPECT_LE(static_cast<int>(r.mission->counts[ReportOutcome::duplicate]), close);
  EXPECT_GT(both - close, 0) << "this maze should have a victim both robots saw far apart in time";
  EXPECT_LE(static_cast<int>(r.mission->counts.charged), seen + close);
  // reports are odometry estimates: accepted ones lie within the 1.5 m radius of their victim
  for (const auto& v : r.mission->victim_states) {
    if (v.found) {
      EXPECT_LE(v.error_m, 1.5);
    }
  }
  EXPECT_EQ(r.mission->score, r.mission->victims_found - 0.5 * static_cast<double>(r.mission->counts[ReportOutcome::false_report]));
}

}  // namespace
}  // namespace rescuesim
namespace rescuesim {
namespace {

TEST(SessionSnapshot, ASnapshotRightAfterAScanKeepsTheCommandTheExplorerQueued) {
  // at 5.0 s a scan has just been published and the explorer's answer waits in the
  // simulation's command queue for the next step: the snapshot must carry it, and a restore
  // must not apply whatever is queued at the moment of the restore instead
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  for (int robots = 1; robots <= 2; ++robots) {
    Scenario s = parse_scenario(
        "name: t\nseed: 4\nworld:\n  maze: {cols: 4, rows: 4, victims: 3, start_cells: [[0, 0], [3, 3]]}\n"
        "robots:\n  - {name: a}\n  - {name: b}\n",
        "t.yaml", models);
    s.robots.resize(static_cast<std::size_t>(robots));
    Session session(s, models, so);
    session.step_until(SimTime::from_seconds(5));
    const SessionSnapshot snap = session.snapshot();
    session.step_until(SimTime::from_seconds(6));
    const std::uint64_t hash = state_hash(session.sim().state());
    session.restore(snap);
    session.step_until(SimTime::from_seconds(6));
    EXPECT_EQ(state_hash(session.sim().state()), hash) << robots << " robot(s)";
  }
}

}  // namespace
}  // namespace rescuesim
