// A mission's topics over ROS 2, seen from a second DDS participant in this process: a
// datagram written on rt/robot/rescue/comms/send (std_msgs/String, JSON) arrives on robot2's
// rt/robot2/rescue/comms/inbox, and a victim report (geometry_msgs/PoseStamped) on
// rt/robot/rescue/report is answered on rt/robot/rescue/report_result.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <cstdlib>
#include <thread>

#include <nlohmann/json.hpp>

#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_bridge.h"
#include "mission/mission.h"
#include "msgs/serialize.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using ros2::DdsParticipant;

TEST(Ros2MissionTopics, ADatagramCrossesTheRadioAndAReportIsAnswered) {
  testing::pin_cyclone_to_loopback();
  const int domain = testing::leased_dds_domain();
  // two robots 4 m apart in a 20 m room, a victim at (5, 0)
  Simulation sim(compile_world(testing::two_robots_and_a_victim(), builtin_models()));
  Mission mission(MissionSpec{}, sim);  // ideal radio, RoboCup rules
  Ros2Options o;
  o.domain_id = domain;
  auto bridge = make_ros2_bridge(o);
  bridge->start(sim);

  DdsParticipant ros(domain, ros2::participant_user_data());
  const int send = ros.create_writer("rt/robot/rescue/comms/send", "std_msgs::msg::dds_::String_", {});
  const int report = ros.create_writer("rt/robot/rescue/report", "geometry_msgs::msg::dds_::PoseStamped_", {});
  const int inbox = ros.create_reader("rt/robot2/rescue/comms/inbox", "std_msgs::msg::dds_::String_", {});
  const int answers = ros.create_reader("rt/robot/rescue/report_result", "std_msgs::msg::dds_::String_", {});
  std::vector<std::uint8_t> send_bytes, report_bytes;
  msg::to_cdr(msg::String{R"({"to": "robot2", "text": "victim near 5,0"})"}, send_bytes);
  msg::PoseStamped p;
  p.header.frame_id = "map";
  p.pose.p = sim.world().victims[0].centre + Vec3(0.3, 0.4, 0);  // 0.5 m off
  msg::to_cdr(p, report_bytes);

  std::vector<nlohmann::json> got_inbox, got_answers;
  int sends = 0, reports = 0;
  const auto take = [&](int reader, std::vector<nlohmann::json>& into) {
    ros.take(reader, [&](std::span<const std::uint8_t> bytes) {
      into.push_back(nlohmann::json::parse(std::get<msg::String>(msg::from_cdr(*msg::find_type("std_msgs/String"), bytes)).data));
    });
  };
  // Matching takes a moment on each side, and the bridge sends only topics someone reads (it
  // looks every 100 ms): so write 1 s after this side has matched, and again every 2 s of wall
  // time until the answer comes. Datagrams repeat harmlessly; repeated reports of the same
  // victim are duplicates, not charged (and 2 s apart, never over the rate limit).
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(40);
  std::optional<std::chrono::steady_clock::time_point> next_write;
  while (std::chrono::steady_clock::now() < give_up && (got_inbox.empty() || got_answers.empty())) {
    std::string error;
    const bool matched = ros.matched_readers(send) > 0 && ros.matched_writers(inbox) > 0 && ros.matched_readers(report) > 0 &&
                         ros.matched_writers(answers) > 0;
    if (matched && !next_write) next_write = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    if (next_write && std::chrono::steady_clock::now() >= *next_write) {
      *next_write += std::chrono::seconds(2);
      if (got_inbox.empty() && ros.matched_readers(send) > 0 && ros.matched_writers(inbox) > 0) {
        ASSERT_TRUE(ros.write(send, send_bytes, &error)) << error;
        ++sends;
      }
      if (got_answers.empty() && ros.matched_readers(report) > 0 && ros.matched_writers(answers) > 0) {
        ASSERT_TRUE(ros.write(report, report_bytes, &error)) << error;
        ++reports;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const SimTime until = sim.time() + SimTime::from_ms(50);
    while (sim.time() < until) {
      sim.step();
      mission.after_step();
    }
    take(inbox, got_inbox);
    take(answers, got_answers);
  }
  bridge->stop();

  ASSERT_GT(sends, 0) << "the bridge's reader on rt/robot/rescue/comms/send never matched";
  ASSERT_GT(reports, 0) << "the bridge's reader on rt/robot/rescue/report never matched";
  ASSERT_FALSE(got_inbox.empty());
  EXPECT_EQ(got_inbox[0]["from"], "robot");
  EXPECT_EQ(got_inbox[0]["text"], "victim near 5,0");
  EXPECT_EQ(got_inbox[0]["hops"], 1);
  ASSERT_FALSE(got_answers.empty());
  // the first report read over ROS 2 was accepted (+1); every answer this peer saw is about v1, 0.5 m away
  EXPECT_EQ(mission.referee().score(), 1.0);
  EXPECT_EQ(mission.referee().victims_found(), 1);
  EXPECT_EQ(mission.referee().counts()[ReportOutcome::accepted], 1u);
  for (const auto& a : got_answers) {
    EXPECT_TRUE(a["outcome"] == "accepted" || a["outcome"] == "duplicate") << a;
    EXPECT_EQ(a["victim"], "v1") << a;
    EXPECT_NEAR(a["distance"].get<double>(), 0.5, 1e-6) << a;
  }
  EXPECT_EQ(bridge->stats().rejected, 0u);
}

}  // namespace
}  // namespace rescuesim
