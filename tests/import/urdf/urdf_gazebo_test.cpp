// Gazebo extensions of a URDF read into the RobotSpec: diff-drive and skid-steer plugins (ROS 1
// and ROS 2 element names) become the drive, ray, camera and IMU sensors become SensorSpecs
// with the numbers of their blocks, and what rescuesim does not know is a warning naming it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import/urdf/urdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using urdf_test::joint_named;
using urdf_test::no_environment;
using urdf_test::line_of;
using urdf_test::warnings;

/// A base with two wheels (joints `l` and `r`, collision cylinders of radius 0.05 on y = +-0.15,
/// axes turned to +y) and sensor links laser, cam and imu_link; `gazebo` goes before </robot>.
std::string two_wheeler(const std::string& gazebo) {
  return R"(<robot name="rover">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
    <collision><geometry><box size="0.4 0.25 0.1"/></geometry></collision>
  </link>
  <link name="left_wheel">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
  </link>
  <link name="right_wheel">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
  </link>
  <link name="laser"/>
  <link name="cam"/>
  <link name="imu_link"/>
  <joint name="l" type="continuous">
    <parent link="base"/><child link="left_wheel"/>
    <origin xyz="0 0.15 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="r" type="continuous">
    <parent link="base"/><child link="right_wheel"/>
    <origin xyz="0 -0.15 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="laser_joint" type="fixed"><parent link="base"/><child link="laser"/><origin xyz="0.1 0 0.1"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="base"/><child link="cam"/><origin xyz="0.2 0 0.05"/></joint>
  <joint name="imu_joint" type="fixed"><parent link="base"/><child link="imu_link"/></joint>
)" + gazebo + "</robot>\n";
}

TEST(UrdfImport, GazeboDiffDrivePlugin) {
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>l</leftJoint>
      <rightJoint>r</rightJoint>
      <wheelSeparation>0.4</wheelSeparation>
      <wheelDiameter>0.2</wheelDiameter>
    </plugin>
  </gazebo>
)"),
                                 "rover.urdf", no_environment());
  const DriveSpec& d = u.spec.drive;
  // the plugin's numbers win over the cylinders' radius 0.05 and the 0.3 m between the wheels
  EXPECT_NEAR(d.wheel_radius, 0.1, 1e-12);
  EXPECT_NEAR(d.track_width, 0.4, 1e-12);
  EXPECT_EQ(d.left_wheels, std::vector<std::string>{"l"});
  EXPECT_EQ(d.right_wheels, std::vector<std::string>{"r"});
  EXPECT_EQ(d.left_signs, std::vector<double>{1.0});
  EXPECT_EQ(d.right_signs, std::vector<double>{1.0});
  EXPECT_THAT(u.drive_source, HasSubstr("libgazebo_ros_diff_drive.so"));
  EXPECT_EQ(u.diagnostics.warning_count(), 0) << warnings(u);
  EXPECT_NE(u.spec.find_sensor("odometry"), nullptr);
}

TEST(UrdfImport, GazeboDiffDrivePluginWithRos2Names) {
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so">
      <left_joint>l</left_joint>
      <right_joint>r</right_joint>
      <wheel_separation>0.4</wheel_separation>
      <wheel_diameter>0.2</wheel_diameter>
      <max_wheel_torque>7</max_wheel_torque>
    </plugin>
  </gazebo>
)"),
                                 "rover.urdf", no_environment());
  EXPECT_NEAR(u.spec.drive.wheel_radius, 0.1, 1e-12);
  EXPECT_NEAR(u.spec.drive.track_width, 0.4, 1e-12);
  EXPECT_EQ(u.spec.drive.left_wheels, std::vector<std::string>{"l"});
  EXPECT_EQ(u.spec.drive.right_wheels, std::vector<std::string>{"r"});
  EXPECT_EQ(joint_named(u.spec, "l").max_effort, 7.0);
  EXPECT_EQ(joint_named(u.spec, "r").control, JointSpec::Control::velocity);
  EXPECT_THAT(u.drive_source, HasSubstr("libgazebo_ros_diff_drive.so"));
}

TEST(UrdfImport, DriveGeometryIsDerivedWhenThePluginOmitsIt) {
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>l</leftJoint>
      <rightJoint>r</rightJoint>
    </plugin>
  </gazebo>
)"),
                                 "rover.urdf", no_environment());
  EXPECT_NEAR(u.spec.drive.wheel_radius, 0.05, 1e-9);  // the cylinders
  EXPECT_NEAR(u.spec.drive.track_width, 0.3, 1e-9);    // y = 0.15 and -0.15
}

TEST(UrdfImport, GazeboPluginJointNamesMayBeSurroundedByWhitespace) {
  // Gazebo (sdformat) trims element values, so this layout is common in hand-written URDFs
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo>
    <plugin name="diff" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>
        l
      </leftJoint>
      <rightJoint> r </rightJoint>
      <wheelSeparation> 0.4 </wheelSeparation>
      <wheelDiameter>0.2</wheelDiameter>
    </plugin>
  </gazebo>
)"),
                                 "rover.urdf", no_environment());
  EXPECT_EQ(u.spec.drive.left_wheels, std::vector<std::string>{"l"});
  EXPECT_EQ(u.spec.drive.right_wheels, std::vector<std::string>{"r"});
}

TEST(UrdfImport, GazeboSkidSteerPluginHasTwoWheelsASide) {
  const std::string text = R"(<robot name="skid">
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.05" ixy="0" ixz="0" iyy="0.08" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.5 0.3 0.1"/></geometry></collision>
  </link>
  <link name="lf_wheel"><collision><geometry><cylinder radius="0.06" length="0.04"/></geometry></collision></link>
  <link name="lr_wheel"><collision><geometry><cylinder radius="0.06" length="0.04"/></geometry></collision></link>
  <link name="rf_wheel"><collision><geometry><cylinder radius="0.06" length="0.04"/></geometry></collision></link>
  <link name="rr_wheel"><collision><geometry><cylinder radius="0.06" length="0.04"/></geometry></collision></link>
  <joint name="lf" type="continuous"><parent link="base"/><child link="lf_wheel"/>
    <origin xyz="0.15 0.2 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="lr" type="continuous"><parent link="base"/><child link="lr_wheel"/>
    <origin xyz="-0.15 0.2 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="rf" type="continuous"><parent link="base"/><child link="rf_wheel"/>
    <origin xyz="0.15 -0.2 0" rpy="1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="rr" type="continuous"><parent link="base"/><child link="rr_wheel"/>
    <origin xyz="-0.15 -0.2 0" rpy="1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  <gazebo>
    <plugin name="skid" filename="libgazebo_ros_skid_steer_drive.so">
      <leftFrontJoint>lf</leftFrontJoint>
      <rightFrontJoint>rf</rightFrontJoint>
      <leftRearJoint>lr</leftRearJoint>
      <rightRearJoint>rr</rightRearJoint>
      <wheelSeparation>0.4</wheelSeparation>
      <wheelDiameter>0.12</wheelDiameter>
    </plugin>
  </gazebo>
</robot>
)";
  const UrdfRobot u = parse_urdf(text, "skid.urdf", no_environment());
  const DriveSpec& d = u.spec.drive;
  EXPECT_EQ(d.left_wheels, (std::vector<std::string>{"lf", "lr"}));
  EXPECT_EQ(d.right_wheels, (std::vector<std::string>{"rf", "rr"}));
  EXPECT_NEAR(d.wheel_radius, 0.06, 1e-12);
  EXPECT_NEAR(d.track_width, 0.4, 1e-12);
  EXPECT_EQ(d.track_multiplier, 1.25);  // more than one wheel a side skids when turning
  // left axes: z turned by roll -90 degrees about x is (0, -sin(-90), cos(-90)) = +y, forward;
  // right axes: z turned by roll +90 degrees is (0, -1, 0) = -y, so a positive speed rolls back
  EXPECT_EQ(d.left_signs, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(d.right_signs, (std::vector<double>{-1.0, -1.0}));
  EXPECT_THAT(u.drive_source, HasSubstr("libgazebo_ros_skid_steer_drive.so"));
  // the wheel links have no <inertial>: their mass comes from the cylinders, with warnings
  EXPECT_THAT(warnings(u), HasSubstr("lf_wheel"));
}

TEST(UrdfImport, GazeboRaySensorBecomesALidar) {
  const std::string text = two_wheeler(R"(  <gazebo reference="laser">
    <sensor type="ray" name="lds">
      <update_rate>5</update_rate>
      <ray>
        <scan><horizontal><samples>360</samples><min_angle>-3.14</min_angle><max_angle>3.14</max_angle></horizontal></scan>
        <range><min>0.12</min><max>3.5</max></range>
      </ray>
    </sensor>
  </gazebo>
)");
  const UrdfRobot u = parse_urdf(text, "rover.urdf", no_environment());
  const SensorSpec* s = u.spec.find_sensor("lds");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->type, SensorSpec::Type::lidar);
  EXPECT_EQ(s->link, "laser");
  EXPECT_EQ(s->frame_id, "laser");
  EXPECT_EQ(s->rate, 5.0);
  EXPECT_EQ(s->lidar.samples, 360);
  EXPECT_EQ(s->lidar.min_angle, -3.14);
  EXPECT_EQ(s->lidar.max_angle, 3.14);
  EXPECT_EQ(s->lidar.min_range, 0.12);
  EXPECT_EQ(s->lidar.max_range, 3.5);
  EXPECT_EQ(s->lidar.layers, 1);
  EXPECT_EQ(s->topic, "scan");  // the robot's first lidar
  EXPECT_EQ(u.diagnostics.warning_count(), 0) << warnings(u);
}

TEST(UrdfImport, GazeboCameraAndImuSensors) {
  const std::string text = two_wheeler(R"(  <gazebo reference="cam">
    <sensor type="camera" name="front_camera">
      <update_rate>30</update_rate>
      <camera>
        <horizontal_fov>1.047</horizontal_fov>
        <image><width>640</width><height>480</height></image>
        <clip><near>0.1</near><far>50</far></clip>
      </camera>
    </sensor>
  </gazebo>
  <gazebo reference="imu_link">
    <sensor type="imu" name="imu">
      <update_rate>200</update_rate>
    </sensor>
  </gazebo>
)");
  const UrdfRobot u = parse_urdf(text, "rover.urdf", no_environment());
  const SensorSpec* cam = u.spec.find_sensor("front_camera");
  ASSERT_NE(cam, nullptr);
  EXPECT_EQ(cam->type, SensorSpec::Type::color_camera);
  EXPECT_EQ(cam->link, "cam");
  EXPECT_EQ(cam->rate, 30.0);
  EXPECT_EQ(cam->camera.hfov, 1.047);
  EXPECT_EQ(cam->camera.width, 640);
  EXPECT_EQ(cam->camera.height, 480);
  EXPECT_EQ(cam->camera.near_clip, 0.1);
  EXPECT_EQ(cam->camera.far_clip, 50.0);
  const SensorSpec* imu = u.spec.find_sensor("imu");
  ASSERT_NE(imu, nullptr);
  EXPECT_EQ(imu->type, SensorSpec::Type::imu);
  EXPECT_EQ(imu->link, "imu_link");
  EXPECT_EQ(imu->rate, 200.0);
  EXPECT_EQ(imu->topic, "imu");
  EXPECT_EQ(u.diagnostics.warning_count(), 0) << warnings(u);
}

TEST(UrdfImport, UnknownPluginAndSensorTypeAreWarnings) {
  const std::string text = two_wheeler(R"(  <gazebo>
    <plugin name="magic" filename="libmagic_wand.so"/>
  </gazebo>
  <gazebo reference="base">
    <sensor type="gps" name="gps0"><update_rate>1</update_rate></sensor>
  </gazebo>
)");
  const UrdfRobot u = parse_urdf(text, "rover.urdf", no_environment());
  ASSERT_EQ(u.diagnostics.warning_count(), 2) << warnings(u);
  EXPECT_EQ(u.diagnostics.error_count(), 0);
  bool plugin = false, sensor = false;
  for (const auto& d : u.diagnostics.items()) {
    EXPECT_EQ(d.where.file, "rover.urdf");
    if (d.message.find("libmagic_wand.so") != std::string::npos) {
      plugin = true;
      EXPECT_EQ(d.where.line, line_of(text, "libmagic_wand.so"));
    }
    if (d.message.find("gps") != std::string::npos) {
      sensor = true;
      EXPECT_THAT(d.message, HasSubstr("gps0"));
      EXPECT_EQ(d.where.line, line_of(text, "type=\"gps\""));
    }
  }
  EXPECT_TRUE(plugin) << warnings(u);
  EXPECT_TRUE(sensor) << warnings(u);
  EXPECT_EQ(u.spec.find_sensor("gps0"), nullptr);
  EXPECT_EQ(u.spec.links.size(), 6u);  // and the robot is all there
}

TEST(UrdfImport, GazeboMuSetsTheLinksContactFriction) {
  // a slippery caster-like base (mu 0.1) and wheels whose friction differs along their y axis;
  // the drive plugin keeps the wheels' own friction instead of the default rubber
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo reference="base"><mu1>0.1</mu1><mu2>0.1</mu2></gazebo>
  <gazebo reference="left_wheel"><mu1>1.2</mu1><mu2>0.6</mu2></gazebo>
  <gazebo><plugin filename="libgazebo_ros_diff_drive.so"><leftJoint>l</leftJoint><rightJoint>r</rightJoint></plugin></gazebo>
)"),
                                 "rover.urdf", no_environment());
  const RobotSpec& r = u.spec;
  auto material = [&](const std::string& link) {
    const LinkSpec& l = r.links[static_cast<std::size_t>(r.link_index(link))];
    for (const auto& sh : l.shapes) {
      if (sh.collides) return sh.material;
    }
    return std::string();
  };
  auto friction = [&](const std::string& name) {
    for (const auto& m : r.materials) {
      if (m.name == name) return m.friction;
    }
    return -1.0;
  };
  EXPECT_EQ(material("base"), "rover/base_contact");
  EXPECT_DOUBLE_EQ(friction("rover/base_contact"), 0.1);
  EXPECT_EQ(r.links[0].friction_scale, Vec3::Ones());
  EXPECT_DOUBLE_EQ(friction(material("left_wheel")), 1.2);
  EXPECT_EQ(r.links[static_cast<std::size_t>(r.link_index("left_wheel"))].friction_scale, Vec3(1.0, 0.5, 1.0));
  // the wheel without <mu1> grips like rubber
  EXPECT_EQ(material("right_wheel"), "robot_wheel");
  EXPECT_EQ(u.diagnostics.warning_count(), 0) << warnings(u);
}

TEST(UrdfImport, DiffDrivePluginSidesComeFromWhereTheWheelsAre) {
  // URDFs written for ROS 1's gazebo_ros_diff_drive often name the right wheel leftJoint (that
  // plugin turns the wrong way round); joint l is at y = +0.15 (left), r at y = -0.15
  const UrdfRobot u = parse_urdf(two_wheeler(R"(  <gazebo><plugin filename="libgazebo_ros_diff_drive.so">
    <leftJoint>r</leftJoint><rightJoint>l</rightJoint><wheelSeparation>0.3</wheelSeparation><wheelDiameter>0.1</wheelDiameter>
  </plugin></gazebo>
)"),
                                 "rover.urdf", no_environment());
  EXPECT_EQ(u.spec.drive.left_wheels, std::vector<std::string>{"l"});
  EXPECT_EQ(u.spec.drive.right_wheels, std::vector<std::string>{"r"});
  ASSERT_EQ(u.diagnostics.warning_count(), 1) << warnings(u);
  EXPECT_THAT(u.diagnostics.items()[0].message, HasSubstr("left ones"));
  // a scenario's drive: naming them the wrong way round is an error, not a guess
  RobotSpec spec = u.spec;
  EXPECT_THROW(configure_diff_drive(spec, {"r"}, {"l"}, 0, 0.3, {}), Error);
}

}  // namespace
}  // namespace rescuesim
