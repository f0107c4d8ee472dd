// What urdfdom (and Gazebo's URDF conversion, and PyBullet) accept, rescuesim accepts too, and
// says what it made of it: masses of zero, inertias no rigid body has, Gazebo's value-attribute
// form, PyBullet's <contact> friction and <gazebo> blocks for links that are not there. Each
// expected number is worked out in the comment beside it.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <string>

#include "import/urdf/urdf_import.h"
#include "world/robot_lumping.h"

namespace rescuesim {
namespace {

UrdfRobot parse(const std::string& text) {
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  return parse_urdf(text, "robot.urdf", o);
}

/// One link "body" (line 2) with the given mass and inertia, and `more` after it.
std::string body_robot(const std::string& mass, const std::string& inertia, const std::string& more = "") {
  return R"(<robot name="r">
  <link name="body">
    <inertial><mass value=")" +
         mass + R"("/><inertia )" + inertia + R"(/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
)" + more +
         "</robot>\n";
}

int warnings_with(const UrdfRobot& r, const std::string& what) {
  int n = 0;
  for (const auto& d : r.diagnostics.items()) n += d.message.find(what) != std::string::npos;
  return n;
}

Eigen::Vector3d moments(const LinkSpec& l) { return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_tensor(l)).eigenvalues(); }

const LinkSpec& link(const UrdfRobot& r, const std::string& name) {
  return r.spec.links[static_cast<std::size_t>(r.spec.link_index(name))];
}

TEST(UrdfAsUrdfdom, AMassOfZeroOnAMovingBodyBecomesATokenMass) {
  const UrdfRobot r = parse(body_robot("0", R"(ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0")"));
  EXPECT_EQ(link(r, "body").mass, 0.01);
  EXPECT_EQ(warnings_with(r, "link 'body' moves but nothing on it has mass: giving it 0.01 kg"), 1);
  EXPECT_EQ(r.diagnostics.items()[0].where.line, 2);
}

TEST(UrdfAsUrdfdom, PrincipalMomentsBreakingTheTriangleInequalityBecomeTheirAverage) {
  // 1 + 1 < 3: no rigid body has these; MuJoCo's balanceinertia gives each (1 + 1 + 3) / 3
  const UrdfRobot r = parse(body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3")"));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moments(link(r, "body"))[k], 5.0 / 3.0, 1e-12);
  EXPECT_EQ(warnings_with(r, "breaks the triangle inequality (principal moments 1, 1, 3 kg m^2)"), 1);
  EXPECT_EQ(warnings_with(r, "balanceinertia"), 1);
}

TEST(UrdfAsUrdfdom, ANegativePrincipalMomentCountsAsZeroInTheAverage) {
  // moments -1, 1, 1: (0 + 1 + 1) / 3 each
  const UrdfRobot r = parse(body_robot("1", R"(ixx="-1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")"));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moments(link(r, "body"))[k], 2.0 / 3.0, 1e-12);
  EXPECT_EQ(warnings_with(r, "is not positive definite"), 1);
}

TEST(UrdfAsUrdfdom, AMassWithoutInertiaGetsASpheresOfFiveCentimetres) {
  // PyBullet's laikago: 2 kg and all six zero; a sphere's radius of gyration 5 cm:
  // 0.4 x 2 kg x 0.05^2 m^2 = 0.002 kg m^2 each
  const UrdfRobot r = parse(body_robot("2", R"(ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0")"));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moments(link(r, "body"))[k], 0.002, 1e-15);
  EXPECT_EQ(warnings_with(r, "has no positive principal moment"), 1);
}

TEST(UrdfAsUrdfdom, ALinkFixedToABodyOnlyAddsToIt) {
  // a camera (10 g, moments 1e-6, 1e-6, 1e-5: 2e-6 < 1e-5) fixed at the body's centre of mass:
  // the body physics sees has 0.1 + 1e-6, 0.1 + 1e-6, 0.1 + 1e-5, which is physical
  const UrdfRobot r = parse(body_robot("1", R"(ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1")", R"(  <link name="cam">
    <inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-5"/></inertial>
  </link>
  <joint name="cam_joint" type="fixed"><parent link="body"/><child link="cam"/></joint>
)"));
  EXPECT_EQ(r.diagnostics.warning_count(), 0);
  EXPECT_NEAR(moments(link(r, "cam"))[2], 1e-5, 1e-18);  // the link itself is kept as written
  const LumpedRobot lumped = lump_fixed_joints(r.spec);
  ASSERT_EQ(lumped.spec.links.size(), 1u);
  const Eigen::Vector3d p = moments(lumped.spec.links[0]);
  EXPECT_NEAR(p[0], 0.1 + 1e-6, 1e-12);
  EXPECT_NEAR(p[2], 0.1 + 1e-5, 1e-12);
}

TEST(UrdfAsUrdfdom, NegativeMassIsStillRefused) {
  EXPECT_THROW(parse(body_robot("-1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")")), Error);
}

double friction_of(const UrdfRobot& r, const std::string& name) {
  for (const LinkShape& sh : link(r, name).shapes) {
    for (const auto& m : r.spec.materials) {
      if (sh.collides && m.name == sh.material) return m.friction;
    }
  }
  return -1;
}

TEST(UrdfAsUrdfdom, GazeboValuesAreReadFromTheValueAttributeFirstAsGazeboDoes) {
  // sdformat's URDF conversion: the value attribute when present, else the text
  EXPECT_EQ(friction_of(parse(body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")",
                                         "  <gazebo reference=\"body\"><mu1 value=\"0.7\"/></gazebo>\n")),
                        "body"),
            0.7);
  EXPECT_EQ(friction_of(parse(body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")",
                                         "  <gazebo reference=\"body\"><mu1>0.7</mu1></gazebo>\n")),
                        "body"),
            0.7);
  EXPECT_EQ(friction_of(parse(body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")",
                                         "  <gazebo reference=\"body\"><mu1 value=\"0.3\">0.9</mu1></gazebo>\n")),
                        "body"),
            0.3);
}

TEST(UrdfAsUrdfdom, WhatAGazeboBlockHoldsBesideFrictionIsIgnoredOneWarningEach) {
  const UrdfRobot r =
      parse(body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")",
                       "  <gazebo reference=\"body\"><mu1>1</mu1><kp>1e6</kp><kd>1</kd><material>Gazebo/Red</material></gazebo>\n"));
  EXPECT_EQ(warnings_with(r, "Gazebo's <"), 3);
  EXPECT_EQ(warnings_with(r, "link 'body': Gazebo's <kp> is ignored"), 1);
}

TEST(UrdfAsUrdfdom, PyBulletsLateralFrictionIsTheLinksFriction) {
  const std::string contact = R"(<contact><lateral_friction value="0.6"/><rolling_friction value="0.01"/></contact>)";
  std::string text = body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")");
  text.insert(text.find("  </link>"), "    " + contact + "\n");
  const UrdfRobot r = parse(text);
  EXPECT_EQ(friction_of(r, "body"), 0.6);
  EXPECT_EQ(warnings_with(r, "PyBullet's <contact> <rolling_friction> is ignored"), 1);
  // a Gazebo <mu1> for the same link wins, and the lateral friction is said to be ignored
  text.insert(text.find("</robot>"), "  <gazebo reference=\"body\"><mu1>0.9</mu1></gazebo>\n");
  const UrdfRobot both = parse(text);
  EXPECT_EQ(friction_of(both, "body"), 0.9);
  EXPECT_EQ(warnings_with(both, "PyBullet's <lateral_friction> is ignored"), 1);
}

TEST(UrdfAsUrdfdom, AGazeboBlockForALinkThatIsNotThereIsIgnored) {
  const UrdfRobot r = parse(
      body_robot("1", R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1")", "  <gazebo reference=\"stick_link\"><mu1>1</mu1></gazebo>\n"));
  EXPECT_EQ(warnings_with(r, "<gazebo reference=\"stick_link\"> names no link of the robot: ignored"), 1);
  EXPECT_EQ(r.diagnostics.items()[0].where.line, 6);
}

}  // namespace
}  // namespace rescuesim
