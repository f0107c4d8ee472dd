// Decoders: decode(encode(m)) == m for every type in both wire formats, and malformed bytes
// (truncated anywhere, absurd counts, trailing bytes, wrong encapsulation, random damage) give
// an Error that names the type and the field, never a crash or a huge allocation.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "msgs/digest.h"
#include "msgs/serialize.h"
#include "samples.h"

namespace rescuesim::msg {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::vector<std::uint8_t> ros1(const Message& m) {
  std::vector<std::uint8_t> out;
  to_ros1(m, out, 17);
  return out;
}
std::vector<std::uint8_t> cdr(const Message& m) {
  std::vector<std::uint8_t> out;
  to_cdr(m, out);
  return out;
}

// the error text of decoding `bytes`, or "" when it decodes
template <class Decode>
std::string error_of(Decode decode, const TypeSupport& t, const std::vector<std::uint8_t>& bytes) {
  try {
    decode(t, bytes);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// messages with more in them than the samples: odd-length strings at every alignment, NaN,
// negative zero, several sequence elements
std::vector<Message> richer_messages() {
  std::vector<Message> out;
  for (int len = 0; len < 9; ++len) {
    const std::string frame(len, 'f');
    Odometry o = test::odometry();
    o.header.frame_id = frame;
    o.child_frame_id = frame + "c";
    out.push_back(o);
    JointState j = test::joint_state();
    j.header.frame_id = frame;
    j.name = {frame, "", frame + "xyz"};
    j.effort = {std::nan(""), -0.0, 1e300};
    out.push_back(j);
    PointCloud2 pc = test::point_cloud2();
    pc.header.frame_id = frame;
    pc.fields[1].name = frame;
    out.push_back(pc);
    CameraInfo ci = test::camera_info();
    ci.distortion_model = frame;
    ci.d.resize(len);
    out.push_back(ci);
  }
  LaserScan s = test::laser_scan();
  s.ranges = {-std::numeric_limits<float>::infinity(), std::nanf(""), 0.f, 3.25f};
  s.intensities = {1, 2, 3, 4};
  out.push_back(s);
  TFMessage tf = test::tf_message();
  tf.transforms.push_back(tf.transforms[0]);
  tf.transforms[1].header.frame_id = "map";
  tf.transforms[1].transform = Pose3::from_rpy(Vec3(1, 2, 3), 0.1, 0.2, 0.3);
  out.push_back(tf);
  out.push_back(TFMessage{});
  out.push_back(Path{test::header(1, "map"), {}});
  Image im = test::image();
  im.data.assign(640 * 480 * 3, 7);
  im.height = 480;
  im.width = 640;
  out.push_back(im);
  out.push_back(Float64MultiArray{});
  out.push_back(Contacts{test::header(0, ""), {"a", "bb", "ccc", ""}});
  // a robot description: long, multi-line, quotes, UTF-8
  out.push_back(String{});
  out.push_back(String{"<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <!-- \u00e9t\u00e9 -->\n" + std::string(70000, ' ') + "</robot>\n"});
  return out;
}

TEST(Decode, RoundTripEveryTypeRos1) {
  for (const auto& source : {test::all_samples(), richer_messages()}) {
    for (const Message& m : source) {
      const Message back = from_ros1(type_of(m), ros1(m));
      EXPECT_EQ(back.index(), m.index());
      EXPECT_EQ(digest(back), digest(m)) << type_name(m) << " " << to_json(m);
    }
  }
}

TEST(Decode, RoundTripEveryTypeCdr) {
  for (const auto& source : {test::all_samples(), richer_messages()}) {
    for (const Message& m : source) {
      const Message back = from_cdr(type_of(m), cdr(m));
      EXPECT_EQ(back.index(), m.index());
      EXPECT_EQ(digest(back), digest(m)) << type_name(m) << " " << to_json(m);
    }
  }
}

TEST(Decode, RosTwoNegativeStampsRoundTrip) {
  Clock c{SimTime{-1'500'000'000}};
  const Message back = from_cdr(type_of(c), cdr(c));
  EXPECT_EQ(std::get<Clock>(back).clock.ns, -1'500'000'000);
}

TEST(Decode, TruncatedAtEveryLengthIsAnError) {
  for (const Message& m : test::all_samples()) {
    const TypeSupport& t = type_of(m);
    const auto full1 = ros1(m);
    for (std::size_t n = 0; n < full1.size(); ++n) {
      const std::vector<std::uint8_t> cut(full1.begin(), full1.begin() + n);
      const std::string e = error_of(from_ros1, t, cut);
      EXPECT_THAT(e, StartsWith(t.ros1_name + ": ")) << "ROS 1, " << n << " of " << full1.size() << " bytes";
      EXPECT_THAT(e, HasSubstr(" left")) << e;  // every message says how many bytes were left
    }
    const auto full2 = cdr(m);
    for (std::size_t n = 0; n < full2.size(); ++n) {
      const std::vector<std::uint8_t> cut(full2.begin(), full2.begin() + n);
      const std::string e = error_of(from_cdr, t, cut);
      EXPECT_THAT(e, StartsWith(t.ros2_name + ": ")) << "CDR, " << n << " of " << full2.size() << " bytes";
    }
  }
}

TEST(Decode, ErrorsNameTheField) {
  const TypeSupport& scan = *find_type("sensor_msgs/LaserScan");
  auto b = ros1(test::laser_scan());
  b.resize(30);  // inside angle_increment (offset 29..32)
  EXPECT_EQ(error_of(from_ros1, scan, b), "sensor_msgs/LaserScan: angle_increment: truncated: a value needs 4 bytes, 1 left");

  b = ros1(test::laser_scan());
  b.resize(14);  // inside header.frame_id's length
  EXPECT_EQ(error_of(from_ros1, scan, b), "sensor_msgs/LaserScan: header.frame_id: truncated: a value needs 4 bytes, 2 left");

  const TypeSupport& tf = *find_type("tf2_msgs/TFMessage");
  // a count the bytes left cannot hold is caught before the elements are read
  b = cdr(test::tf_message());
  b.resize(4 + 18);  // inside transforms[0].header.frame_id ("odom\0" at 16..20)
  EXPECT_EQ(error_of(from_cdr, tf, b), "tf2_msgs/msg/TFMessage: transforms: sequence of 1 elements needs at least 74 bytes, 14 left");
  // two transforms (the second from offset 96 to 192): cut inside [1].transform.rotation.x (160..167)
  TFMessage two = test::tf_message();
  two.transforms.push_back(two.transforms[0]);
  b = cdr(two);
  ASSERT_EQ(b.size(), 4u + 192);
  b.resize(4 + 164);
  EXPECT_EQ(error_of(from_cdr, tf, b),
            "tf2_msgs/msg/TFMessage: transforms[1].transform.rotation.x: truncated: a value needs 8 bytes, 4 left");

  const TypeSupport& cam = *find_type("sensor_msgs/CameraInfo");
  b = cdr(test::camera_info());
  b.resize(4 + 100);  // inside k
  EXPECT_EQ(error_of(from_cdr, cam, b), "sensor_msgs/msg/CameraInfo: k: truncated: array of 9 elements needs 72 bytes, 12 left");
  b = ros1(test::camera_info());
  b.resize(100);
  EXPECT_THAT(error_of(from_ros1, cam, b), StartsWith("sensor_msgs/CameraInfo: K: truncated"));
}

void put_u32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

TEST(Decode, AbsurdCountsAreRejectedBeforeAllocating) {
  const TypeSupport& scan = *find_type("sensor_msgs/LaserScan");
  auto b = ros1(test::laser_scan());
  put_u32(b, 49, 4'000'000'000u);  // ranges count
  EXPECT_EQ(error_of(from_ros1, scan, b),
            "sensor_msgs/LaserScan: ranges: sequence of 4000000000 elements needs 16000000000 bytes, 12 left");

  b = cdr(test::laser_scan());
  put_u32(b, 4 + 48, 0xffffffffu);
  EXPECT_EQ(error_of(from_cdr, scan, b),
            "sensor_msgs/msg/LaserScan: ranges: sequence of 4294967295 elements needs 17179869180 bytes, 12 left");

  // sequences of messages and strings: each element takes at least its fixed part
  const TypeSupport& tf = *find_type("tf2_msgs/TFMessage");
  b = ros1(test::tf_message());
  put_u32(b, 0, 0xffffffffu);
  EXPECT_THAT(error_of(from_ros1, tf, b),
              StartsWith("tf2_msgs/TFMessage: transforms: sequence of 4294967295 elements needs at least "));
  b = cdr(test::tf_message());
  put_u32(b, 4, 1'000'000u);
  EXPECT_THAT(error_of(from_cdr, tf, b),
              StartsWith("tf2_msgs/msg/TFMessage: transforms: sequence of 1000000 elements needs at least "));

  const TypeSupport& js = *find_type("sensor_msgs/JointState");
  b = ros1(test::joint_state());
  put_u32(b, 4 + 8 + 4 + 9, 100'000'000u);  // name count after the header
  EXPECT_THAT(error_of(from_ros1, js, b),
              StartsWith("sensor_msgs/JointState: name: sequence of 100000000 elements needs at least 400000000 bytes"));

  const TypeSupport& img = *find_type("sensor_msgs/Image");
  b = ros1(test::image());
  put_u32(b, 12, 0xfffffff0u);  // frame_id length
  EXPECT_EQ(error_of(from_ros1, img, b),
            "sensor_msgs/Image: header.frame_id: truncated: string of 4294967280 bytes needs 4294967280 bytes, 34 left");
}

TEST(Decode, TrailingBytesAreAnError) {
  for (const Message& m : test::all_samples()) {
    const TypeSupport& t = type_of(m);
    auto b = ros1(m);
    b.push_back(0);
    EXPECT_EQ(error_of(from_ros1, t, b), t.ros1_name + ": 1 trailing bytes after the message");
    b = cdr(m);
    b.push_back(0);
    EXPECT_EQ(error_of(from_cdr, t, b), t.ros2_name + ": 1 trailing bytes after the message");
  }
}

TEST(Decode, CdrPaddingAnnouncedInTheOptionsIsAccepted) {
  const TypeSupport& t = *find_type("rescuesim_msgs/Contacts");
  auto b = cdr(test::contacts());  // 41-byte body: a writer padding to 4 appends 3 bytes
  b.insert(b.end(), {0, 0, 0});
  EXPECT_THAT(error_of(from_cdr, t, b), HasSubstr("3 trailing bytes"));
  b[3] = 0x03;
  EXPECT_EQ(error_of(from_cdr, t, b), "");
  EXPECT_EQ(digest(from_cdr(t, b)), digest(test::contacts()));
  b.push_back(0);
  EXPECT_EQ(error_of(from_cdr, t, b),
            "rescuesim_msgs/msg/Contacts: 4 trailing bytes after the message (the encapsulation options allow 3)");
}

TEST(Decode, CdrEncapsulationIsChecked) {
  const TypeSupport& t = *find_type("rosgraph_msgs/Clock");
  auto b = cdr(test::clock_msg());
  b[1] = 0x00;
  EXPECT_EQ(error_of(from_cdr, t, b),
            "rosgraph_msgs/msg/Clock: encapsulation 00 00 (big-endian CDR) is not supported; expected 00 01 (XCDR1 little endian)");
  b[1] = 0x07;  // XCDR2 little endian
  EXPECT_EQ(error_of(from_cdr, t, b),
            "rosgraph_msgs/msg/Clock: encapsulation 00 07 is not supported; expected 00 01 (XCDR1 little endian)");
  EXPECT_EQ(error_of(from_cdr, t, {0x00, 0x01}),
            "rosgraph_msgs/msg/Clock: CDR data of 2 bytes is shorter than the 4-byte encapsulation header");
  EXPECT_EQ(error_of(from_cdr, t, {}), "rosgraph_msgs/msg/Clock: CDR data of 0 bytes is shorter than the 4-byte encapsulation header");
}

TEST(Decode, CdrStringsMustCountAndEndWithTheirNul) {
  const TypeSupport& t = *find_type("rescuesim_msgs/Contacts");
  auto b = cdr(test::contacts());
  put_u32(b, 4 + 8, 0);  // header.frame_id length
  EXPECT_EQ(error_of(from_cdr, t, b),
            "rescuesim_msgs/msg/Contacts: header.frame_id: string length 0 (a CDR string counts its terminating NUL)");
  b = cdr(test::contacts());
  b[4 + 40] = 'x';  // the NUL of touching[0] "victim_1" (28: length, 32..40: bytes)
  EXPECT_EQ(error_of(from_cdr, t, b), "rescuesim_msgs/msg/Contacts: touching[0]: string of 9 bytes does not end in NUL");
}

TEST(Decode, StringLengthsAreChecked) {
  const TypeSupport& t = *find_type("std_msgs/String");
  auto b = ros1(test::string_msg());
  put_u32(b, 0, 3);  // one byte more than there is
  EXPECT_EQ(error_of(from_ros1, t, b), "std_msgs/String: data: truncated: string of 3 bytes needs 3 bytes, 2 left");
  b = cdr(test::string_msg());
  b[4 + 6] = 'c';  // the NUL
  EXPECT_EQ(error_of(from_cdr, t, b), "std_msgs/msg/String: data: string of 3 bytes does not end in NUL");
}

TEST(Decode, BadVariantIndexIsAnError) {
  TypeSupport bogus = *find_type("sensor_msgs/Range");
  bogus.variant_index = 99;
  EXPECT_THROW(from_ros1(bogus, {}), Error);
  EXPECT_THROW(from_cdr(bogus, {}), Error);
}

// random damage to valid messages: every outcome is a message or an Error (run under ASan to
// see that no read leaves the buffer)
TEST(Decode, RandomDamageNeverCrashes) {
  std::mt19937 rng(1234);
  std::size_t errors = 0, decoded = 0;
  for (const Message& m : test::all_samples()) {
    const TypeSupport& t = type_of(m);
    for (const bool is_cdr : {false, true}) {
      const auto good = is_cdr ? cdr(m) : ros1(m);
      for (int trial = 0; trial < 300; ++trial) {
        auto b = good;
        const int flips = 1 + static_cast<int>(rng() % 4);
        for (int f = 0; f < flips; ++f) b[rng() % b.size()] = static_cast<std::uint8_t>(rng());
        if (rng() % 4 == 0) b.resize(rng() % (b.size() + 1));
        try {
          (void)(is_cdr ? from_cdr(t, b) : from_ros1(t, b));
          ++decoded;
        } catch (const Error& e) {
          ++errors;
          EXPECT_THAT(std::string(e.what()), StartsWith(t.ros1_name.substr(0, t.ros1_name.find('/'))));
        }
      }
    }
  }
  EXPECT_GT(errors, 0u);
  EXPECT_GT(decoded, 0u);
}

}  // namespace
}  // namespace rescuesim::msg
