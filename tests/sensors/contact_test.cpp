// Contact (bumper) sensor: what touches the robot, as physics recorded it, in the sensor's frame.

#include "sensors/contact.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

TEST(Contacts, NamesTouchingThisRobotInTheSensorFrame) {
  // two robots; the second touches a wall and a rubble block (State keeps the names sorted)
  State state;
  state.robots.resize(2);
  state.robots[0].touching = {"floor_step"};
  state.robots[1].touching = {"rubble_3", "wall_12"};
  SensorSpec bumper;
  bumper.type = SensorSpec::Type::contact;
  bumper.frame_id = "robot2/base_link";
  const msg::Contacts c = sample_contacts(state, RobotIndex(1), bumper, SimTime::from_ms(150));
  EXPECT_EQ(c.header.stamp, SimTime::from_ms(150));
  EXPECT_EQ(c.header.frame_id, "robot2/base_link");
  EXPECT_EQ(c.touching, (std::vector<std::string>{"rubble_3", "wall_12"}));
}

TEST(Contacts, NothingTouchingGivesAnEmptyList) {
  State state;
  state.robots.resize(1);
  SensorSpec bumper;
  bumper.frame_id = "base_link";
  EXPECT_TRUE(sample_contacts(state, RobotIndex(0), bumper, SimTime{}).touching.empty());
}

}  // namespace
}  // namespace rescuesim
