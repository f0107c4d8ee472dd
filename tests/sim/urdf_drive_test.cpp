// The TurtleBot3 burger from its own URDF (worlds/robots, ROBOTIS, Apache-2.0) on flat ground:
// it drives at a commanded 0.2 m/s within 5 %, turns at a commanded 1.0 rad/s within 10 %, and
// its laser on base_scan reads a wall at a known distance within 1 cm.

#include <gtest/gtest.h>

#include <cmath>

#include "import/urdf/urdf_import.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

RobotSpec burger() {
  UrdfOptions o;
  o.resolver = ResourceResolver({std::string(RESCUESIM_SOURCE_DIR) + "/worlds/robots"}, false);
  RobotSpec spec =
      load_urdf(std::string(RESCUESIM_SOURCE_DIR) + "/worlds/robots/turtlebot3_description/urdf/turtlebot3_burger.urdf", o).spec;
  configure_diff_drive(spec, {"wheel_left_joint"}, {"wheel_right_joint"}, 0, 0, {});
  spec.drive.max_linear = 0.22;
  spec.drive.max_angular = 2.84;
  add_standard_sensors(spec);
  SensorSpec laser;
  laser.name = "lidar";
  laser.type = SensorSpec::Type::lidar;
  laser.link = "base_scan";
  laser.frame_id = "base_scan";
  laser.topic = "scan";
  laser.rate = 5;
  laser.lidar.min_angle = -M_PI;
  laser.lidar.max_angle = M_PI * 358.0 / 360.0;
  laser.lidar.samples = 360;
  laser.lidar.min_range = 0.12;
  laser.lidar.max_range = 3.5;
  laser.lidar.noise = {};
  spec.sensors.push_back(laser);
  return spec;
}

/// A floor with, optionally, a wall whose near face is at x = `wall_face` (m); the burger at the origin facing +x.
World flat_world(double wall_face = 0) {
  WorldSpec w;
  w.floor_min = {-5, -5};
  w.floor_max = {5, 5};
  w.materials = default_materials();
  if (wall_face > 0) w.walls.push_back(WallSpec{{wall_face + 0.05, -2}, {wall_face + 0.05, 2}, 0.1, 1.0, "wall", {}});
  RobotPlacement p;
  p.name = "tb3";
  p.model = "burger";
  w.robots.push_back(p);
  return compile_world(w, {{"burger", burger()}});
}

/// Holds a command for `seconds` (re-sent every step, as a ROS node would at any rate).
void drive(Simulation& sim, double v, double w, double seconds) {
  msg::Twist t;
  t.linear = Vec3(v, 0, 0);
  t.angular = Vec3(0, 0, w);
  const SimTime end = sim.time() + SimTime::from_seconds(seconds);
  while (sim.time() < end) {
    sim.command_velocity(RobotIndex(0), t);
    sim.step();
  }
}

TEST(UrdfDrive, BurgerDrivesAtTheCommandedSpeed) {
  // the drive wheels grip like rubber (the robot_wheel material), the body does not
  const RobotSpec spec = burger();
  for (const LinkShape& sh : spec.links[static_cast<std::size_t>(spec.link_index("wheel_left_link"))].shapes) {
    if (sh.collides) {
      EXPECT_EQ(sh.material, "robot_wheel");
    }
  }
  Simulation sim(flat_world());
  drive(sim, 0.2, 0, 2.0);  // accelerate
  const Vec3 p0 = sim.state().robots[0].base.X_WB.p;
  drive(sim, 0.2, 0, 3.0);
  const Vec3 p1 = sim.state().robots[0].base.X_WB.p;
  const double speed = (p1 - p0).head<2>().norm() / 3.0;
  EXPECT_NEAR(speed, 0.2, 0.2 * 0.05);
  // straight ahead: along +x, not off to a side
  EXPECT_NEAR(p1.y(), 0.0, 0.05);
  EXPECT_GT(p1.x(), 0.8);
  // on its wheels: base_footprint stays on the ground, level
  EXPECT_NEAR(p1.z(), 0.0, 0.005);
  // wheel odometry (wheel radius and separation derived from the URDF) agrees with the truth
  const Pose2 odom = sim.state().robots[0].odom;
  EXPECT_NEAR(odom.x, p1.x(), 0.02 * p1.x());
  EXPECT_NEAR(odom.y, p1.y(), 0.02);
  EXPECT_FALSE(sim.in_trouble());
}

TEST(UrdfDrive, BurgerTurnsAtTheCommandedRate) {
  Simulation sim(flat_world());
  drive(sim, 0, 1.0, 2.0);
  const double yaw0 = sim.state().robots[0].base.X_WB.yaw();
  double turned = 0, last = yaw0;
  const SimTime end = sim.time() + SimTime::from_seconds(3.0);
  msg::Twist t;
  t.angular = Vec3(0, 0, 1.0);
  while (sim.time() < end) {
    sim.command_velocity(RobotIndex(0), t);
    sim.step();
    const double yaw = sim.state().robots[0].base.X_WB.yaw();
    turned += std::remainder(yaw - last, 2 * M_PI);
    last = yaw;
  }
  EXPECT_NEAR(turned / 3.0, 1.0, 0.1);
  // turning in place: the centre stays put
  EXPECT_LT(sim.state().robots[0].base.X_WB.p.head<2>().norm(), 0.05);
}

TEST(UrdfDrive, LaserOnBaseScanReadsAWallAtAKnownDistance) {
  // base_scan is 0.032 m behind base_link's origin, which sits over base_footprint
  const double wall_face = 1.5;
  Simulation sim(flat_world(wall_face));
  msg::LaserScan scan;
  int scans = 0;
  sim.bus().subscribe("/scan", [&](const Topic&, const msg::Message& m) {
    scan = std::get<msg::LaserScan>(m);
    ++scans;
  });
  sim.step_until(SimTime::from_seconds(0.5));
  ASSERT_GT(scans, 0);
  EXPECT_EQ(scan.header.frame_id, "base_scan");
  ASSERT_EQ(scan.ranges.size(), 360u);
  // the beam straight ahead is beam 180 (angle_min = -pi, 1 degree apart)
  const double angle = scan.angle_min + 180 * scan.angle_increment;
  ASSERT_NEAR(angle, 0.0, 1e-6);
  const double x_scan = sim.state().robots[0].base.X_WB.p.x() - 0.032;
  EXPECT_NEAR(scan.ranges[180], wall_face - x_scan, 0.01);
  // 45 degrees to the left the same wall (it reaches 2 m to each side) is 1/cos(45) further
  EXPECT_NEAR(scan.ranges[225], (wall_face - x_scan) / std::cos(M_PI / 4), 0.01);
}

}  // namespace
}  // namespace rescuesim
