#include <gtest/gtest.h>

#include <string>

#include "msgs/serialize.h"
#include "samples.h"

namespace rescuesim::msg {
namespace {

// The MD5 sums ROS 1 Noetic publishes for these types. Each value was read on this project's
// Debian 12 machine from two independent sources, which agree: the generated roscpp headers
// (`grep -A5 'struct MD5Sum<' /usr/include/<pkg>/<Type>.h`, packages libsensor-msgs-dev,
// libgeometry-msgs-dev, libnav-msgs-dev, libtf2-msgs-dev, libros-rosgraph-msgs-dev,
// libstd-msgs-dev) and the Python message classes (`rosmsg md5 <pkg>/<Type>`).
const std::pair<const char*, const char*> kRosMd5[] = {
    {"rosgraph_msgs/Clock", "a9c97c1d230cfc112e270351a944ee47"},
    {"sensor_msgs/LaserScan", "90c7ef2dc6895d81024acba2ac42f369"},
    {"sensor_msgs/Range", "c005c34273dc426c67a020a87bc24148"},
    {"sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2"},
    {"geometry_msgs/Twist", "9f195f881246fdfa2798d1d3eebca84a"},
    {"nav_msgs/Odometry", "cd5e73d190d741a2f92e81eda573aca7"},
    {"sensor_msgs/JointState", "3066dcd76a6cfaef579bd0f34173e9fd"},
    {"tf2_msgs/TFMessage", "94810edda583a504dfda3829e70d7eec"},
    {"geometry_msgs/PoseStamped", "d3812c3cbc69362b77dc0b19b345f8f5"},
    {"nav_msgs/Path", "6227e2b7e9cce15051f669a5e197bbf7"},
    {"nav_msgs/OccupancyGrid", "3381f2d731d4076ec5c71b0759edbe4e"},
    {"std_msgs/Float64MultiArray", "4b7d974086d4060e7db4613a7e6c3ba4"},
    {"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1"},
    {"std_msgs/Bool", "8b94c1b53db61fb6aed406028ad6332a"},
    {"sensor_msgs/Image", "060021388200f6f0f447d0fcd9c64743"},
    {"sensor_msgs/CameraInfo", "c9a58c1b0b154e0e6da7578cb991d214"},
    {"sensor_msgs/PointCloud2", "1158d486dd51d683ce2f1be655c3c181"},
};

TEST(TypeSupport, Ros1Md5MatchesRos) {
  for (const auto& [name, md5] : kRosMd5) {
    const TypeSupport* t = find_type(name);
    ASSERT_NE(t, nullptr) << name;
    EXPECT_EQ(t->ros1_md5, md5) << name << "\n" << t->ros1_definition;
  }
}

// The same sources (generated headers under /usr/include) for the dependency types, checked
// through ros1_md5_of on hand-written texts with comments, blank lines and spaced constants,
// which genmsg ignores.
std::string text_of(std::string_view type) {
  if (type == "std_msgs/Header") return "# a comment line\nuint32 seq\n\ntime stamp   # trailing comment\nstring frame_id\n";
  if (type == "geometry_msgs/Point") return "float64 x\nfloat64 y\nfloat64 z";
  if (type == "geometry_msgs/Vector3") return "float64 x\nfloat64 y\nfloat64 z";
  if (type == "geometry_msgs/Quaternion") return "float64 x\nfloat64 y\nfloat64 z\nfloat64 w";
  if (type == "geometry_msgs/Pose") return "Point position\nQuaternion orientation";
  if (type == "geometry_msgs/Transform") return "Vector3 translation\nQuaternion rotation";
  ADD_FAILURE() << "unexpected dependency " << type;
  return "";
}

TEST(Ros1Md5Of, DependencyTypesMatchRos) {
  EXPECT_EQ(ros1_md5_of(text_of("std_msgs/Header"), "std_msgs", text_of), "2176decaecbce78abc3b96ef049fabed");
  EXPECT_EQ(ros1_md5_of(text_of("geometry_msgs/Quaternion"), "geometry_msgs", text_of), "a779879fadf0160734f906b8c19c7004");
  EXPECT_EQ(ros1_md5_of(text_of("geometry_msgs/Vector3"), "geometry_msgs", text_of), "4a842b65f413084dc2b10fb484ea7f17");
  EXPECT_EQ(ros1_md5_of(text_of("geometry_msgs/Pose"), "geometry_msgs", text_of), "e45d45a5a1ce597b249e23fb30fc871f");
  EXPECT_EQ(ros1_md5_of("Header header\nstring child_frame_id\nTransform transform", "geometry_msgs", text_of),
            "b5764a33bfeb3588febc2682852579b0");
  // the same with the qualified names a .msg may also use
  EXPECT_EQ(ros1_md5_of("std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform",
                        "geometry_msgs", text_of),
            "b5764a33bfeb3588febc2682852579b0");
}

TEST(Ros1Md5Of, ConstantsComeFirstWhateverTheirPlaceAndSpacing) {
  // sensor_msgs/PointField (268eacb2962780ceac86cbd17e328150 in /usr/include/sensor_msgs/PointField.h),
  // written with the constants after the fields and spaces around '='
  const char* text =
      "string name      # field name\nuint32 offset\nuint8  datatype\nuint32 count\n"
      "uint8 INT8    = 1\nuint8 UINT8   = 2\nuint8 INT16   = 3\nuint8 UINT16  = 4\n"
      "uint8 INT32   = 5\nuint8 UINT32  = 6\nuint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\n";
  EXPECT_EQ(ros1_md5_of(text, "sensor_msgs", text_of), "268eacb2962780ceac86cbd17e328150");
}

TEST(Ros1Md5Of, MessageArraysDropTheirSuffix) {
  // nav_msgs/Path's poses is geometry_msgs/PoseStamped[]: the md5 line is "<md5> poses"
  const TypeSupport* path = find_type("nav_msgs/Path");
  ASSERT_NE(path, nullptr);
  EXPECT_EQ(path->ros1_md5, "6227e2b7e9cce15051f669a5e197bbf7");
}

TEST(TypeSupport, OwnContactsTypeMd5MatchesGenmsg) {
  // rescuesim_msgs/Contacts ("Header header\nstring[] touching") has no published constant:
  // this value was computed on this machine by Debian's python3-genmsg
  // (genmsg.gentools.compute_md5 on a Contacts.msg with that text and std_msgs/Header.msg)
  const TypeSupport* t = find_type("rescuesim_msgs/Contacts");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->ros1_md5, "a66b1a9c2e2dfdbff6ebd2978e95421e");
}

TEST(TypeSupport, TableFollowsTheVariant) {
  const auto& types = all_types();
  ASSERT_EQ(types.size(), std::variant_size_v<Message>);
  const auto samples = test::all_samples();
  for (std::size_t i = 0; i < types.size(); ++i) {
    EXPECT_EQ(types[i].variant_index, i);
    EXPECT_EQ(types[i].ros1_name, type_name(samples[i]));
    EXPECT_EQ(&type_of(samples[i]), &types[i]);
    EXPECT_EQ(types[i].ros1_md5.size(), 32u);
  }
}

TEST(TypeSupport, NamesInEveryConvention) {
  const TypeSupport* scan = find_type("sensor_msgs/LaserScan");
  ASSERT_NE(scan, nullptr);
  EXPECT_EQ(find_type("sensor_msgs/msg/LaserScan"), scan);
  EXPECT_EQ(scan->ros2_name, "sensor_msgs/msg/LaserScan");
  EXPECT_EQ(scan->dds_name, "sensor_msgs::msg::dds_::LaserScan_");
  EXPECT_EQ(find_type("rosgraph_msgs/msg/Clock")->dds_name, "rosgraph_msgs::msg::dds_::Clock_");
  EXPECT_EQ(find_type("rescuesim_msgs/msg/Contacts")->dds_name, "rescuesim_msgs::msg::dds_::Contacts_");
  EXPECT_EQ(find_type("std_msgs/msg/String")->dds_name, "std_msgs::msg::dds_::String_");
  EXPECT_EQ(find_type("sensor_msgs/Foo"), nullptr);
  EXPECT_EQ(find_type("sensor_msgs::msg::dds_::LaserScan_"), nullptr);
  EXPECT_EQ(find_type(""), nullptr);
}

const std::string kRule(80, '=');

TEST(TypeSupport, Ros1DefinitionInGendepsLayout) {
  EXPECT_EQ(find_type("sensor_msgs/LaserScan")->ros1_definition,
            "Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\nfloat32 time_increment\n"
            "float32 scan_time\nfloat32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities\n" +
                kRule + "\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n");
  // dependencies depth-first in field order, each once (Quaternion is met twice)
  EXPECT_EQ(find_type("tf2_msgs/TFMessage")->ros1_definition,
            "geometry_msgs/TransformStamped[] transforms\n" + kRule + "\nMSG: geometry_msgs/TransformStamped\n" +
                "Header header\nstring child_frame_id\nTransform transform\n" + kRule +
                "\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n" + kRule +
                "\nMSG: geometry_msgs/Transform\nVector3 translation\nQuaternion rotation\n" + kRule +
                "\nMSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n" + kRule +
                "\nMSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n");
  EXPECT_EQ(find_type("rosgraph_msgs/Clock")->ros1_definition, "time clock\n");
  EXPECT_EQ(find_type("std_msgs/String")->ros1_definition, "string data\n");
}

TEST(TypeSupport, Ros2DefinitionsAreHumble) {
  EXPECT_EQ(find_type("sensor_msgs/Range")->ros2_definition,
            "std_msgs/Header header\nuint8 ULTRASOUND=0\nuint8 INFRARED=1\nuint8 radiation_type\n"
            "float32 field_of_view\nfloat32 min_range\nfloat32 max_range\nfloat32 range\n" +
                kRule + "\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" + kRule +
                "\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n");
  const std::string& cam = find_type("sensor_msgs/CameraInfo")->ros2_definition;
  EXPECT_NE(cam.find("\nfloat64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\n"), std::string::npos) << cam;
  EXPECT_NE(cam.find("\nRegionOfInterest roi\n"), std::string::npos) << cam;
  EXPECT_EQ(find_type("std_msgs/String")->ros2_definition, "string data\n");
  const std::string& clock = find_type("rosgraph_msgs/Clock")->ros2_definition;
  EXPECT_EQ(clock, "builtin_interfaces/Time clock\n" + kRule + "\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n");
  // ROS 1 keeps the upper-case names
  EXPECT_NE(find_type("sensor_msgs/CameraInfo")->ros1_definition.find("\nfloat64[] D\nfloat64[9] K\n"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim::msg
