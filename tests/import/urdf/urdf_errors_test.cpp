// Bad URDF input, one class per test: each is an Error whose text names the file, the line
// (counted by hand in the inline text) and the element, and says what was expected; none
// crashes. Meshes named by the URDFs are written by the tests into a temporary folder.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "import/urdf/urdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using urdf_test::error_of;
using urdf_test::TempDir;

/// Options that find nothing outside `dir` (no ROS or Gazebo environment).
UrdfOptions isolated(const std::filesystem::path& dir) {
  UrdfOptions o;
  o.resolver = ResourceResolver({dir}, false);
  return o;
}

/// The Error of parsing `text` as "bad.urdf".
Error parse_error(const std::string& text) {
  TempDir dir;
  return error_of([&] { parse_urdf(text, "bad.urdf", isolated(dir.path())); });
}

/// Checks that an Error is located at file:line and mentions `element`.
void expect_at(const Error& e, const std::string& file, int line, const std::string& element) {
  EXPECT_EQ(e.where().file, file) << e.what();
  EXPECT_EQ(e.where().line, line) << e.what();
  EXPECT_THAT(e.what(), HasSubstr(file + ":" + std::to_string(line) + ":"));
  EXPECT_THAT(e.what(), HasSubstr(element));
}

const char* kInertia = R"(<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>)";

// the document

TEST(UrdfErrors, MalformedXmlNamesTheLineAndTheUnclosedElement) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="a">
    <visual>
  </link>
</robot>
)");
  EXPECT_EQ(e.where().file, "bad.urdf");
  EXPECT_THAT(e.what(), HasSubstr("malformed XML"));
  // <visual>, opened on line 3, is closed by </link>
  EXPECT_EQ(e.where().line, 3) << e.what();
  EXPECT_THAT(e.what(), HasSubstr("bad.urdf:3:"));
  EXPECT_THAT(e.what(), HasSubstr("name=visual"));
}

TEST(UrdfErrors, TruncatedFileIsMalformed) {
  const Error e = parse_error("<robot name=\"r\">\n  <link name=\"a\"/>\n");
  EXPECT_EQ(e.where().file, "bad.urdf");
  EXPECT_GT(e.where().line, 0) << e.what();
  EXPECT_THAT(e.what(), HasSubstr("malformed XML"));
}

TEST(UrdfErrors, RootElementMustBeRobot) {
  const Error sdf = parse_error(R"(<?xml version="1.0"?>
<sdf version="1.6">
  <model name="m"/>
</sdf>
)");
  expect_at(sdf, "bad.urdf", 2, "<sdf>");
  EXPECT_THAT(sdf.what(), HasSubstr("root element must be <robot>"));
  EXPECT_THAT(sdf.what(), HasSubstr("SDF"));
  const Error model = parse_error("<model name=\"m\"/>\n");
  expect_at(model, "bad.urdf", 1, "<model>");
  EXPECT_THAT(model.what(), HasSubstr("<robot>"));
}

TEST(UrdfErrors, XacroMacroIsRefusedWithHowToExpandIt) {
  const Error e = parse_error(R"(<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="radius" value="0.1"/>
  <xacro:macro name="wheel" params="side">
    <link name="wheel"/>
  </xacro:macro>
  <link name="base"/>
</robot>
)");
  expect_at(e, "bad.urdf", 4, "<xacro:macro>");
  EXPECT_THAT(e.what(), HasSubstr("xacro"));
  EXPECT_THAT(e.what(), HasSubstr("expand"));
  EXPECT_THAT(e.what(), HasSubstr("xacro robot.urdf.xacro > robot.urdf"));
}

TEST(UrdfErrors, PlaceholderLeftInAnAttribute) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="base">
    <visual>
      <geometry><box size="${foo} 1 1"/></geometry>
    </visual>
  </link>
</robot>
)");
  expect_at(e, "bad.urdf", 4, "<box>");
  EXPECT_THAT(e.what(), HasSubstr("${foo}"));
  EXPECT_THAT(e.what(), HasSubstr("xacro"));
}

TEST(UrdfErrors, MissingUrdfFileIsNamed) {
  TempDir dir;
  const auto file = dir.path() / "nowhere.urdf";
  const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
  EXPECT_THAT(e.what(), HasSubstr(file.string()));
  EXPECT_THAT(e.what(), HasSubstr("cannot read the URDF"));
}

// meshes

/// A robot of one link (line 2) whose collision (line 4) is the mesh at `uri`.
std::string mesh_robot(const std::string& uri, const std::string& scale = "1 1 1") {
  return R"(<robot name="r">
  <link name="base">
    <inertial><mass value="1"/>)" +
         std::string(kInertia) + R"(</inertial>
    <collision><geometry><mesh filename=")" + uri + R"(" scale=")" + scale + R"("/></geometry></collision>
  </link>
</robot>
)";
}

TEST(UrdfErrors, MissingMeshFileNamesTheUriAndWhereItLooked) {
  TempDir dir;
  const auto file = dir.write("robot/robot.urdf", mesh_robot("meshes/missing.stl"));
  const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
  // located at the <mesh> element (line 4), quoting it
  expect_at(e, file.string(), 4, "<mesh filename=\"meshes/missing.stl\">");
  EXPECT_THAT(e.what(), HasSubstr("'meshes/missing.stl'"));
  EXPECT_THAT(e.what(), HasSubstr((dir.path() / "robot" / "meshes" / "missing.stl").string()));
}

TEST(UrdfErrors, UnresolvablePackageListsEveryPlaceSearched) {
  TempDir dir;
  const auto file = dir.write("robot.urdf", mesh_robot("package://nopkg/meshes/m.stl"));
  urdf_test::ScopedEnv ros("ROS_PACKAGE_PATH", (dir.path() / "ros_ws").string());
  urdf_test::ScopedEnv ament("AMENT_PREFIX_PATH", (dir.path() / "install").string());
  UrdfOptions o;
  o.resolver = ResourceResolver({dir.path() / "first", dir.path() / "second"}, true);
  const Error e = error_of([&] { load_urdf(file, o); });
  expect_at(e, file.string(), 4, "package://nopkg/meshes/m.stl");
  for (const auto& place : {dir.path() / "first/nopkg/meshes/m.stl", dir.path() / "second/nopkg/meshes/m.stl",
                            dir.path() / "ros_ws/nopkg/meshes/m.stl", dir.path() / "install/share/nopkg/meshes/m.stl"}) {
    EXPECT_THAT(e.what(), HasSubstr(place.string()));
  }
  EXPECT_THAT(e.what(), HasSubstr("ROS_PACKAGE_PATH"));  // and how to fix it
}

TEST(UrdfErrors, UnresolvablePackageWithNowhereToLook) {
  TempDir dir;
  const auto file = dir.write("robot.urdf", mesh_robot("package://nopkg/meshes/m.stl"));
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  const Error e = error_of([&] { load_urdf(file, o); });
  EXPECT_THAT(e.what(), HasSubstr("package://nopkg/meshes/m.stl"));
  EXPECT_THAT(e.what(), HasSubstr("nowhere"));
}

TEST(UrdfErrors, GarbageMeshFilesAreRefusedNamingTheFile) {
  TempDir dir;
  std::mt19937 rng(20240611);
  for (const std::string name : {"garbage.stl", "garbage.dae"}) {
    for (int round = 0; round < 5; ++round) {
      std::string bytes(300 + 37 * round, '\0');
      for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
      const auto mesh = dir.write(name, bytes);
      const auto file = dir.write("robot.urdf", mesh_robot(name));
      const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
      EXPECT_THAT(e.what(), HasSubstr(mesh.string())) << name << " round " << round;
      EXPECT_EQ(e.where().file, file.string()) << e.what();
      EXPECT_EQ(e.where().line, 4) << e.what();
    }
  }
}

TEST(UrdfErrors, StlHeaderClaimingTooManyTrianglesIsRefusedBeforeReading) {
  TempDir dir;
  // a sparse file of the size 2,000,001 triangles need, all zeros after the header
  std::string header(80, ' ');
  urdf_test::put(header, std::uint32_t{2000001});
  const auto mesh = dir.write("huge.stl", header);
  std::filesystem::resize_file(mesh, 84 + 50ull * 2000001);
  const auto file = dir.write("robot.urdf", mesh_robot("huge.stl"));
  const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
  EXPECT_THAT(e.what(), HasSubstr("2000001"));
  EXPECT_THAT(e.what(), HasSubstr(mesh.string()));
  expect_at(e, file.string(), 4, "huge.stl");
}

TEST(UrdfErrors, ZeroMeshScaleIsRefused) {
  TempDir dir;
  dir.write("cube.stl", urdf_test::binary_stl(urdf_test::box_mesh(Vec3::Constant(-0.05), Vec3::Constant(0.05))));
  const auto file = dir.write("robot.urdf", mesh_robot("cube.stl", "0.001 0 0.001"));
  const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
  expect_at(e, file.string(), 4, "cube.stl");
  EXPECT_THAT(e.what(), HasSubstr("scale"));
}

TEST(UrdfErrors, FlatCollisionMeshNamesTheUrdfAndTheMesh) {
  // a single square (two triangles in z = 0) encloses no volume, so it has no convex hull
  TempDir dir;
  TriangleMesh square;
  square.vertices = {{0, 0, 0}, {0.2, 0, 0}, {0.2, 0.2, 0}, {0, 0.2, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  const auto mesh = dir.write("plate.stl", urdf_test::binary_stl(square));
  const auto file = dir.write("robot.urdf", mesh_robot("plate.stl"));
  const Error e = error_of([&] { load_urdf(file, isolated(dir.path())); });
  expect_at(e, file.string(), 4, "plate.stl");
  EXPECT_THAT(e.what(), HasSubstr("plane"));
}

TEST(UrdfErrors, MalformedNumbersAndShapesNameTheirLine) {
  // what urdfdom reads (origins, shapes, colours) is wrong in one element on line 4; urdfdom 3
  // logs an error and drops the whole <visual> or <collision>, so the importer must say so
  struct Case {
    std::string element, tag;
  };
  const std::vector<Case> cases = {
      {R"(<visual><origin xyz="1 2"/><geometry><box size="1 1 1"/></geometry></visual>)", "<origin>"},
      {R"(<visual><geometry><box size="1 1"/></geometry></visual>)", "<box>"},
      {R"(<visual><geometry><cylinder radius="wide" length="1"/></geometry></visual>)", "<cylinder>"},
      {R"(<visual><geometry><sphere/></geometry></visual>)", "<sphere>"},
      {R"(<visual><geometry><box size="1 1 1"/></geometry><material name="m"><color rgba="1 0 0"/></material></visual>)", "<color>"},
      {R"(<collision><origin xyz="0 0 0"/></collision>)", "<collision>"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.element);
    const Error e = parse_error(R"(<robot name="r">
  <link name="base">
    <inertial><mass value="1"/>)" + std::string(kInertia) + R"(</inertial>
    )" + c.element + R"(
  </link>
</robot>
)");
    expect_at(e, "bad.urdf", 4, c.tag);
  }
}

// inertials

/// A link (line 2) whose <mass> is on line 4 and <inertia> on line 5.
std::string inertial_robot(const std::string& mass, const std::string& inertia) {
  return R"(<robot name="r">
  <link name="body">
    <inertial>
      <mass value=")" +
         mass + R"("/>
      <inertia )" + inertia + R"(/>
    </inertial>
  </link>
</robot>
)";
}

const char* kGoodInertia = R"(ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01")";

TEST(UrdfErrors, NegativeMass) {
  const Error e = parse_error(inertial_robot("-2.5", kGoodInertia));
  expect_at(e, "bad.urdf", 4, "<mass>");
  EXPECT_THAT(e.what(), HasSubstr("-2.5"));
}

TEST(UrdfErrors, MassThatIsNotANumber) {
  const Error e = parse_error(inertial_robot("heavy", kGoodInertia));
  expect_at(e, "bad.urdf", 4, "<mass>");
  EXPECT_THAT(e.what(), HasSubstr("'heavy'"));
}

TEST(UrdfErrors, InertiaMissingAnAttribute) {
  // urdfdom 3 logs an error and drops the whole <inertial> when one of the six is missing, which
  // would leave the link without its 1 kg
  const Error e = parse_error(inertial_robot("1", R"(ixx="0.01" iyy="0.01" izz="0.01")"));
  expect_at(e, "bad.urdf", 5, "<inertia>");
  EXPECT_THAT(e.what(), HasSubstr("ixy"));
}

// the tree of links and joints

TEST(UrdfErrors, LinkWithTwoParents) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>
  <joint name="j3" type="fixed"><parent link="b"/><child link="c"/></joint>
</robot>
)");
  expect_at(e, "bad.urdf", 7, "<joint name=\"j3\">");
  EXPECT_THAT(e.what(), HasSubstr("'c' has two parents"));
  EXPECT_THAT(e.what(), HasSubstr("'j2'"));
}

TEST(UrdfErrors, JointCycleWithNoRoot) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>
)");
  expect_at(e, "bad.urdf", 1, "<robot>");
  EXPECT_THAT(e.what(), HasSubstr("loop"));
}

TEST(UrdfErrors, JointCycleBesideARoot) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="root"/>
  <link name="a"/>
  <link name="b"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>
)");
  expect_at(e, "bad.urdf", 3, "<link name=\"a\">");
  EXPECT_THAT(e.what(), HasSubstr("loop"));
}

TEST(UrdfErrors, TwoRoots) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="a"/>
  <link name="b"/>
</robot>
)");
  expect_at(e, "bad.urdf", 3, "<link name=\"b\">");
  EXPECT_THAT(e.what(), HasSubstr("single root"));
}

/// Two links joined by a joint (line 4) of `type`, with `inside` in the joint element.
std::string joint_robot(const std::string& type, const std::string& inside = "") {
  return R"(<robot name="r">
  <link name="a"><inertial><mass value="1"/>)" + std::string(kInertia) + R"(</inertial></link>
  <link name="b"><inertial><mass value="1"/>)" + std::string(kInertia) + R"(</inertial></link>
  <joint name="j" type=")" + type + R"(">
    <parent link="a"/>
    <child link="b"/>)" + inside + R"(
  </joint>
</robot>
)";
}

TEST(UrdfErrors, UnknownJointType) {
  const Error e = parse_error(joint_robot("ball"));
  expect_at(e, "bad.urdf", 4, "<joint name=\"j\">");
  EXPECT_THAT(e.what(), HasSubstr("unknown joint type 'ball'"));
  EXPECT_THAT(e.what(), HasSubstr("revolute, continuous, prismatic or fixed"));
}

TEST(UrdfErrors, FloatingAndPlanarJointsAreRefused) {
  for (const std::string type : {"floating", "planar"}) {
    const Error e = parse_error(joint_robot(type));
    expect_at(e, "bad.urdf", 4, "<joint name=\"j\">");
    EXPECT_THAT(e.what(), HasSubstr("'" + type + "' is not supported"));
    EXPECT_THAT(e.what(), HasSubstr("fixed joint"));  // what to do instead
  }
}

TEST(UrdfErrors, JointNamingAnUndefinedLink) {
  const Error e = parse_error(R"(<robot name="r">
  <link name="a"/>
  <joint name="j" type="fixed">
    <parent link="a"/>
    <child link="ghost"/>
  </joint>
</robot>
)");
  expect_at(e, "bad.urdf", 5, "<child>");
  EXPECT_THAT(e.what(), HasSubstr("'ghost' is not defined"));
}

TEST(UrdfErrors, RevoluteWithoutLimit) {
  const Error e = parse_error(joint_robot("revolute", "\n    <axis xyz=\"0 0 1\"/>"));
  expect_at(e, "bad.urdf", 4, "<joint name=\"j\">");
  EXPECT_THAT(e.what(), HasSubstr("<limit"));
}

TEST(UrdfErrors, LimitsTheWrongWayRound) {
  const Error e = parse_error(joint_robot("prismatic", "\n    <limit lower=\"0.5\" upper=\"0.1\" effort=\"1\" velocity=\"1\"/>"));
  expect_at(e, "bad.urdf", 4, "<joint name=\"j\">");
  EXPECT_THAT(e.what(), HasSubstr("lower"));
}

TEST(UrdfErrors, ZeroAxis) {
  const Error e = parse_error(joint_robot("continuous", "\n    <axis xyz=\"0 0 0\"/>"));
  expect_at(e, "bad.urdf", 4, "<joint name=\"j\">");
  EXPECT_THAT(e.what(), HasSubstr("zero <axis>"));
}

TEST(UrdfErrors, NonPositiveShapeSizes) {
  // a box with a negative side or a cylinder of radius 0 is no solid at all
  for (const std::string geometry :
       {R"(<box size="0.1 -0.2 0.1"/>)", R"(<cylinder radius="0" length="0.1"/>)", R"(<sphere radius="-1"/>)"}) {
    const Error e = parse_error(R"(<robot name="r">
  <link name="base">
    <inertial><mass value="1"/>)" + std::string(kInertia) + R"(</inertial>
    <collision><geometry>)" + geometry + R"(</geometry></collision>
  </link>
</robot>
)");
    EXPECT_EQ(e.where().file, "bad.urdf") << geometry;
    EXPECT_GE(e.where().line, 2) << geometry << ": " << e.what();
  }
}

// Gazebo extensions

/// A base and two wheels on joints l and r; `gazebo` starts on line 11.
std::string gazebo_robot(const std::string& gazebo) {
  return R"(<robot name="r">
  <link name="base"><inertial><mass value="1"/>)" + std::string(kInertia) + R"(</inertial></link>
  <link name="lw"><collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <link name="rw"><collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="l" type="continuous">
    <parent link="base"/><child link="lw"/><origin xyz="0 0.1 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="r" type="continuous">
    <parent link="base"/><child link="rw"/><origin xyz="0 -0.1 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/>
  </joint>
)" + gazebo + "</robot>\n";
}

TEST(UrdfErrors, DrivePluginNamingAMissingJoint) {
  const Error e = parse_error(gazebo_robot(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>l</leftJoint>
      <rightJoint>right_wheel_joint</rightJoint>
    </plugin>
  </gazebo>
)"));
  expect_at(e, "bad.urdf", 12, "<plugin name=\"diff\">");
  EXPECT_THAT(e.what(), HasSubstr("'right_wheel_joint' is not a joint"));
  EXPECT_THAT(e.what(), HasSubstr("joints: l, r"));
}

TEST(UrdfErrors, DrivePluginWithoutWheels) {
  const Error e = parse_error(gazebo_robot(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so"/>
  </gazebo>
)"));
  expect_at(e, "bad.urdf", 12, "<plugin name=\"diff\">");
  EXPECT_THAT(e.what(), HasSubstr("each side"));
}

TEST(UrdfErrors, RaySensorWithOneSample) {
  const Error e = parse_error(gazebo_robot(R"(  <gazebo reference="base">
    <sensor type="ray" name="lidar">
      <ray><scan><horizontal><samples>1</samples></horizontal></scan></ray>
    </sensor>
  </gazebo>
)"));
  // the element at fault is <samples>, on the line below the sensor's
  expect_at(e, "bad.urdf", 13, "<samples>");
  EXPECT_THAT(e.what(), HasSubstr("sensor 'lidar'"));
}

TEST(UrdfErrors, SensorCountsTooBigForAnIntAreRefused) {
  // beam, layer and pixel counts beyond an int must be refused, not converted (converting an
  // out-of-range double to int is undefined behaviour; the fuzz build's UBSan stops on it)
  for (const std::string sensor : {
           R"(<sensor type="ray" name="s"><ray><scan><horizontal><samples>1e12</samples></horizontal></scan></ray></sensor>)",
           R"(<sensor type="ray" name="s"><ray><scan><vertical><samples>1e10</samples></vertical></scan></ray></sensor>)",
           R"(<sensor type="camera" name="s"><camera><image><width>1e12</width><height>480</height></image></camera></sensor>)"}) {
    SCOPED_TRACE(sensor);
    const Error e = parse_error(gazebo_robot("  <gazebo reference=\"base\">\n    " + sensor + "\n  </gazebo>\n"));
    EXPECT_EQ(e.where().file, "bad.urdf");
    EXPECT_GE(e.where().line, 12) << e.what();
  }
}

TEST(UrdfErrors, SensorNumberThatIsNotANumber) {
  const Error e = parse_error(gazebo_robot(R"(  <gazebo reference="base">
    <sensor type="imu" name="imu">
      <update_rate>fast</update_rate>
    </sensor>
  </gazebo>
)"));
  expect_at(e, "bad.urdf", 13, "<update_rate>");
  EXPECT_THAT(e.what(), HasSubstr("'fast'"));
}

}  // namespace
}  // namespace rescuesim
