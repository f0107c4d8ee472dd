// URDF robots read into RobotSpecs: the TurtleBot3 burger and waffle_pi from their own files
// (ROBOTIS, Apache-2.0), package:// and relative mesh URIs found where ROS would find them,
// and inertials, mimic and prismatic joints from small inline URDFs (Gazebo extensions are in
// urdf_gazebo_test.cpp). Every expected number is read off the URDF text or computed by hand.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "import/mesh/mesh.h"
#include "import/urdf/urdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using urdf_test::joint_named;
using urdf_test::link_named;
using urdf_test::no_environment;
using urdf_test::TempDir;
using urdf_test::warnings;

UrdfOptions turtlebot3_options() {
  UrdfOptions o;
  o.resolver = ResourceResolver({urdf_test::robots_dir()}, false);
  return o;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// TurtleBot3 burger

TEST(UrdfImport, BurgerHasItsLinksAndJoints) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  const RobotSpec& r = u.spec;
  EXPECT_EQ(r.model, "turtlebot3_burger");
  EXPECT_EQ(u.root_link, "base_footprint");
  ASSERT_EQ(r.links.size(), 7u);
  EXPECT_EQ(r.links[0].name, "base_footprint");  // links[0] is the base
  ASSERT_EQ(r.joints.size(), 6u);
  EXPECT_EQ(u.moving_joints, 2);
  EXPECT_EQ(u.fixed_joints, 4);
  EXPECT_EQ(joint_named(r, "wheel_left_joint").type, JointSpec::Type::continuous);
  EXPECT_EQ(joint_named(r, "wheel_right_joint").type, JointSpec::Type::continuous);
  for (const char* fixed : {"base_joint", "caster_back_joint", "imu_joint", "scan_joint"}) {
    EXPECT_EQ(joint_named(r, fixed).type, JointSpec::Type::fixed) << fixed;
  }
  // tree order: every joint's parent link comes before its child link
  for (const auto& j : r.joints) EXPECT_LT(r.link_index(j.parent), r.link_index(j.child)) << j.name;
  // the wheel joint sits 0.08 m to the left of base_link and 0.023 m up
  EXPECT_NEAR(joint_named(r, "wheel_left_joint").X_PJ.p.y(), 0.08, 1e-12);
  EXPECT_NEAR(joint_named(r, "wheel_left_joint").X_PJ.p.z(), 0.023, 1e-12);
  EXPECT_EQ(r.source_file, urdf_test::turtlebot3_urdf("burger").string());
}

TEST(UrdfImport, BurgerMassIsTheSumOfItsInertials) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  // base_link + two wheels + caster + base_scan; base_footprint and imu_link have no inertial
  EXPECT_NEAR(u.spec.total_mass(), 0.8257 + 2 * 0.0285 + 0.005 + 0.114, 1e-3);
  EXPECT_NEAR(link_named(u.spec, "base_link").mass, 8.2573504e-01, 1e-12);
  EXPECT_NEAR(link_named(u.spec, "wheel_left_link").mass, 2.8498940e-02, 1e-12);
  EXPECT_EQ(link_named(u.spec, "base_footprint").mass, 0.0);
  // every link that moves has mass of its own, so nothing was made up
  EXPECT_EQ(u.diagnostics.warning_count(), 0) << warnings(u);
}

TEST(UrdfImport, NamespacePlaceholderIsEmptyByDefault) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  for (const auto& l : u.spec.links) EXPECT_EQ(l.name.find('$'), std::string::npos) << l.name;
  for (const auto& j : u.spec.joints) {
    EXPECT_EQ(j.name.find('$'), std::string::npos) << j.name;
    EXPECT_EQ(j.parent.find('$'), std::string::npos) << j.parent;
    EXPECT_EQ(j.child.find('$'), std::string::npos) << j.child;
  }
  EXPECT_GE(u.spec.link_index("base_link"), 0);
}

TEST(UrdfImport, NamespacePrefixFillsThePlaceholder) {
  UrdfOptions o = turtlebot3_options();
  o.namespace_prefix = "tb3_";
  UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), o);
  EXPECT_EQ(u.root_link, "tb3_base_footprint");
  for (const char* name : {"tb3_base_footprint", "tb3_base_link", "tb3_wheel_left_link", "tb3_wheel_right_link", "tb3_caster_back_link",
                           "tb3_imu_link", "tb3_base_scan"}) {
    EXPECT_GE(u.spec.link_index(name), 0) << name;
  }
  EXPECT_EQ(u.spec.link_index("base_link"), -1);
  EXPECT_EQ(joint_named(u.spec, "tb3_wheel_left_joint").parent, "tb3_base_link");
  // the prefixed wheels make the same drive
  configure_diff_drive(u.spec, {"tb3_wheel_left_joint"}, {"tb3_wheel_right_joint"}, 0, 0, {});
  EXPECT_NEAR(u.spec.drive.track_width, 0.160, 1e-3);
}

TEST(UrdfImport, BurgerWheelsMakeADiffDrive) {
  UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  RobotSpec& r = u.spec;
  EXPECT_TRUE(r.drive.left_wheels.empty());  // the burger URDF has no drive plugin
  configure_diff_drive(r, {"wheel_left_joint"}, {"wheel_right_joint"}, 0, 0, {});
  // radius from the wheels' collision cylinders (radius 0.033); track between y = +0.08 and -0.08
  EXPECT_NEAR(r.drive.wheel_radius, 0.033, 1e-6);
  EXPECT_NEAR(r.drive.track_width, 0.160, 1e-3);
  // axis z turned by roll -1.57 about x is (0, sin 1.57, cos 1.57): +y on both sides, so a
  // positive speed rolls each wheel forward
  ASSERT_EQ(r.drive.left_signs.size(), 1u);
  ASSERT_EQ(r.drive.right_signs.size(), 1u);
  EXPECT_EQ(r.drive.left_signs[0], 1.0);
  EXPECT_EQ(r.drive.right_signs[0], 1.0);
  EXPECT_EQ(r.drive.track_multiplier, 1.0);
  EXPECT_EQ(joint_named(r, "wheel_left_joint").control, JointSpec::Control::velocity);
  EXPECT_EQ(joint_named(r, "wheel_right_joint").control, JointSpec::Control::velocity);
  // and with a drive, the standard sensors include odometry
  add_standard_sensors(r);
  bool odometry = false;
  for (const auto& s : r.sensors) odometry = odometry || s.type == SensorSpec::Type::odometry;
  EXPECT_TRUE(odometry);
}

TEST(UrdfImport, OffDiagonalInertiaIsKept) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  // base_link's <inertia>, with its rotation-free <origin>
  const Eigen::Matrix3d I = inertia_tensor(link_named(u.spec, "base_link"));
  EXPECT_NEAR(I(0, 0), 2.2124416e-03, 1e-9);
  EXPECT_NEAR(I(0, 1), -1.2294101e-05, 1e-9);
  EXPECT_NEAR(I(0, 2), 3.4938785e-05, 1e-9);
  EXPECT_NEAR(I(1, 1), 2.1193702e-03, 1e-9);
  EXPECT_NEAR(I(1, 2), -5.0120904e-06, 1e-9);
  EXPECT_NEAR(I(2, 2), 2.0064271e-03, 1e-9);
  EXPECT_NEAR(I(1, 0), I(0, 1), 1e-15);
  EXPECT_NEAR(I(2, 0), I(0, 2), 1e-15);
  EXPECT_NEAR(I(2, 1), I(1, 2), 1e-15);
  // the wheel's tiny products of inertia too
  const Eigen::Matrix3d W = inertia_tensor(link_named(u.spec, "wheel_left_link"));
  EXPECT_NEAR(W(0, 0), 1.1175580e-05, 1e-9);
  EXPECT_NEAR(W(0, 2), -5.9381719e-09, 1e-12);
  EXPECT_NEAR(W(2, 2), 2.0712558e-05, 1e-9);
}

TEST(UrdfImport, VisualMeshesAreVisibleCollisionShapesAreNot) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  const LinkSpec& base = link_named(u.spec, "base_link");
  ASSERT_EQ(base.shapes.size(), 2u);  // one <collision> box, one <visual> mesh
  int visual = 0, collision = 0;
  for (const auto& l : u.spec.links) {
    for (const auto& sh : l.shapes) {
      EXPECT_NE(sh.collides, sh.visible) << l.name;  // each shape is one or the other
      if (sh.geometry.type == Geometry::Type::mesh) {
        EXPECT_FALSE(sh.collides) << l.name;
        EXPECT_TRUE(sh.visible) << l.name;
      }
      (sh.collides ? collision : visual)++;
    }
  }
  // visuals: base, two tyres, lds; collisions: base box, two cylinders, caster box, lds cylinder
  EXPECT_EQ(visual, 4);
  EXPECT_EQ(collision, 5);
  for (const auto& sh : base.shapes) {
    if (!sh.collides) continue;
    ASSERT_EQ(sh.geometry.type, Geometry::Type::box);
    EXPECT_TRUE(sh.geometry.size.isApprox(Vec3(0.140, 0.140, 0.143), 1e-12));
    EXPECT_TRUE(sh.X_LG.p.isApprox(Vec3(-0.032, 0, 0.070), 1e-12));
  }
}

TEST(UrdfImport, BurgerMeshesAreReportedWithTheirTriangles) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  ASSERT_EQ(u.meshes.size(), 4u);
  const auto base = urdf_test::robots_dir() / "turtlebot3_description/meshes/bases/burger_base.stl";
  bool found = false;
  for (const auto& m : u.meshes) {
    EXPECT_FALSE(m.collision) << m.uri;
    EXPECT_GT(m.triangles, 0) << m.uri;
    EXPECT_TRUE(std::filesystem::exists(m.file)) << m.file;
    if (m.uri == "package://turtlebot3_description/meshes/bases/burger_base.stl") {
      found = true;
      EXPECT_EQ(m.link, "base_link");
      EXPECT_TRUE(std::filesystem::equivalent(m.file, base));
      // a binary STL holds (size - 84) / 50 triangles
      EXPECT_EQ(m.triangles, static_cast<int>((std::filesystem::file_size(base) - 84) / 50));
      EXPECT_EQ(m.triangles, 34320);
    }
  }
  EXPECT_TRUE(found);
}

TEST(UrdfImport, DescriptionIsTheUrdfTextWithPlaceholdersFilled) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("burger"), turtlebot3_options());
  std::string text = slurp(urdf_test::turtlebot3_urdf("burger"));
  ASSERT_NE(text.find("${namespace}"), std::string::npos);
  for (std::size_t at; (at = text.find("${namespace}")) != std::string::npos;) text.erase(at, 12);
  EXPECT_EQ(u.spec.description, text);
}

// TurtleBot3 waffle_pi, and the COLLADA camera mesh of the same package

TEST(UrdfImport, WafflePiLoads) {
  const UrdfRobot u = load_urdf(urdf_test::turtlebot3_urdf("waffle_pi"), turtlebot3_options());
  EXPECT_EQ(u.spec.model, "turtlebot3_waffle_pi");
  EXPECT_EQ(u.root_link, "base_footprint");
  EXPECT_EQ(u.spec.links.size(), 11u);
  EXPECT_EQ(u.moving_joints, 2);
  EXPECT_EQ(u.fixed_joints, 8);
  ASSERT_FALSE(u.meshes.empty());
  for (const auto& m : u.meshes) EXPECT_GT(m.triangles, 0) << m.uri;
  for (const auto& m : u.meshes) {
    if (m.uri.find("waffle_pi_base.stl") != std::string::npos) {
      EXPECT_EQ(m.triangles, 63200);  // (3160084 - 84) / 50
    }
  }
  // camera_link has a collision box but no <inertial>: its mass is estimated, with a warning
  EXPECT_THAT(warnings(u), HasSubstr("camera_link"));
  EXPECT_NEAR(link_named(u.spec, "camera_link").mass, 1000 * 0.015 * 0.030 * 0.027, 1e-9);
}

TEST(UrdfImport, ColladaMeshFromThePackageLoads) {
  TempDir dir;
  const auto file = dir.write("camera.urdf", R"(<robot name="camera">
  <link name="camera_link">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <visual><geometry><mesh filename="package://turtlebot3_description/meshes/sensors/r200.dae"/></geometry></visual>
  </link>
</robot>
)");
  const UrdfRobot u = load_urdf(file, turtlebot3_options());
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_GT(u.meshes[0].triangles, 0);
  EXPECT_FALSE(u.meshes[0].collision);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, urdf_test::robots_dir() / "turtlebot3_description/meshes/sensors/r200.dae"));
  const LinkSpec& l = u.spec.links[0];
  ASSERT_EQ(l.shapes.size(), 1u);
  EXPECT_EQ(l.shapes[0].geometry.type, Geometry::Type::mesh);
  EXPECT_EQ(static_cast<int>(l.shapes[0].geometry.mesh.triangles.size()), u.meshes[0].triangles);
}

// where mesh URIs are found

/// A robot of one link whose visual is the mesh at `uri` (line 4).
std::string one_mesh_robot(const std::string& uri, bool collision = false) {
  const std::string tag = collision ? "collision" : "visual";
  return R"(<robot name="meshy">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <)" + tag + R"(><geometry><mesh filename=")" + uri + R"("/></geometry></)" + tag + R"(>
  </link>
</robot>
)";
}

/// A 0.1 m cube mesh, centred on the origin.
std::string cube_stl() { return urdf_test::binary_stl(urdf_test::box_mesh(Vec3::Constant(-0.05), Vec3::Constant(0.05))); }

TEST(UrdfImport, PackageFoundThroughSearchPaths) {
  TempDir dir;
  const auto mesh = dir.write("ws/src/mypkg/meshes/cube.stl", cube_stl());
  const auto file = dir.write("robot/robot.urdf", one_mesh_robot("package://mypkg/meshes/cube.stl"));
  UrdfOptions o;
  o.resolver = ResourceResolver({dir.path() / "elsewhere", dir.path() / "ws" / "src"}, false);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, mesh));
  EXPECT_EQ(u.meshes[0].triangles, 12);
  // a search path may also be the package folder itself
  o.resolver = ResourceResolver({dir.path() / "ws" / "src" / "mypkg"}, false);
  EXPECT_TRUE(std::filesystem::equivalent(load_urdf(file, o).meshes.at(0).file, mesh));
}

TEST(UrdfImport, PackageFoundThroughRosPackagePath) {
  TempDir dir;
  const auto mesh = dir.write("catkin/src/mypkg/meshes/cube.stl", cube_stl());
  const auto file = dir.write("robot.urdf", one_mesh_robot("package://mypkg/meshes/cube.stl"));
  urdf_test::ScopedEnv ros("ROS_PACKAGE_PATH", (dir.path() / "nothing").string() + ":" + (dir.path() / "catkin/src").string());
  urdf_test::ScopedEnv ament("AMENT_PREFIX_PATH", std::nullopt);
  UrdfOptions o;
  o.resolver = ResourceResolver({}, true);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, mesh));
}

TEST(UrdfImport, PackageFoundThroughAmentPrefixPath) {
  TempDir dir;
  const auto mesh = dir.write("install/share/mypkg/meshes/cube.stl", cube_stl());
  const auto file = dir.write("robot.urdf", one_mesh_robot("package://mypkg/meshes/cube.stl"));
  urdf_test::ScopedEnv ros("ROS_PACKAGE_PATH", std::nullopt);
  urdf_test::ScopedEnv ament("AMENT_PREFIX_PATH", (dir.path() / "opt").string() + ":" + (dir.path() / "install").string());
  UrdfOptions o;
  o.resolver = ResourceResolver({}, true);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, mesh));
}

TEST(UrdfImport, EnvironmentIsIgnoredWhenTheResolverSaysSo) {
  TempDir dir;
  dir.write("catkin/src/mypkg/meshes/cube.stl", cube_stl());
  const auto file = dir.write("robot.urdf", one_mesh_robot("package://mypkg/meshes/cube.stl"));
  urdf_test::ScopedEnv ros("ROS_PACKAGE_PATH", (dir.path() / "catkin/src").string());
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  // a visual mesh not found is left out with a warning (as in Gazebo and RViz); a collision one
  // is an error
  const UrdfRobot u = load_urdf(file, o);
  EXPECT_TRUE(u.meshes.empty());
  ASSERT_EQ(u.diagnostics.warning_count(), 2);  // and that it has no collision shape
  EXPECT_NE(u.diagnostics.items()[0].message.find("visual mesh left out"), std::string::npos);
  EXPECT_NE(u.diagnostics.items()[0].message.find("package://mypkg/meshes/cube.stl"), std::string::npos);
  const auto with_collision = dir.write("robot2.urdf", one_mesh_robot("package://mypkg/meshes/cube.stl", true));
  EXPECT_THROW(load_urdf(with_collision, o), Error);
}

TEST(UrdfImport, RelativeMeshPathIsTakenFromTheUrdfFolder) {
  TempDir dir;
  const auto mesh = dir.write("robot/meshes/cube.stl", cube_stl());
  dir.write("meshes/cube.stl", "not this one");  // beside the working directory's idea of "meshes"
  const auto file = dir.write("robot/robot.urdf", one_mesh_robot("meshes/cube.stl"));
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, mesh));
}

TEST(UrdfImport, FileUriWithAnAbsolutePath) {
  TempDir dir;
  const auto mesh = dir.write("anywhere/cube.stl", cube_stl());
  ASSERT_TRUE(mesh.is_absolute());
  const auto file = dir.write("robot/robot.urdf", one_mesh_robot("file://" + mesh.string()));
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  EXPECT_TRUE(std::filesystem::equivalent(u.meshes[0].file, mesh));
}

TEST(UrdfImport, CollisionMeshBecomesItsConvexHull) {
  TempDir dir;
  dir.write("cube.stl", cube_stl());
  const auto file = dir.write("robot.urdf", one_mesh_robot("cube.stl", true));
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  const UrdfRobot u = load_urdf(file, o);
  ASSERT_EQ(u.meshes.size(), 1u);
  const UrdfMeshReport& m = u.meshes[0];
  EXPECT_TRUE(m.collision);
  EXPECT_EQ(m.triangles, 12);
  EXPECT_EQ(m.pieces, 1);
  EXPECT_EQ(m.hull_vertices, 8);  // a cube's hull is its 8 corners
  EXPECT_NEAR(m.mesh_volume, 0.001, 1e-9);
  EXPECT_NEAR(m.hull_volume, 0.001, 1e-9);
  ASSERT_EQ(u.spec.links[0].shapes.size(), 1u);
  const LinkShape& sh = u.spec.links[0].shapes[0];
  EXPECT_EQ(sh.geometry.type, Geometry::Type::convex);
  EXPECT_TRUE(sh.collides);
  EXPECT_FALSE(sh.visible);
}

TEST(UrdfImport, UndefinedMaterialIsAWarningWithItsLine) {
  // urdfdom 3 keeps the visual and only warns; the warning should reach the user
  const std::string text = R"(<robot name="plain">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <visual>
      <geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="undefined_colour"/>
    </visual>
  </link>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "plain.urdf", no_environment());
  ASSERT_EQ(u.spec.links.at(0).shapes.size(), 1u);
  // the material's, and that a robot of visuals only falls through the floor
  ASSERT_EQ(u.diagnostics.warning_count(), 2) << warnings(u);
  EXPECT_THAT(u.diagnostics.items()[1].message, HasSubstr("no <collision> shape"));
  EXPECT_THAT(u.diagnostics.items()[0].message, HasSubstr("undefined_colour"));
  EXPECT_EQ(u.diagnostics.items()[0].where.file, "plain.urdf");
  EXPECT_GT(u.diagnostics.items()[0].where.line, 0);
}

// inertials and joints

TEST(UrdfImport, LinkWithoutInertialGetsMassFromItsCollisionBox) {
  const std::string text = R"(<robot name="block">
  <link name="cube">
    <collision>
      <origin xyz="0.2 0 0.05"/>
      <geometry><box size="0.1 0.1 0.1"/></geometry>
    </collision>
  </link>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "block.urdf", no_environment());
  const LinkSpec& l = u.spec.links.at(0);
  // 1000 kg/m^3 x 0.001 m^3
  EXPECT_NEAR(l.mass, 1.0, 1e-9);
  EXPECT_TRUE(l.com.isApprox(Vec3(0.2, 0, 0.05), 1e-9));
  // a solid cube: m (a^2 + a^2) / 12 about each axis through its centre
  EXPECT_NEAR(l.inertia.x(), 1.0 * 0.02 / 12, 1e-9);
  EXPECT_NEAR(l.inertia.y(), 1.0 * 0.02 / 12, 1e-9);
  EXPECT_NEAR(l.inertia.z(), 1.0 * 0.02 / 12, 1e-9);
  ASSERT_EQ(u.diagnostics.warning_count(), 1) << warnings(u);
  const Diagnostic& d = u.diagnostics.items()[0];
  EXPECT_THAT(d.message, HasSubstr("'cube'"));
  EXPECT_THAT(d.message, HasSubstr("<inertial>"));
  EXPECT_EQ(d.where.file, "block.urdf");
  EXPECT_EQ(d.where.line, 2);
}

TEST(UrdfImport, InertialOriginRotatesTheInertia) {
  // principal moments (1, 2, 3) about axes turned 90 degrees about z: x and y swap
  const std::string text = R"(<robot name="turned">
  <link name="body">
    <inertial>
      <origin xyz="0.1 0.2 0.3" rpy="0 0 1.5707963267948966"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
    </inertial>
  </link>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "turned.urdf", no_environment());
  const LinkSpec& l = u.spec.links.at(0);
  EXPECT_TRUE(l.com.isApprox(Vec3(0.1, 0.2, 0.3), 1e-12));
  const Eigen::Matrix3d I = inertia_tensor(l);
  EXPECT_NEAR(I(0, 0), 2, 1e-9);
  EXPECT_NEAR(I(1, 1), 1, 1e-9);
  EXPECT_NEAR(I(2, 2), 3, 1e-9);
  EXPECT_NEAR(I(0, 1), 0, 1e-9);
}

TEST(UrdfImport, MimicJointKeepsMultiplierAndOffset) {
  const std::string text = R"(<robot name="gripper">
  <link name="palm"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="f1"><inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <link name="f2"><inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <joint name="finger1" type="revolute">
    <parent link="palm"/><child link="f1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
  <joint name="finger2" type="revolute">
    <parent link="palm"/><child link="f2"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="2"/>
    <mimic joint="finger1" multiplier="-2" offset="0.1"/>
  </joint>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "gripper.urdf", no_environment());
  const JointSpec& j = joint_named(u.spec, "finger2");
  EXPECT_EQ(j.mimic, "finger1");
  EXPECT_EQ(j.mimic_multiplier, -2.0);
  EXPECT_EQ(j.mimic_offset, 0.1);
  EXPECT_EQ(j.control, JointSpec::Control::position);
  EXPECT_TRUE(joint_named(u.spec, "finger1").mimic.empty());
}

TEST(UrdfImport, PrismaticJointKeepsItsLimits) {
  const std::string text = R"(<robot name="lifter">
  <link name="base"><inertial><mass value="3"/><inertia ixx="0.03" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.03"/></inertial></link>
  <link name="fork"><inertial><mass value="0.5"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="lift" type="prismatic">
    <parent link="base"/><child link="fork"/>
    <origin xyz="0.3 0 0.1"/>
    <axis xyz="0 0 2"/>
    <limit lower="0.05" upper="0.3" effort="50" velocity="0.5"/>
    <dynamics damping="4" friction="1.5"/>
  </joint>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "lifter.urdf", no_environment());
  const JointSpec& j = joint_named(u.spec, "lift");
  EXPECT_EQ(j.type, JointSpec::Type::prismatic);
  EXPECT_EQ(j.lower, 0.05);
  EXPECT_EQ(j.upper, 0.3);
  EXPECT_EQ(j.max_effort, 50.0);
  EXPECT_EQ(j.max_velocity, 0.5);
  EXPECT_EQ(j.damping, 4.0);
  EXPECT_EQ(j.friction, 1.5);
  EXPECT_TRUE(j.axis.isApprox(Vec3::UnitZ(), 1e-12));  // normalised
  EXPECT_TRUE(j.X_PJ.p.isApprox(Vec3(0.3, 0, 0.1), 1e-12));
  // it holds its place like a servo, starting at the nearest position to 0 within its limits
  EXPECT_EQ(j.control, JointSpec::Control::position);
  EXPECT_EQ(j.initial, 0.05);
  EXPECT_EQ(u.moving_joints, 1);
  // at q = 0.1 the fork is 0.1 m above the joint
  const auto X = link_poses(u.spec, {0.1});
  EXPECT_TRUE(X[1].p.isApprox(Vec3(0.3, 0, 0.2), 1e-12));
}

}  // namespace
}  // namespace rescuesim
