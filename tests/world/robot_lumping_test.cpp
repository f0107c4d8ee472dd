// Fixed joints merged for physics: masses, centres of mass and inertias combine as the
// parallel-axis theorem says, shapes move into the body frame, and a robot without fixed
// joints comes back unchanged.

#include <gtest/gtest.h>

#include "robots/rescue_robot.h"
#include "world/robot_lumping.h"

namespace rescuesim {
namespace {

LinkSpec point_like(const std::string& name, double mass, const Vec3& inertia) {
  LinkSpec l;
  l.name = name;
  l.mass = mass;
  l.inertia = inertia;
  return l;
}

JointSpec joint(const std::string& name, JointSpec::Type type, const std::string& parent, const std::string& child, const Pose3& X_PJ) {
  JointSpec j;
  j.name = name;
  j.type = type;
  j.parent = parent;
  j.child = child;
  j.X_PJ = X_PJ;
  j.axis = Vec3::UnitY();
  return j;
}

TEST(RobotLumping, FixedChildMergesByTheParallelAxisTheorem) {
  RobotSpec r;
  r.links.push_back(point_like("base", 2.0, {0.1, 0.2, 0.3}));
  r.links.push_back(point_like("sensor", 1.0, {0.01, 0.01, 0.01}));
  r.links.push_back(point_like("wheel", 0.5, {0.02, 0.03, 0.02}));
  LinkShape box;
  box.geometry = Geometry::box({0.1, 0.1, 0.1});
  r.links[1].shapes.push_back(box);
  // the sensor 0.3 m ahead of the base, turned 90 degrees about z; the wheel on a moving joint below the sensor
  r.joints.push_back(joint("mount", JointSpec::Type::fixed, "base", "sensor", Pose3::from_rpy({0.3, 0, 0}, 0, 0, M_PI / 2)));
  r.joints.push_back(joint("axle", JointSpec::Type::continuous, "sensor", "wheel", Pose3{{0, 0, -0.1}, Quat::Identity()}));

  const LumpedRobot l = lump_fixed_joints(r);
  ASSERT_EQ(l.spec.links.size(), 2u);
  ASSERT_EQ(l.spec.joints.size(), 1u);
  EXPECT_EQ(l.body_of_link, (std::vector<int>{0, 0, 1}));
  EXPECT_EQ(l.lumped_joint, (std::vector<int>{-1, 0}));
  EXPECT_EQ(l.joint_of, (std::vector<int>{1}));
  const LinkSpec& body = l.spec.links[0];
  EXPECT_DOUBLE_EQ(body.mass, 3.0);
  // centre of mass: (2 x 0 + 1 x 0.3) / 3 = 0.1 m ahead
  EXPECT_NEAR(body.com.x(), 0.1, 1e-12);
  // inertia about the common centre: base (0.1, 0.2, 0.3) + 2 x 0.1^2 off-axis in y and z;
  // sensor turned 90 degrees about z (x and y moments swap, all 0.01 here) + 1 x 0.2^2 off-axis
  const Eigen::Matrix3d I = inertia_tensor(body);
  EXPECT_NEAR(I(0, 0), 0.1 + 0.01, 1e-12);
  EXPECT_NEAR(I(1, 1), 0.2 + 2 * 0.01 + 0.01 + 0.04, 1e-12);
  EXPECT_NEAR(I(2, 2), 0.3 + 2 * 0.01 + 0.01 + 0.04, 1e-12);
  // the sensor's box now sits 0.3 m ahead in the body frame
  ASSERT_EQ(body.shapes.size(), 1u);
  EXPECT_NEAR(body.shapes[0].X_LG.p.x(), 0.3, 1e-12);
  // the moving joint hangs from the body at the sensor's place
  EXPECT_EQ(l.spec.joints[0].parent, "base");
  EXPECT_NEAR(l.spec.joints[0].X_PJ.p.x(), 0.3, 1e-12);
  EXPECT_NEAR(l.spec.joints[0].X_PJ.p.z(), -0.1, 1e-12);
  // the sensor link is found again through its body
  EXPECT_NEAR(l.X_BL[1].p.x(), 0.3, 1e-12);
}

TEST(RobotLumping, RobotWithoutFixedJointsIsUnchanged) {
  const RobotSpec r = rescue_robot();
  const LumpedRobot l = lump_fixed_joints(r);
  ASSERT_EQ(l.spec.links.size(), r.links.size());
  ASSERT_EQ(l.spec.joints.size(), r.joints.size());
  for (std::size_t i = 0; i < r.links.size(); ++i) {
    EXPECT_EQ(l.spec.links[i].name, r.links[i].name);
    EXPECT_EQ(l.spec.links[i].mass, r.links[i].mass);
    EXPECT_EQ(l.spec.links[i].com, r.links[i].com);
    EXPECT_EQ(l.spec.links[i].inertia, r.links[i].inertia);
    EXPECT_EQ(l.body_of_link[i], static_cast<int>(i));
  }
  for (std::size_t j = 0; j < r.joints.size(); ++j) {
    EXPECT_EQ(l.spec.joints[j].X_PJ.p, r.joints[j].X_PJ.p);
    EXPECT_EQ(l.lumped_joint[j], static_cast<int>(j));
  }
}

TEST(RobotLumping, InertiaTensorRoundTripsThroughPrincipalAxes) {
  LinkSpec l;
  Eigen::Matrix3d I;
  I << 2.2124416e-03, -1.2294101e-05, 3.4938785e-05, -1.2294101e-05, 2.1193702e-03, -5.0120904e-06, 3.4938785e-05, -5.0120904e-06,
      2.0064271e-03;
  set_inertia_tensor(l, I);
  EXPECT_TRUE(inertia_tensor(l).isApprox(I, 1e-12));
  EXPECT_NEAR(l.inertia_axes.norm(), 1.0, 1e-12);
  // a diagonal tensor keeps the identity axes exactly
  set_inertia_tensor(l, Eigen::Vector3d(1, 2, 3).asDiagonal());
  EXPECT_EQ(l.inertia_axes.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(l.inertia, Vec3(1, 2, 3));
}

}  // namespace
}  // namespace rescuesim
