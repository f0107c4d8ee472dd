#include "autonomy/slip_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "autonomy/kinematic_sim.h"

namespace rescuesim::autonomy {
namespace {

using testing::Segment;

// a 360-beam scan of zero-thickness segments from sensor pose X_WS, 8 m range
msg::LaserScan scan_of(const std::vector<Segment>& walls, const Pose2& X_WS) {
  msg::LaserScan s;
  s.angle_min = static_cast<float>(-M_PI);
  s.angle_increment = static_cast<float>(2 * M_PI / 360);
  s.angle_max = s.angle_min + 359 * s.angle_increment;
  s.range_min = 0.05f;
  s.range_max = 8.0f;
  for (int i = 0; i < 360; ++i) {
    const double a = X_WS.yaw + s.angle_min + i * static_cast<double>(s.angle_increment);
    const double r = testing::ray_cast(X_WS.position(), Vec2(std::cos(a), std::sin(a)), walls);
    s.ranges.push_back(r < s.range_max ? static_cast<float>(r) : std::numeric_limits<float>::infinity());
  }
  return s;
}

// an L-shaped room with a pillar: plenty to see from anywhere
std::vector<Segment> room() {
  std::vector<Segment> w = testing::box(0, 0, 6, 4);
  for (const Segment& s : testing::box(3.5, 1.5, 4.0, 2.0)) w.push_back(s);
  return w;
}

TEST(SlipDetector, RealMotionFitsOdometry) {
  SlipDetector d;
  const Pose2 start{1.0, 1.0, 0.3};
  EXPECT_FALSE(d.add(scan_of(room(), start), start));
  int comparisons = 0;
  for (int k = 1; k <= 20; ++k) {
    const Pose2 X{1.0 + 0.1 * k, 1.0 + 0.05 * k, 0.3 + 0.03 * k};  // odometry = truth
    comparisons += d.add(scan_of(room(), X), X) ? 1 : 0;
    EXPECT_FALSE(d.last_misfit()) << k;
    EXPECT_FALSE(d.slipping()) << k;
  }
  EXPECT_EQ(comparisons, 6);  // every 0.335 m of travel
  EXPECT_LT(d.moved_error(), 0.05);
  EXPECT_GT(d.still_error(), 0.1);
}

TEST(SlipDetector, OdometryMovingWhileTheScansStayIsSlipping) {
  SlipDetector d;
  const Pose2 truth{1.0, 1.0, 0.3};
  const msg::LaserScan scan = scan_of(room(), truth);
  d.add(scan, truth);
  EXPECT_FALSE(d.add(scan, {1.2, 1.06, 0.3}));  // 0.21 m claimed: too little to judge yet
  EXPECT_TRUE(d.add(scan, {1.5, 1.15, 0.3}));   // 0.52 m claimed, the world did not move
  EXPECT_TRUE(d.last_misfit());
  EXPECT_FALSE(d.slipping());                   // one misfit is not yet slipping ...
  EXPECT_LT(d.still_error(), 1e-9);
  EXPECT_GT(d.moved_error(), 0.2);
  EXPECT_TRUE(d.add(scan, {1.9, 1.3, 0.3}));
  EXPECT_TRUE(d.slipping());                    // ... two of the last three are
  // a claimed turn on the spot that the scans do not show
  SlipDetector turning;
  turning.add(scan, truth);
  turning.add(scan, {1.0, 1.0, 0.9});
  turning.add(scan, {1.0, 1.0, 1.5});
  EXPECT_TRUE(turning.slipping());
  // a good fit pushes the misfits out of the window
  const Pose2 moved{1.9, 1.3, 0.3};
  d.add(scan_of(room(), moved), {2.3, 1.45, 0.3});
  EXPECT_TRUE(d.slipping());
  for (double x : {2.3, 2.7}) d.add(scan_of(room(), {x, 1.3, 0.3}), {x + 0.4, 1.45, 0.3});
  EXPECT_FALSE(d.slipping());
}

TEST(SlipDetector, AFeaturelessCorridorIsNeverCalledSlipping) {
  // two parallel walls running out of range both ways: moving along them changes nothing,
  // so no claimed motion along them can be refuted
  const std::vector<Segment> corridor = {{{-50.0, 0.0}, {50.0, 0.0}}, {{-50.0, 1.5}, {50.0, 1.5}}};
  SlipDetector d;
  const Pose2 X{0.0, 0.75, 0.0};
  const msg::LaserScan scan = scan_of(corridor, X);
  d.add(scan, X);
  for (double x : {0.5, 1.0, 1.5}) EXPECT_TRUE(d.add(scan, {x, 0.75, 0.0}));
  EXPECT_FALSE(d.slipping());
  EXPECT_LT(d.moved_error(), 0.05);
}

TEST(SlipDetector, OdometryAgainstScanMatching) {
  // matched poses that follow odometry up to a fixed correction (a drifted odom frame, X_MO =
  // (0.5 m, -0.2 m, 0.1 rad)) agree with it: the same motion, only expressed elsewhere
  const Pose2 X_MO{0.5, -0.2, 0.1};
  SlipDetector agree;
  int comparisons = 0;
  for (int k = 0; k <= 12; ++k) {
    const Pose2 X_OB{0.1 * k, 0.02 * k, 0.05 * k};
    comparisons += agree.add_motion(X_OB, X_MO * X_OB) ? 1 : 0;
    EXPECT_FALSE(agree.last_misfit()) << k;
  }
  EXPECT_EQ(comparisons, 4);  // every 0.306 m of odometry travel (every 3 steps of 0.102 m)
  EXPECT_LT(agree.moved_error(), 1e-9);
  EXPECT_FALSE(agree.slipping());
  // odometry runs on 0.11 m a step while the map keeps the robot in place: every comparison
  // (0.33 m claimed, none matched) is a misfit, and two of them are slipping
  SlipDetector spin;
  const Pose2 X_MB{2.0, 1.0, 0.4};
  for (int k = 0; k <= 3; ++k) spin.add_motion({0.11 * k, 0, 0}, X_MB);
  EXPECT_TRUE(spin.last_misfit());
  EXPECT_NEAR(spin.moved_error(), 0.33, 1e-9);
  EXPECT_FALSE(spin.slipping());
  for (int k = 4; k <= 6; ++k) spin.add_motion({0.11 * k, 0, 0}, X_MB);
  EXPECT_TRUE(spin.slipping());
  spin.reset();
  EXPECT_FALSE(spin.slipping());
}

TEST(SlipDetector, ResetAndANewLaserSetupStartAfresh) {
  SlipDetector d;
  const Pose2 X{1.0, 1.0, 0.0};
  const msg::LaserScan scan = scan_of(room(), X);
  d.add(scan, X);
  d.add(scan, {1.5, 1.0, 0.0});
  d.add(scan, {2.0, 1.0, 0.0});
  EXPECT_TRUE(d.slipping());
  d.reset();
  EXPECT_FALSE(d.slipping());
  EXPECT_FALSE(d.add(scan, {2.0, 1.0, 0.0}));  // the new reference
  msg::LaserScan other = scan;
  other.ranges.resize(180);
  EXPECT_FALSE(d.add(other, {3.0, 1.0, 0.0}));  // another setup: a new reference, no verdict
  EXPECT_FALSE(d.slipping());
}

}  // namespace
}  // namespace rescuesim::autonomy
