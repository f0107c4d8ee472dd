// Lidar and sonar through smoke and dust (sensors/media_echo.h): the fraction of returns from a
// wall behind a slab against two-way Beer-Lambert, exp(-2 sigma L), with its binomial tolerance;
// rays that miss the slab read the wall exactly; early echoes lie inside the slab; a drifting
// slab moves its shadow; repeatable draws; and no change at all where there is no medium.

#include "sensors/media_echo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sensors/lidar.h"
#include "sensors/ray_sensor_world.h"
#include "sensors/sonar.h"

namespace rescuesim {
namespace {

using namespace rescuesim::testing;

constexpr double kWall = 4.0;  // m: the wall's face, x = 4

/// A lidar 5 cm above base_link (0.202 m above the floor) with `samples` beams over ±half rad.
SensorSpec test_lidar(int samples, double half, double stddev = 0.0) {
  SensorSpec s;
  s.name = "scan";
  s.type = SensorSpec::Type::lidar;
  s.link = "base_link";
  s.X_LS = Pose3{Vec3(0, 0, 0.05), Quat::Identity()};
  s.rate = 20;
  s.frame_id = "laser";
  s.lidar.min_angle = -half;
  s.lidar.max_angle = half;
  s.lidar.samples = samples;
  s.lidar.min_range = 0.05;
  s.lidar.max_range = 20.0;
  s.lidar.noise = {stddev, 0.0, 0.0};
  return s;
}

/// A medium over x in [x0, x1], y in [-w, w], from the floor to 1 m.
MediumSpec slab(MediumSpec::Kind kind, double density, double x0, double x1, double w = 10) {
  MediumSpec m;
  m.kind = kind;
  m.name = "slab";
  m.outline = {{x0, -w}, {x1, -w}, {x1, w}, {x0, w}};
  m.density = density;
  m.bottom = 0;
  m.height = 1;
  return m;
}

/// One robot at the origin facing +x, a wall whose face is x = 4, and the given media.
struct Fixture {
  World world;
  State state;
  RayScene scene;
  Fixture(const SensorSpec& s, std::vector<MediumSpec> media)
      : world(make_world(s, std::move(media))), state(initial_state(world)), scene(world) {}
  static World make_world(const SensorSpec& s, std::vector<MediumSpec> media) {
    WorldSpec spec = empty_spec();
    spec.walls.push_back(wall_facing_west(kWall));
    spec.robots.push_back({"r", "box_bot", {0, 0, 0}, {}});
    spec.media = std::move(media);
    return compile_with(spec, box_robot({s}));
  }
  msg::LaserScan scan(const SensorSpec& s, Rng& rng, SimTime stamp = SimTime::from_ms(1500)) const {
    return sample_lidar(world, state, scene, RobotIndex(0), s, stamp, rng);
  }
};

double beam_angle(const SensorSpec& s, int i) {
  return s.lidar.min_angle + i * (s.lidar.max_angle - s.lidar.min_angle) / (s.lidar.samples - 1);
}

/// True when a reading is the wall's return for beam angle a.
bool is_wall(float r, double a) { return std::abs(r - kWall / std::cos(a)) < 1e-4; }

TEST(LidarSmoke, ReturnFractionThroughASlabIsTwoWayBeerLambert) {
  // smoke of 0.5 /m over x in [1.5, 2.5] (L = 1 m), wall at 4 m: a beam at angle a crosses
  // L / cos a of it, so its wall echo survives with p(a) = exp(-2 * 0.5 / cos a); at a = 0 that is
  // exp(-1) = 0.3679. 101 beams over ±0.05 rad (cos a >= 0.99875, so p differs from exp(-1) by at
  // most 0.1 %) in 100 scans: N = 10100 rays. The count of wall echoes is a sum of independent
  // Bernoulli draws with mean sum p(a) and variance sum p (1 - p); its fraction has standard
  // deviation sqrt(0.3679 * 0.6321 / 10100) = 0.0048. We allow 4 of them: 0.0192, 5.2 % of exp(-1).
  const SensorSpec s = test_lidar(101, 0.05);
  const double sigma = 0.5, L = 1.0;
  const Fixture f(s, {slab(MediumSpec::Kind::smoke, sigma, 1.5, 1.5 + L)});
  Rng rng(7, "scan");
  int wall = 0, early = 0, none = 0, n = 0;
  double mean = 0, var = 0;
  for (int k = 0; k < 100; ++k) {
    const msg::LaserScan scan = f.scan(s, rng, SimTime::from_ms(50 * k));
    for (int i = 0; i < s.lidar.samples; ++i) {
      const double a = beam_angle(s, i);
      const float r = scan.ranges[static_cast<std::size_t>(i)];
      const double p = std::exp(-2 * sigma * L / std::cos(a));
      mean += p;
      var += p * (1 - p);
      ++n;
      if (is_wall(r, a)) {
        ++wall;
      } else if (std::isinf(r) && r > 0) {
        ++none;
      } else {
        // an early echo: inside the slab, x = r cos a in [1.5, 2.5]
        ++early;
        EXPECT_GE(r * std::cos(a), 1.5 - 1e-4) << "beam " << i << " scan " << k;
        EXPECT_LE(r * std::cos(a), 2.5 + 1e-4) << "beam " << i << " scan " << k;
      }
    }
  }
  mean /= n;
  const double sd = std::sqrt(var) / n;
  EXPECT_NEAR(mean, std::exp(-2 * sigma * L), 0.001 * std::exp(-2 * sigma * L));
  EXPECT_NEAR(static_cast<double>(wall) / n, mean, 4 * sd) << "sd " << sd;
  EXPECT_LT(4 * sd, 0.06 * std::exp(-2 * sigma * L));
  // the echoes lost (1 - 0.3679 of them) come back from the smoke half the time: 0.3161 of all
  // rays, standard deviation sqrt(0.3161 * 0.6839 / 10100) = 0.0046
  const double p_early = 0.5 * (1 - mean);
  EXPECT_NEAR(static_cast<double>(early) / n, p_early, 4 * std::sqrt(p_early * (1 - p_early) / n));
  EXPECT_EQ(wall + early + none, n);
}

TEST(LidarSmoke, EarlyEchoesFollowTheFirstScatteringDistribution) {
  // the early echo's depth into the slab, given it happened, has the truncated exponential law
  // P(depth <= x) = (1 - exp(-sigma x)) / (1 - exp(-sigma L)). With sigma = 2 /m, L = 1 m, the
  // median is x = -ln(1 - 0.5 (1 - exp(-2))) / 2 = 0.2832 m. Among the early echoes of 200 scans
  // of 21 beams over ±0.01 rad (about 2000 of them), the share nearer than 1.5 + 0.2832 m is 0.5
  // with standard deviation sqrt(0.25 / 2000) = 0.011; we allow 0.045.
  const SensorSpec s = test_lidar(21, 0.01);
  const Fixture f(s, {slab(MediumSpec::Kind::dust, 2.0, 1.5, 2.5)});
  Rng rng(3, "scan");
  const double median = -std::log(1 - 0.5 * (1 - std::exp(-2.0))) / 2.0;
  int early = 0, nearer = 0;
  for (int k = 0; k < 200; ++k) {
    const msg::LaserScan scan = f.scan(s, rng, SimTime::from_ms(50 * k));
    for (float r : scan.ranges) {
      if (!std::isfinite(r) || std::abs(r - kWall) < 0.01) continue;
      ++early;
      nearer += r < 1.5 + median;
    }
  }
  ASSERT_GT(early, 1500);
  EXPECT_NEAR(static_cast<double>(nearer) / early, 0.5, 0.045) << early << " early echoes";
}

TEST(LidarSmoke, RaysThatMissTheSlabReadTheWallExactly) {
  // a slab only 0.6 m wide (y in [-0.3, 0.3]) from x = 1.5 to 2.5: a beam at angle a reaches
  // x = 1.5 at |y| = 1.5 tan|a|, beside the slab when |a| > atan(0.2) = 0.1974 rad, and then
  // misses it all the way to the wall. 201 beams over ±1 rad, 20 scans.
  const SensorSpec s = test_lidar(201, 1.0);
  const Fixture f(s, {slab(MediumSpec::Kind::smoke, 3.0, 1.5, 2.5, 0.3)});
  Rng rng(11, "scan");
  int lost = 0, full = 0;
  for (int k = 0; k < 20; ++k) {
    const msg::LaserScan scan = f.scan(s, rng, SimTime::from_ms(50 * k));
    for (int i = 0; i < s.lidar.samples; ++i) {
      const double a = beam_angle(s, i);
      const float r = scan.ranges[static_cast<std::size_t>(i)];
      if (std::abs(a) > std::atan(0.2) + 1e-9) {
        EXPECT_TRUE(is_wall(r, a)) << "beam " << i << " at " << a << " rad read " << r;
      } else if (std::abs(a) < std::atan(0.3 / 2.5)) {
        // these leave through the far face: at least 1 m of 3 /m smoke, so the wall's echo
        // survives at most exp(-6) = 0.25 % of the time; of 20 x 23 such beams about 1 keeps it
        ++full;
        lost += !is_wall(r, a);
      }
    }
  }
  EXPECT_EQ(full, 20 * 23);
  EXPECT_GE(lost, full - 6);
}

TEST(LidarSmoke, ADriftingSlabMovesItsShadow) {
  // a 0.4 m wide slab (y in [-0.2, 0.2]) of dense smoke at x in [1.5, 2.5], drifting north at
  // 1 m/s: at t = 0 it covers the beams within atan(0.2 / 1.5) of the axis; at t = 2 s it spans
  // y in [1.8, 2.2], so the axis beam reads the wall and a beam at atan(2 / 2) = 45 deg is
  // inside it (from x = 1.8 to 2.2).
  const SensorSpec s = test_lidar(91, M_PI / 4);  // beams every 1 degree, the last at 45 degrees
  MediumSpec m = slab(MediumSpec::Kind::smoke, 20.0, 1.5, 2.5, 0.2);
  m.drift = {0, 1.0};
  const Fixture f(s, {m});
  Rng rng(5, "scan");
  const msg::LaserScan at0 = f.scan(s, rng, SimTime::from_seconds(0));
  const msg::LaserScan at2 = f.scan(s, rng, SimTime::from_seconds(2));
  EXPECT_FALSE(is_wall(at0.ranges[45], 0.0));  // exp(-40): no wall echo
  EXPECT_TRUE(is_wall(at0.ranges[90], M_PI / 4));
  EXPECT_TRUE(is_wall(at2.ranges[45], 0.0));
  EXPECT_FALSE(is_wall(at2.ranges[90], M_PI / 4));
}

TEST(LidarSmoke, TheSameSeedGivesTheSameScans) {
  const SensorSpec s = test_lidar(201, 1.0, 0.01);
  const Fixture f(s, {slab(MediumSpec::Kind::smoke, 0.7, 1.5, 2.5)});
  Rng a(9, "scan"), b(9, "scan"), c(10, "scan");
  bool differs = false;
  for (int k = 0; k < 10; ++k) {
    const msg::LaserScan sa = f.scan(s, a), sb = f.scan(s, b), sc = f.scan(s, c);
    ASSERT_EQ(std::memcmp(sa.ranges.data(), sb.ranges.data(), sa.ranges.size() * sizeof(float)), 0) << "scan " << k;
    differs = differs || std::memcmp(sa.ranges.data(), sc.ranges.data(), sa.ranges.size() * sizeof(float)) != 0;
  }
  EXPECT_TRUE(differs);
}

TEST(LidarSmoke, WithoutMediaOrWhereRaysMissThemScansAreBitwiseUnchanged) {
  // noisy beams, so any extra draw from the stream would shift every later reading: a world with
  // no media, a world whose smoke hangs above the beams (from 1 m up; the cloud's highest beam
  // is 0.67 m up where it leaves x = 2.5) and a world whose dust lies behind the lidar give the
  // same bytes
  const SensorSpec s = test_lidar(201, 1.0, 0.02);
  MediumSpec above = slab(MediumSpec::Kind::smoke, 5.0, 1.5, 2.5);
  above.bottom = 1.0;
  const Fixture clear(s, {}), high(s, {above}), behind(s, {slab(MediumSpec::Kind::dust, 5.0, -3, -1)});
  Rng r1(4, "scan"), r2(4, "scan"), r3(4, "scan");
  for (int k = 0; k < 5; ++k) {
    const msg::LaserScan a = clear.scan(s, r1), b = high.scan(s, r2), c = behind.scan(s, r3);
    ASSERT_EQ(std::memcmp(a.ranges.data(), b.ranges.data(), a.ranges.size() * sizeof(float)), 0) << "scan " << k;
    ASSERT_EQ(std::memcmp(a.ranges.data(), c.ranges.data(), a.ranges.size() * sizeof(float)), 0) << "scan " << k;
  }
  // and the multi-layer cloud likewise
  SensorSpec layered = s;
  layered.lidar.layers = 4;
  layered.lidar.vertical_fov = 0.2;
  Rng c1(4, "scan"), c2(4, "scan");
  const Fixture clear3(layered, {}), high3(layered, {above});
  EXPECT_EQ(sample_lidar_cloud(clear3.world, clear3.state, clear3.scene, RobotIndex(0), layered, SimTime::from_ms(100), c1).data,
            sample_lidar_cloud(high3.world, high3.state, high3.scene, RobotIndex(0), layered, SimTime::from_ms(100), c2).data);
}

/// A sonar with only its axis ray, 5 cm above base_link, facing +x.
SensorSpec axis_sonar() {
  SensorSpec s;
  s.name = "sonar_front";
  s.type = SensorSpec::Type::sonar;
  s.link = "base_link";
  s.X_LS = Pose3{Vec3(0, 0, 0.05), Quat::Identity()};
  s.rate = 10;
  s.frame_id = "sonar_front";
  s.sonar.fov = 0.5;
  s.sonar.rays = 1;
  s.sonar.max_range = 6.0;
  s.sonar.noise = {0.0, 0.0, 0.0};
  return s;
}

TEST(SonarSmoke, DustDampsTheEchoAtItsUltrasoundCoefficientAndSmokeNotAtAll) {
  // dust of 50 /m (visibility 6 cm) has an ultrasound coefficient of 0.01 * 50 = 0.5 /m: through
  // its 1 m the axis ray's echo survives exp(-2 * 0.5) = 0.3679. Over 2000 readings the fraction
  // has standard deviation sqrt(0.3679 * 0.6321 / 2000) = 0.0108; we allow 4 of them, 0.043.
  // Sound is not scattered back by the grains: a lost echo is no reading (+inf).
  const SensorSpec s = axis_sonar();
  const Fixture dust(s, {slab(MediumSpec::Kind::dust, 50.0, 1.5, 2.5)});
  const Fixture smoke(s, {slab(MediumSpec::Kind::smoke, 50.0, 1.5, 2.5)});
  Rng rng(2, "sonar_front");
  int heard = 0, silent = 0;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    const float r = sample_sonar(dust.world, dust.state, dust.scene, RobotIndex(0), s, SimTime::from_ms(100 * k), rng).range;
    if (std::abs(r - kWall) < 1e-3) ++heard;
    else if (std::isinf(r) && r > 0) ++silent;
  }
  EXPECT_EQ(heard + silent, n);
  const double p = std::exp(-1.0);
  EXPECT_NEAR(static_cast<double>(heard) / n, p, 4 * std::sqrt(p * (1 - p) / n));
  for (int k = 0; k < 50; ++k) {
    EXPECT_NEAR(sample_sonar(smoke.world, smoke.state, smoke.scene, RobotIndex(0), s, SimTime::from_ms(100 * k), rng).range, kWall, 1e-3);
  }
}

TEST(MediaEcho, ARayThroughNoMediumDrawsNothing) {
  const std::vector<MediumVolume> none;
  std::vector<MediumSegment> scratch;
  Rng a(1, "x"), b(1, "x");
  const Ray ray{Vec3(0, 0, 0.2), Vec3::UnitX(), 10.0f};
  EXPECT_EQ(echo_through_media(3.0f, ray, none, 0.5, a, scratch), 3.0f);
  std::vector<MediumVolume> beside;
  media_at(std::vector<MediumSpec>{slab(MediumSpec::Kind::smoke, 1.0, 1, 2, 0.5)}, 0, SensingBand::near_infrared, beside);
  const Ray away{Vec3(0, 1, 0.2), Vec3::UnitX(), 10.0f};
  EXPECT_EQ(echo_through_media(3.0f, away, beside, 0.5, a, scratch), 3.0f);
  EXPECT_EQ(a.next_u32(), b.next_u32());
}

}  // namespace
}  // namespace rescuesim
