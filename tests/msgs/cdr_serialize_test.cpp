// Byte-exact CDR (XCDR1 little endian) of every message type, expected bytes written by hand
// from the ROS 2 Humble layouts. After the encapsulation header 00 01 00 00, offsets (in the
// comments and checked by `.at(n)`) count from 0; a primitive of size n starts at a multiple of
// n, so the padding below is worked out by hand and written with `.pad(n)`. Strings are u32
// length including the NUL, bytes, NUL; Time is i32 sec + u32 nanosec; Header has no seq.

#include <gtest/gtest.h>

#include "msgs/serialize.h"
#include "samples.h"

namespace rescuesim::msg {
namespace {

using test::Bytes;

std::vector<std::uint8_t> cdr(const Message& m) {
  std::vector<std::uint8_t> out;
  to_cdr(m, out);
  return out;
}

Bytes encapsulated() { return Bytes().hex("00 01 00 00"); }

TEST(CdrSerialize, Clock) {
  const auto expected = encapsulated().hex("01 00 00 00  00 65 cd 1d").bytes();  // sec 1, nanosec 5e8
  EXPECT_EQ(cdr(test::clock_msg()), expected);
}

TEST(CdrSerialize, RangeHumbleLayoutWithoutVariance) {
  const auto expected = encapsulated()
                            .at(0).hex("03 00 00 00")      // stamp.sec 3
                            .at(4).hex("00 00 00 00")      // stamp.nanosec
                            .at(8).hex("02 00 00 00 73 00")  // frame_id "s" (length 2 with NUL)
                            .at(14).hex("01")              // radiation_type
                            .at(15).pad(1)                 // float32 aligns to 4
                            .at(16).hex("00 00 00 3f")     // field_of_view
                            .at(20).hex("00 00 80 3e")     // min_range
                            .at(24).hex("00 00 00 40")     // max_range
                            .at(28).hex("00 00 80 3f")     // range; no variance in Humble
                            .at(32)
                            .bytes();
  EXPECT_EQ(cdr(test::range_msg()), expected);
}

TEST(CdrSerialize, LaserScan) {
  const auto expected = encapsulated()
                            .at(0).i32(2).u32(250'000'000)     // stamp
                            .at(8).str2("laser")               // frame_id, ends at 18
                            .at(18).pad(2)
                            .at(20).f32(-0.5f).f32(0.5f).f32(1.0f).f32(0.25f).f32(0.125f).f32(0.0625f).f32(8.0f)
                            .at(48).u32(2)                     // ranges count
                            .at(52).f32(1.5f).hex("00 00 80 7f")  // 1.5, +inf
                            .at(60).u32(0)                     // intensities: empty, no element padding
                            .at(64)
                            .bytes();
  EXPECT_EQ(cdr(test::laser_scan()), expected);
}

TEST(CdrSerialize, Imu) {
  Bytes b = encapsulated();
  b.at(0).i32(1).u32(0).at(8).str2("imu");  // frame_id ends at 16: already 8-aligned
  b.at(16).f64(1).f64(2).f64(3).f64(4);    // orientation x y z w
  b.at(48);
  for (double c : {1., 0., 0., 0., 2., 0., 0., 0., 3.}) b.f64(c);
  b.at(120).f64(-1).f64(0).f64(1);
  b.at(144).f64(-1);
  for (int i = 1; i < 9; ++i) b.f64(0);
  b.at(216).f64(0).f64(0).f64(9.75);
  for (int i = 0; i < 9; ++i) b.f64(0);
  b.at(312);
  EXPECT_EQ(cdr(test::imu()), b.bytes());
}

TEST(CdrSerialize, Twist) {
  const auto expected =
      encapsulated().at(0).f64(0.5).f64(0).f64(0).at(24).f64(0).f64(0).f64(-0.25).at(48).bytes();
  EXPECT_EQ(cdr(test::twist()), expected);
}

TEST(CdrSerialize, OdometryDoubleAfterOddString) {
  Bytes b = encapsulated();
  b.at(0).i32(12).u32(1);                  // stamp 12.000000001 s
  b.at(8).str2("odom");                    // 8: length 5, "odom\0" at 12..16
  b.at(17).pad(3);                         // u32 length aligns to 4
  b.at(20).str2("base_link");              // child_frame_id: length 10, bytes at 24..33
  b.at(34).pad(6);                         // float64 aligns to 8: 34 -> 40
  b.at(40).f64(1).f64(2).f64(0);           // pose.pose.position
  b.at(64).f64(0).f64(0).f64(-0.5).f64(0.75);  // orientation x y z w
  b.at(96).f64(0.5);                       // pose.covariance
  for (int i = 1; i < 35; ++i) b.f64(0);
  b.f64(0.25);
  b.at(384).f64(0.5).f64(0).f64(0).f64(0).f64(0).f64(0.125);  // twist.twist
  b.at(432).f64(2);                        // twist.covariance
  for (int i = 1; i < 36; ++i) b.f64(0);
  b.at(720);
  EXPECT_EQ(cdr(test::odometry()), b.bytes());
}

TEST(CdrSerialize, JointState) {
  const auto expected = encapsulated()
                            .at(0).i32(1).u32(0)
                            .at(8).str2("base_link")  // ends at 22
                            .at(22).pad(2)
                            .at(24).u32(2)            // name count
                            .at(28).str2("pan")       // 28..35
                            .at(36).str2("tilt")      // 36..44
                            .at(45).pad(3)
                            .at(48).u32(2)            // position count
                            .at(52).pad(4)            // doubles align to 8
                            .at(56).f64(0.5).f64(-0.25)
                            .at(72).u32(2)            // velocity count
                            .at(76).pad(4)
                            .at(80).f64(1).f64(2)
                            .at(96).u32(0)            // effort: empty
                            .at(100)
                            .bytes();
  EXPECT_EQ(cdr(test::joint_state()), expected);
}

TEST(CdrSerialize, TFMessage) {
  const auto expected = encapsulated()
                            .at(0).u32(1)                   // transforms count
                            .at(4).i32(2).u32(0)            // [0].header.stamp
                            .at(12).str2("odom")            // 12..20
                            .at(21).pad(3)
                            .at(24).str2("base_link")       // 24..37
                            .at(38).pad(2)
                            .at(40).f64(1).f64(-1).f64(0)   // translation
                            .at(64).f64(0).f64(0).f64(0).f64(1)  // rotation x y z w
                            .at(96)
                            .bytes();
  EXPECT_EQ(cdr(test::tf_message()), expected);
}

TEST(CdrSerialize, PoseStamped) {
  const auto expected = encapsulated()
                            .at(0).i32(5).u32(0)
                            .at(8).str2("map")  // ends at 16, aligned
                            .at(16).f64(1).f64(2).f64(3).f64(0).f64(0).f64(0).f64(1)
                            .at(72)
                            .bytes();
  EXPECT_EQ(cdr(test::pose_stamped()), expected);
}

TEST(CdrSerialize, Path) {
  const auto expected = encapsulated()
                            .at(0).i32(5).u32(0).at(8).str2("map")
                            .at(16).u32(2)                       // poses count
                            .at(20).i32(1).u32(0).at(28).str2("map")  // poses[0].header, ends at 36
                            .at(36).pad(4)
                            .at(40).f64(1).f64(0).f64(0).f64(0).f64(0).f64(0).f64(1)
                            .at(96).i32(2).u32(0).at(104).str2("map")  // poses[1].header, ends at 112
                            .at(112).f64(2).f64(0).f64(0).f64(0).f64(0).f64(1).f64(0)
                            .at(168)
                            .bytes();
  EXPECT_EQ(cdr(test::path()), expected);
}

TEST(CdrSerialize, OccupancyGrid) {
  const auto expected = encapsulated()
                            .at(0).i32(7).u32(0).at(8).str2("map")
                            .at(16).i32(6).u32(0)          // info.map_load_time
                            .at(24).f32(0.5f).u32(2).u32(1)  // resolution, width, height
                            .at(36).pad(4)
                            .at(40).f64(-1).f64(-2).f64(0).f64(0).f64(0).f64(0).f64(1)  // origin
                            .at(96).u32(2).hex("ff 64")    // data -1, 100
                            .at(102)
                            .bytes();
  EXPECT_EQ(cdr(test::occupancy_grid()), expected);
}

TEST(CdrSerialize, Float64MultiArray) {
  const auto expected = encapsulated()
                            .at(0).u32(0)   // layout.dim count
                            .at(4).u32(0)   // layout.data_offset
                            .at(8).u32(2)   // data count
                            .at(12).pad(4)
                            .at(16).hex("00 00 00 00 00 00 f8 3f  00 00 00 00 00 00 00 c0")
                            .at(32)
                            .bytes();
  EXPECT_EQ(cdr(test::float64_multi_array()), expected);
}

TEST(CdrSerialize, Contacts) {
  const auto expected = encapsulated()
                            .at(0).i32(1).u32(0).at(8).str2("base_link")
                            .at(22).pad(2)
                            .at(24).u32(1).at(28).str2("victim_1")
                            .at(41)
                            .bytes();
  EXPECT_EQ(cdr(test::contacts()), expected);
}

TEST(CdrSerialize, String) {
  // std_msgs/String "ab": uint32 length 3 with the NUL, the bytes, the NUL; no padding after
  const auto expected = encapsulated().at(0).hex("03 00 00 00").at(4).hex("61 62 00").at(7).bytes();
  EXPECT_EQ(cdr(test::string_msg()), expected);
  EXPECT_EQ(cdr(String{}), encapsulated().hex("01 00 00 00  00").bytes());  // the empty string is its NUL
}

TEST(CdrSerialize, Bool) {
  // std_msgs/Bool: one octet, 1 for true
  EXPECT_EQ(cdr(test::bool_msg()), encapsulated().hex("01").bytes());
  EXPECT_EQ(cdr(Bool{}), encapsulated().hex("00").bytes());
}

TEST(CdrSerialize, Image2x1Rgb8) {
  const auto expected = encapsulated()
                            .at(0).hex("01 00 00 00  00 00 00 00")   // stamp 1 s
                            .at(8).hex("04 00 00 00  63 61 6d 00")   // frame_id "cam\0"
                            .at(16).hex("01 00 00 00")               // height
                            .at(20).hex("02 00 00 00")               // width
                            .at(24).hex("05 00 00 00  72 67 62 38 00")  // encoding "rgb8\0"
                            .at(33).hex("00")                        // is_bigendian
                            .at(34).pad(2)
                            .at(36).hex("06 00 00 00")               // step
                            .at(40).hex("06 00 00 00  01 02 03 04 05 06")  // data
                            .at(50)
                            .bytes();
  EXPECT_EQ(cdr(test::image()), expected);
}

TEST(CdrSerialize, CameraInfo) {
  Bytes b = encapsulated();
  b.at(0).i32(1).u32(0).at(8).str2("cam");
  b.at(16).u32(480).u32(640);
  b.at(24).str2("plumb_bob");          // 24..37
  b.at(38).pad(2);
  b.at(40).u32(5);                     // d count
  b.at(44).pad(4);
  b.at(48).f64(0.5).f64(-0.25).f64(0).f64(0).f64(0.125);
  b.at(88);
  for (double k : {500., 0., 320., 0., 500., 240., 0., 0., 1.}) b.f64(k);
  b.at(160);
  for (double r : {1., 0., 0., 0., 1., 0., 0., 0., 1.}) b.f64(r);
  b.at(232);
  for (double p : {500., 0., 320., 0., 0., 500., 240., 0., 0., 0., 1., 0.}) b.f64(p);
  b.at(328).u32(1).u32(0);                       // binning
  b.at(336).u32(0).u32(0).u32(0).u32(8).u8(1);  // roi
  b.at(353);
  EXPECT_EQ(cdr(test::camera_info()), b.bytes());
}

TEST(CdrSerialize, PointCloud2) {
  const auto expected = encapsulated()
                            .at(0).i32(1).u32(0).at(8).str2("cam")
                            .at(16).u32(1).u32(1)    // height, width
                            .at(24).u32(3)           // fields count
                            .at(28).str2("x").at(34).pad(2).at(36).u32(0).at(40).u8(7).pad(3).at(44).u32(1)
                            .at(48).str2("y").at(54).pad(2).at(56).u32(4).at(60).u8(7).pad(3).at(64).u32(1)
                            .at(68).str2("z").at(74).pad(2).at(76).u32(8).at(80).u8(7).pad(3).at(84).u32(1)
                            .at(88).u8(0)            // is_bigendian
                            .at(89).pad(3)
                            .at(92).u32(12).u32(12)  // point_step, row_step
                            .at(100).u32(12).f32(1).f32(2).f32(-0.5f)  // data
                            .at(116).u8(1)           // is_dense
                            .at(117)
                            .bytes();
  EXPECT_EQ(cdr(test::point_cloud2()), expected);
}

TEST(CdrSerialize, AlignmentIsCountedAfterTheHeaderWhenAppending) {
  std::vector<std::uint8_t> out = {0xaa, 0xbb, 0xcc};
  to_cdr(test::float64_multi_array(), out);
  std::vector<std::uint8_t> expected = {0xaa, 0xbb, 0xcc};
  const auto body = cdr(test::float64_multi_array());
  expected.insert(expected.end(), body.begin(), body.end());
  EXPECT_EQ(out, expected);
}

}  // namespace
}  // namespace rescuesim::msg
