// Lidar against a wall at a known distance: d / cos(angle) per beam, REP-117 limits, noise
// statistics, the robot's own body invisible, and repeatable noise.

#include "sensors/lidar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sensors/ray_sensor_world.h"

namespace rescuesim {
namespace {

using namespace rescuesim::testing;

/// A lidar 5 cm above base_link (inside the robot's own box), 201 beams over ±1 rad.
SensorSpec test_lidar() {
  SensorSpec s;
  s.name = "scan";
  s.type = SensorSpec::Type::lidar;
  s.link = "base_link";
  s.X_LS = Pose3{Vec3(0, 0, 0.05), Quat::Identity()};
  s.rate = 20;
  s.frame_id = "laser";
  s.lidar.min_angle = -1.0;
  s.lidar.max_angle = 1.0;
  s.lidar.samples = 201;
  s.lidar.min_range = 0.05;
  s.lidar.max_range = 20.0;
  s.lidar.noise = {0.0, 0.0, 0.0};
  return s;
}

/// One robot at the origin facing +x, a wall whose face is x = d.
struct Fixture {
  World world;
  State state;
  RayScene scene;
  Fixture(double d, const RobotSpec& model) : world(make_world(d, model)), state(initial_state(world)), scene(world) {}
  static World make_world(double d, const RobotSpec& model) {
    WorldSpec spec = empty_spec();
    spec.walls.push_back(wall_facing_west(d));
    spec.robots.push_back({"r", "box_bot", {0, 0, 0}, {}});
    return compile_with(spec, model);
  }
  msg::LaserScan scan(const SensorSpec& s, Rng& rng, SimTime stamp = SimTime::from_ms(1500)) const {
    return sample_lidar(world, state, scene, RobotIndex(0), s, stamp, rng);
  }
};

double beam_angle(const SensorSpec& s, int i) {
  return s.lidar.min_angle + i * (s.lidar.max_angle - s.lidar.min_angle) / (s.lidar.samples - 1);
}

TEST(LidarWall, CentreBeamReadsTheDistanceAndOthersTheCosineLaw) {
  const SensorSpec s = test_lidar();
  const Fixture f(2.0, box_robot({s}));
  Rng rng(1, "scan");
  const msg::LaserScan scan = f.scan(s, rng);
  ASSERT_EQ(scan.ranges.size(), 201u);
  EXPECT_NEAR(scan.ranges[100], 2.0, 1e-4);
  for (int i = 0; i < 201; ++i) {
    EXPECT_NEAR(scan.ranges[static_cast<std::size_t>(i)], 2.0 / std::cos(beam_angle(s, i)), 1e-4) << "beam " << i;
  }
}

TEST(LidarWall, HeaderAndLimitsFollowTheSpec) {
  const SensorSpec s = test_lidar();
  const Fixture f(2.0, box_robot({s}));
  Rng rng(1, "scan");
  const msg::LaserScan scan = f.scan(s, rng, SimTime::from_ms(1500));
  EXPECT_EQ(scan.header.stamp, SimTime::from_ms(1500));
  EXPECT_EQ(scan.header.frame_id, "laser");
  EXPECT_FLOAT_EQ(scan.angle_min, -1.0f);
  EXPECT_FLOAT_EQ(scan.angle_max, 1.0f);
  EXPECT_FLOAT_EQ(scan.angle_increment, 0.01f);
  EXPECT_FLOAT_EQ(scan.range_min, 0.05f);
  EXPECT_FLOAT_EQ(scan.range_max, 20.0f);
  EXPECT_FLOAT_EQ(scan.scan_time, 0.05f);
  EXPECT_EQ(scan.time_increment, 0.0f);
  EXPECT_TRUE(scan.intensities.empty());
}

TEST(LidarWall, MountFollowsLinkPoseAndSensorPose) {
  // the robot faces +y; the lidar is turned −90° on it, so it faces +x again
  SensorSpec s = test_lidar();
  s.X_LS = Pose3::from_rpy(Vec3(0, 0, 0.05), 0, 0, -M_PI / 2);
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_facing_west(2.0));
  spec.robots.push_back({"r", "box_bot", {0.5, 0, M_PI / 2}, {}});
  const World world = compile_with(spec, box_robot({s}));
  const RayScene scene(world);
  Rng rng(1, "scan");
  const msg::LaserScan scan = sample_lidar(world, initial_state(world), scene, RobotIndex(0), s, SimTime{}, rng);
  EXPECT_NEAR(scan.ranges[100], 1.5, 1e-4);
  EXPECT_NEAR(scan.ranges[0], 1.5 / std::cos(1.0), 1e-4);
}

TEST(LidarRep117, BelowMinimumIsMinusInfinity) {
  // min_range 2.5 with the wall at 2: beams with 2 / cos(a) < 2.5, i.e. |a| < acos(0.8) = 0.6435 rad, are too near
  SensorSpec s = test_lidar();
  s.lidar.min_range = 2.5;
  const Fixture f(2.0, box_robot({s}));
  Rng rng(1, "scan");
  const msg::LaserScan scan = f.scan(s, rng);
  for (int i = 0; i < 201; ++i) {
    const double a = beam_angle(s, i);
    const float r = scan.ranges[static_cast<std::size_t>(i)];
    if (std::abs(a) < 0.64) {
      EXPECT_TRUE(std::isinf(r) && r < 0) << "beam " << i;
    } else if (std::abs(a) > 0.65) {
      EXPECT_NEAR(r, 2.0 / std::cos(a), 1e-4) << "beam " << i;
    }
  }
}

TEST(LidarRep117, NothingInRangeIsPlusInfinity) {
  SensorSpec s = test_lidar();
  s.lidar.max_range = 1.9;
  const Fixture f(2.0, box_robot({s}));
  Rng rng(1, "scan");
  for (float r : f.scan(s, rng).ranges) EXPECT_TRUE(std::isinf(r) && r > 0);
  // and turned away from the wall there is nothing at all (the floor is below every beam)
  SensorSpec back = test_lidar();
  back.X_LS = Pose3::from_rpy(Vec3(0, 0, 0.05), 0, 0, M_PI);
  const Fixture g(2.0, box_robot({back}));
  for (float r : g.scan(back, rng).ranges) EXPECT_TRUE(std::isinf(r) && r > 0);
}

TEST(LidarNoise, MeanErrorIsZeroAndSpreadIsTheStddev) {
  SensorSpec s = test_lidar();
  s.lidar.samples = 1000;
  s.lidar.noise = {0.02, 0.0, 0.0};
  const Fixture f(2.0, box_robot({s}));
  Rng rng(2024, "scan");
  // 20 scans × 1000 beams = 20 000 errors against d / cos(a)
  double sum = 0, sum_sq = 0;
  int n = 0;
  for (int k = 0; k < 20; ++k) {
    const msg::LaserScan scan = f.scan(s, rng);
    for (int i = 0; i < s.lidar.samples; ++i) {
      const double e = scan.ranges[static_cast<std::size_t>(i)] - 2.0 / std::cos(beam_angle(s, i));
      sum += e;
      sum_sq += e * e;
      ++n;
    }
  }
  const double mean = sum / n;
  const double stddev = std::sqrt((sum_sq - n * mean * mean) / (n - 1));
  // standard error of the mean: 0.02 / sqrt(20000) = 1.4e-4; of the stddev: 0.5 %
  EXPECT_NEAR(mean, 0.0, 6e-4);
  EXPECT_NEAR(stddev, 0.02, 0.03 * 0.02);
}

TEST(LidarNoise, NoisyValuesStayInsideTheRange) {
  // the wall sits exactly at max_range: half the noisy readings would exceed it without the clamp
  SensorSpec s = test_lidar();
  s.lidar.min_angle = s.lidar.max_angle = 0;
  s.lidar.samples = 1;
  s.lidar.max_range = 2.0001;
  s.lidar.noise = {0.05, 0.0, 0.0};
  const Fixture f(2.0, box_robot({s}));
  Rng rng(3, "scan");
  int at_max = 0;
  for (int k = 0; k < 200; ++k) {
    const float r = f.scan(s, rng).ranges[0];
    EXPECT_LE(r, static_cast<float>(s.lidar.max_range));
    EXPECT_GE(r, static_cast<float>(s.lidar.min_range));
    at_max += r == static_cast<float>(s.lidar.max_range);
  }
  EXPECT_GT(at_max, 50);
}

TEST(LidarSelf, RobotNeverSeesItsOwnLinks) {
  // a second shape 0.3 m in front of the lidar, on the robot's own link: the scan looks through it
  SensorSpec s = test_lidar();
  RobotSpec model = box_robot({s});
  model.links[0].shapes.push_back({Geometry::box({0.05, 0.6, 0.3}), Pose3{Vec3(0.3, 0, 0.05), Quat::Identity()}, "robot_body", true});
  const Fixture f(2.0, model);
  Rng rng(1, "scan");
  const msg::LaserScan scan = f.scan(s, rng);
  EXPECT_NEAR(scan.ranges[100], 2.0, 1e-4);
  // while the same ray not ignoring the robot stops at the inside of its own box (x = 0.2), and
  // from just outside the box at the shape's near face (x = 0.275)
  const Ray rays[2] = {{Vec3(0, 0, kBaseHeight + 0.05), Vec3::UnitX(), 10.0f}, {Vec3(0.25, 0, kBaseHeight + 0.05), Vec3::UnitX(), 10.0f}};
  RayHit hits[2];
  f.scene.cast(rays, hits, RobotIndex());
  EXPECT_NEAR(hits[0].distance, 0.2, 1e-4);
  EXPECT_EQ(hits[0].source, RayHit::Source::robot_link);
  EXPECT_NEAR(hits[1].distance, 0.025, 1e-4);
  EXPECT_EQ(hits[1].robot, RobotIndex(0));
}

TEST(LidarSelf, OtherRobotsAreSeen) {
  // robot b stands 1 m ahead: its box's near face is 0.8 m from robot a's lidar
  SensorSpec s = test_lidar();
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_facing_west(2.0));
  spec.robots.push_back({"a", "box_bot", {0, 0, 0}, {}});
  spec.robots.push_back({"b", "box_bot", {1, 0, 0}, {}});
  const World world = compile_with(spec, box_robot({s}));
  const RayScene scene(world);
  Rng rng(1, "scan");
  const msg::LaserScan scan = sample_lidar(world, initial_state(world), scene, RobotIndex(0), s, SimTime{}, rng);
  EXPECT_NEAR(scan.ranges[100], 0.8, 1e-4);
  EXPECT_NEAR(scan.ranges[0], 2.0 / std::cos(1.0), 1e-4);
}

TEST(LidarRepeatability, SameSeedSameScan) {
  SensorSpec s = test_lidar();
  s.lidar.noise = {0.02, 0.0, 0.0};
  const Fixture f(2.0, box_robot({s}));
  Rng a(42, "scan"), b(42, "scan"), c(43, "scan");
  const auto sa = f.scan(s, a).ranges, sb = f.scan(s, b).ranges, sc = f.scan(s, c).ranges;
  ASSERT_EQ(sa.size(), sb.size());
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(float)), 0);
  EXPECT_NE(sa, sc);
}

TEST(LidarCloud, LayersLandOnTheWallInTheSensorFrame) {
  // 3 layers at elevations −0.05, 0, 0.05 rad and 9 beams every 0.5 rad over ±2 rad, max range 3:
  // per layer only a = 0, ±0.5 reach the wall (2 / (cos e cos a) ≤ 2.29 m); a = ±1 needs 3.7 m,
  // the rest point sideways or back, where the floor is farther than 3 m (0.2 / sin 0.05 = 4 m)
  SensorSpec s = test_lidar();
  s.lidar.samples = 9;
  s.lidar.min_angle = -2.0;
  s.lidar.max_angle = 2.0;
  s.lidar.layers = 3;
  s.lidar.vertical_fov = 0.1;
  s.lidar.max_range = 3.0;
  const Fixture f(2.0, box_robot({s}));
  Rng rng(1, "scan");
  const msg::PointCloud2 cloud = sample_lidar_cloud(f.world, f.state, f.scene, RobotIndex(0), s, SimTime::from_ms(7), rng);
  EXPECT_EQ(cloud.header.frame_id, "laser");
  EXPECT_EQ(cloud.header.stamp, SimTime::from_ms(7));
  EXPECT_EQ(cloud.height, 1u);
  ASSERT_EQ(cloud.width, 9u);
  EXPECT_TRUE(cloud.is_dense);
  EXPECT_EQ(cloud.point_step, 12u);
  EXPECT_EQ(cloud.row_step, 12u * 9u);
  ASSERT_EQ(cloud.fields.size(), 3u);
  EXPECT_EQ(cloud.fields[2].name, "z");
  EXPECT_EQ(cloud.fields[2].offset, 8u);
  ASSERT_EQ(cloud.data.size(), 12u * 9u);
  // ring by ring, the wall plane x = 2 in the sensor frame; heights 2 tan(e) / cos(a)
  const double elevations[3] = {-0.05, 0.0, 0.05};
  const double angles[3] = {-0.5, 0.0, 0.5};
  for (int k = 0; k < 9; ++k) {
    float xyz[3];
    std::memcpy(xyz, cloud.data.data() + 12 * k, sizeof xyz);
    const double e = elevations[k / 3], a = angles[k % 3];
    EXPECT_NEAR(xyz[0], 2.0, 1e-4) << "point " << k;
    EXPECT_NEAR(xyz[1], 2.0 * std::tan(a), 1e-4) << "point " << k;
    EXPECT_NEAR(xyz[2], 2.0 * std::tan(e) / std::cos(a), 1e-4) << "point " << k;
  }
}

}  // namespace
}  // namespace rescuesim
