// SDF worlds in the running simulator: the test ramp (tests/data/sdf/models/ramp, an STL wedge
// 2.0 m long, 1.0 m wide, rising 0.3 m) is an exact triangle mesh for the ray sensors and for
// physics; a box dropped on it comes to rest on its slope; the SDF skid-steer robot
// (tests/data/sdf/models/skid_steer, gz-sim's diff-drive system with two joints a side) drives at
// a commanded speed and up the ramp. Every expected number follows from the ramp's geometry.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "import/scenario/scenario.h"
#include "import/sdf/sdf_import.h"
#include "sensors/lidar.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

const std::string kData = std::string(RESCUESIM_SOURCE_DIR) + "/tests/data/sdf";

/// The ramp course: ramp low edge on x = 2, top (z = 0.3) at x = 4, y in [-0.5, 0.5].
constexpr double kRampStart = 2.0, kRampLength = 2.0, kRampHeight = 0.3, kRampHalfWidth = 0.5;
const double kSlope = kRampHeight / kRampLength;  // 0.15: tan of the slope angle

/// Height of the ramp's surface at x (m), on the course.
double ramp_surface(double x) { return kSlope * (x - kRampStart); }

SdfOptions options() {
  SdfOptions o;
  o.resolver = ResourceResolver({kData + "/models"}, false);
  return o;
}

/// A world of SDF text (named as if it were in tests/data/sdf), compiled with its robots.
World world_of(const std::string& sdf_text) {
  const SdfWorld w = parse_sdf_world(sdf_text, kData + "/inline.sdf", options());
  return compile_world(w.spec, w.robots);
}

std::string with_ramp(const std::string& more) {
  return R"(<?xml version="1.0"?><sdf version="1.9"><world name="t">
    <include><uri>model://sun</uri></include>
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://ramp</uri><name>ramp</name><pose>2 0 0 0 0 0</pose></include>)" +
         more + "</world></sdf>";
}

TEST(SdfWorld, RaysHitTheMeshRampWhereItsGeometrySays) {
  const World world = world_of(with_ramp(""));
  // the ramp is one static object, kept as its triangles (not a convex hull)
  int meshes = 0;
  for (const StaticObject& s : world.statics) meshes += s.geometry.type == Geometry::Type::mesh;
  EXPECT_EQ(meshes, 1);
  const RayScene scene(world);
  const auto cast = [&](const Vec3& origin, const Vec3& direction) {
    const Ray ray{origin, direction.normalized(), 100.f};
    RayHit hit;
    scene.cast({&ray, 1}, {&hit, 1});
    return hit;
  };
  // level, 0.15 m up, along the ramp's axis: the slope is 0.15 m high at x = 3.0
  const RayHit level = cast({0, 0, 0.15}, Vec3::UnitX());
  ASSERT_TRUE(level.hit());
  EXPECT_NEAR(level.distance, 3.0, 0.01);
  // the slope's normal leans back toward -x by the slope angle
  EXPECT_NEAR(level.normal.x(), -std::sin(std::atan(kSlope)), 0.01);
  // straight down onto the slope at x = 3.5, from 1 m up
  const RayHit down = cast({3.5, 0.2, 1.0}, -Vec3::UnitZ());
  ASSERT_TRUE(down.hit());
  EXPECT_NEAR(down.distance, 1.0 - ramp_surface(3.5), 0.01);
  // across the ramp at x = 3.0 and 0.1 m up: its side face at y = -0.5
  const RayHit side = cast({3.0, -2.0, 0.1}, Vec3::UnitY());
  ASSERT_TRUE(side.hit());
  EXPECT_NEAR(side.distance, 2.0 - kRampHalfWidth, 0.01);
  // 0.31 m up, level, the ray passes over the top edge and meets nothing
  EXPECT_FALSE(cast({0, 0, kRampHeight + 0.01}, Vec3::UnitX()).hit());
}

TEST(SdfWorld, ABoxDroppedOnTheMeshRampComesToRestOnItsSlope) {
  // a 0.2 m cube of 2 kg (I = m (0.2^2 + 0.2^2) / 12), released 0.5 m above the slope at x = 3
  const double side = 0.2, mass = 2.0, I = mass * (side * side + side * side) / 12;
  const std::string crate = R"(<model name="crate"><pose>3 0.2 0.65 0 0 0</pose><link name="link">
      <inertial><mass>2</mass><inertia><ixx>)" + std::to_string(I) + "</ixx><iyy>" + std::to_string(I) + "</iyy><izz>" +
                            std::to_string(I) + R"(</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
      <visual name="v"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></visual></link></model>)";
  Simulation sim(world_of(with_ramp(crate)));
  ASSERT_EQ(sim.world().dynamics.size(), 1u);
  EXPECT_NEAR(sim.world().dynamics[0].mass, mass, 1e-12);
  sim.step_until(SimTime::from_seconds(3.0));
  const Pose3 X = sim.state().dynamics[0].X_WB;
  // still on the ramp (friction 0.8 > tan 8.5 deg = 0.15: it does not slide off)
  EXPECT_GT(X.p.x(), kRampStart + 0.2);
  EXPECT_LT(X.p.x(), kRampStart + kRampLength - 0.1);
  EXPECT_NEAR(X.p.y(), 0.2, 0.05);
  // lying flat on the slope: its centre half a side from the slope's plane, along the normal
  const Vec3 normal = Vec3(-kSlope, 0, 1).normalized();
  const Vec3 on_slope(X.p.x(), X.p.y(), ramp_surface(X.p.x()));
  EXPECT_NEAR((X.p - on_slope).dot(normal), side / 2, 0.005);
  // ... with a face on it: one of its axes is the slope's normal (within 1 degree)
  double best = 0;
  for (int a = 0; a < 3; ++a) best = std::max(best, std::abs((X.q * Vec3::Unit(a)).dot(normal)));
  EXPECT_GT(best, std::cos(1.0 * M_PI / 180));
  // and at rest
  EXPECT_LT(sim.state().dynamics[0].v_WB.norm(), 0.01);
}

/// Holds a command for `seconds` (re-sent every step, as a ROS node would at any rate).
void drive(Simulation& sim, double v, double seconds) {
  msg::Twist t;
  t.linear = Vec3(v, 0, 0);
  const SimTime end = sim.time() + SimTime::from_seconds(seconds);
  while (sim.time() < end) {
    sim.command_velocity(RobotIndex(0), t);
    sim.step();
  }
}

/// The scenario of a user: the ramp course from its SDF file, the skid steer from model://.
Scenario course_scenario(double start_x) {
  const std::string yaml = "name: sdf_course\n"
                           "world: {sdf: ramp_course.sdf}\n"
                           "resource_paths: [models]\n"
                           "robots:\n"
                           "  - name: skid\n"
                           "    sdf: model://skid_steer\n"
                           "    controller: none\n"
                           "    start: {x: " + std::to_string(start_x) + ", y: 0, yaw: 0}\n";
  return parse_scenario(yaml, kData + "/course.yaml", {});
}

Simulation simulation_of(const Scenario& s) {
  SimOptions o;
  o.physics.dt = s.physics_dt;
  return Simulation(compile_scenario(s, build_world(s), {}), o);
}

TEST(SdfWorld, TheRobotsLidarReadsTheMeshRampAtTheRangeItsGeometrySays) {
  // the skid steer's gpu_lidar (no <noise>: exact ranges), level, about 0.2 m up: its beams
  // toward +x meet the slope where the slope is as high as the lidar, x = 2 + h / 0.15
  Simulation sim = simulation_of(course_scenario(0.5));
  msg::LaserScan scan;
  int scans = 0;
  sim.bus().subscribe("/scan", [&](const Topic&, const msg::Message& m) {
    scan = std::get<msg::LaserScan>(m);
    ++scans;
  });
  sim.step_until(SimTime::from_seconds(0.55));
  ASSERT_GT(scans, 0);
  ASSERT_EQ(scan.ranges.size(), 360u);
  const SensorSpec& lidar = *sim.world().robots[0].spec.find_sensor("lidar");
  EXPECT_EQ(lidar.lidar.noise.stddev, 0.0);
  const Pose3 X_WS = sensor_pose_in_world(sim.world(), sim.state(), RobotIndex(0), lidar);
  ASSERT_LT(X_WS.p.z(), kRampHeight) << "the lidar must be below the ramp's top to see its slope";
  const double x_hit = kRampStart + X_WS.p.z() / kSlope;
  int checked = 0;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double angle = scan.angle_min + static_cast<double>(i) * scan.angle_increment + X_WS.yaw();
    // beams within 5 degrees of +x, whose hit lies on the slope's width
    if (std::abs(angle) > 5 * M_PI / 180) continue;
    const double range = (x_hit - X_WS.p.x()) / std::cos(angle);
    if (std::abs(X_WS.p.y() + range * std::sin(angle)) > kRampHalfWidth - 0.05) continue;
    EXPECT_NEAR(scan.ranges[i], range, 0.01) << "beam " << i << " at " << angle << " rad";
    ++checked;
  }
  EXPECT_GE(checked, 9);
}

TEST(SdfWorld, SkidSteerFromItsSdfDrivesAtTheCommandedSpeed) {
  const Scenario s = course_scenario(-4.0);  // on the flat, 6 m before the ramp
  // the SDF's <max_step_size> became the step
  EXPECT_DOUBLE_EQ(s.physics_dt, 0.005);
  ASSERT_EQ(s.robots.size(), 1u);
  const DriveSpec& drive_spec = s.robots[0].spec.drive;
  EXPECT_EQ(drive_spec.left_wheels.size(), 2u);
  EXPECT_EQ(drive_spec.right_wheels.size(), 2u);
  Simulation sim = simulation_of(s);
  drive(sim, 0.3, 2.0);  // accelerate
  const Vec3 p0 = sim.state().robots[0].base.X_WB.p;
  drive(sim, 0.3, 4.0);
  const Vec3 p1 = sim.state().robots[0].base.X_WB.p;
  EXPECT_NEAR((p1 - p0).head<2>().norm() / 4.0, 0.3, 0.3 * 0.05);
  EXPECT_NEAR(p1.y(), 0.0, 0.1);
  EXPECT_FALSE(sim.in_trouble());
}

TEST(SdfWorld, SkidSteerDrivesUpTheMeshRamp) {
  const Scenario s = course_scenario(0.5);
  Simulation sim = simulation_of(s);
  sim.step_until(SimTime::from_seconds(0.5));  // settle on its wheels
  const double z_flat = sim.state().robots[0].base.X_WB.p.z();
  // drive until the robot's centre is 1.2 m up the slope (or give up after 20 s)
  msg::Twist t;
  t.linear = Vec3(0.3, 0, 0);
  const SimTime end = sim.time() + SimTime::from_seconds(20);
  while (sim.time() < end && sim.state().robots[0].base.X_WB.p.x() < kRampStart + 1.2) {
    sim.command_velocity(RobotIndex(0), t);
    sim.step();
  }
  const Pose3 X = sim.state().robots[0].base.X_WB;
  ASSERT_GE(X.p.x(), kRampStart + 1.2) << "the robot did not get up the ramp in 20 s";
  EXPECT_NEAR(X.p.y(), 0.0, 0.2);
  // its centre has risen with the slope: the wheels' contact points straddle x, so the rise is
  // the surface height under the centre (within 3 cm for the chassis' height above the slope)
  EXPECT_NEAR(X.p.z() - z_flat, ramp_surface(X.p.x()), 0.03);
  // and it is pitched nose-up by the slope angle (within 1.5 degrees)
  const Vec3 forward = X.q * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(forward.z(), forward.head<2>().norm()), std::atan(kSlope), 1.5 * M_PI / 180);
}

}  // namespace
}  // namespace rescuesim
