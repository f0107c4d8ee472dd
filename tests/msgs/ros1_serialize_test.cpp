// Byte-exact ROS 1 serialisation of every message type, expected bytes written by hand from the
// Noetic message layouts: little endian, no padding, time = u32 sec + u32 nsec, string = u32
// length + bytes, T[] = u32 count + elements, T[N] = elements, Header = u32 seq + time + string.

#include <gtest/gtest.h>

#include "msgs/serialize.h"
#include "samples.h"

namespace rescuesim::msg {
namespace {

using test::Bytes;

std::vector<std::uint8_t> ros1(const Message& m, std::uint32_t seq = 0) {
  std::vector<std::uint8_t> out;
  to_ros1(m, out, seq);
  return out;
}

TEST(Ros1Serialize, Clock) {
  // 1.5 s: sec = 1, nsec = 500000000 = 0x1dcd6500
  const std::vector<std::uint8_t> expected = Bytes().hex("01 00 00 00  00 65 cd 1d").bytes();
  EXPECT_EQ(ros1(test::clock_msg()), expected);
}

TEST(Ros1Serialize, RangeHasNoVariance) {
  // Noetic's sensor_msgs/Range: header, radiation_type, field_of_view, min_range, max_range, range
  const std::vector<std::uint8_t> expected = Bytes()
                                                 .hex("05 00 00 00")  // 0  seq = 5
                                                 .hex("03 00 00 00")  // 4  stamp.sec = 3
                                                 .hex("00 00 00 00")  // 8  stamp.nsec
                                                 .hex("01 00 00 00")  // 12 frame_id length 1
                                                 .hex("73")           // 16 "s"
                                                 .hex("01")           // 17 radiation_type INFRARED
                                                 .hex("00 00 00 3f")  // 18 field_of_view 0.5f
                                                 .hex("00 00 80 3e")  // 22 min_range 0.25f
                                                 .hex("00 00 00 40")  // 26 max_range 2.0f
                                                 .hex("00 00 80 3f")  // 30 range 1.0f; 34 bytes
                                                 .bytes();
  EXPECT_EQ(ros1(test::range_msg(), 5), expected);
}

TEST(Ros1Serialize, LaserScan) {
  const std::vector<std::uint8_t> expected = Bytes()
                                                 .u32(7)             // 0  seq
                                                 .u32(2)             // 4  stamp.sec
                                                 .u32(250'000'000)   // 8  stamp.nsec
                                                 .str1("laser")      // 12 frame_id (4 + 5)
                                                 .f32(-0.5f)         // 21 angle_min
                                                 .f32(0.5f)          // 25 angle_max
                                                 .f32(1.0f)          // 29 angle_increment
                                                 .f32(0.25f)         // 33 time_increment
                                                 .f32(0.125f)        // 37 scan_time
                                                 .f32(0.0625f)       // 41 range_min
                                                 .f32(8.0f)          // 45 range_max
                                                 .u32(2)             // 49 ranges count
                                                 .hex("00 00 c0 3f")  // 53 1.5f
                                                 .hex("00 00 80 7f")  // 57 +inf
                                                 .u32(0)             // 61 intensities count; 65 bytes
                                                 .bytes();
  EXPECT_EQ(ros1(test::laser_scan(), 7), expected);
}

TEST(Ros1Serialize, Imu) {
  Bytes b;
  b.u32(0).u32(1).u32(0).str1("imu");      // header
  b.f64(1).f64(2).f64(3).f64(4);          // orientation x, y, z, w
  for (double c : {1., 0., 0., 0., 2., 0., 0., 0., 3.}) b.f64(c);  // orientation_covariance[9]
  b.f64(-1).f64(0).f64(1);                // angular_velocity
  b.f64(-1);                              // angular_velocity_covariance[0]
  for (int i = 1; i < 9; ++i) b.f64(0);
  b.f64(0).f64(0).f64(9.75);              // linear_acceleration
  for (int i = 0; i < 9; ++i) b.f64(0);   // linear_acceleration_covariance
  EXPECT_EQ(b.bytes().size(), 4u + 8 + 7 + 4 * 8 + 3 * 9 * 8 + 2 * 3 * 8);
  EXPECT_EQ(ros1(test::imu()), b.bytes());
}

TEST(Ros1Serialize, Twist) {
  const std::vector<std::uint8_t> expected = Bytes()
                                                 .hex("00 00 00 00 00 00 e0 3f")  // linear.x 0.5
                                                 .hex("00 00 00 00 00 00 00 00")  // linear.y
                                                 .hex("00 00 00 00 00 00 00 00")  // linear.z
                                                 .hex("00 00 00 00 00 00 00 00")  // angular.x
                                                 .hex("00 00 00 00 00 00 00 00")  // angular.y
                                                 .hex("00 00 00 00 00 00 d0 bf")  // angular.z -0.25
                                                 .bytes();
  EXPECT_EQ(ros1(test::twist()), expected);
}

TEST(Ros1Serialize, Odometry) {
  Bytes b;
  b.u32(9).u32(12).u32(1).str1("odom");                  // header: 12.000000001 s
  b.str1("base_link");                                   // child_frame_id
  b.f64(1).f64(2).f64(0);                                // pose.pose.position
  b.f64(0).f64(0).f64(-0.5).f64(0.75);                   // pose.pose.orientation x y z w
  b.f64(0.5);                                            // pose.covariance[0]
  for (int i = 1; i < 35; ++i) b.f64(0);
  b.f64(0.25);                                           // pose.covariance[35]
  b.f64(0.5).f64(0).f64(0).f64(0).f64(0).f64(0.125);     // twist.twist linear, angular
  b.f64(2);                                              // twist.covariance[0]
  for (int i = 1; i < 36; ++i) b.f64(0);
  EXPECT_EQ(b.bytes().size(), 4u + 8 + 8 + 13 + 7 * 8 + 36 * 8 + 6 * 8 + 36 * 8);
  EXPECT_EQ(ros1(test::odometry(), 9), b.bytes());
}

TEST(Ros1Serialize, JointState) {
  Bytes b;
  b.u32(0).u32(1).u32(0).str1("base_link");
  b.u32(2).str1("pan").str1("tilt");    // name
  b.u32(2).f64(0.5).f64(-0.25);         // position
  b.u32(2).f64(1).f64(2);               // velocity
  b.u32(0);                             // effort
  EXPECT_EQ(ros1(test::joint_state()), b.bytes());
}

TEST(Ros1Serialize, TFMessageNestedHeaderHasSeqZero) {
  Bytes b;
  b.u32(1);                                  // transforms count
  b.u32(0).u32(2).u32(0).str1("odom");       // [0].header: seq stays 0 inside the array
  b.str1("base_link");                       // [0].child_frame_id
  b.f64(1).f64(-1).f64(0);                   // transform.translation
  b.f64(0).f64(0).f64(0).f64(1);             // transform.rotation x y z w
  EXPECT_EQ(ros1(test::tf_message(), 33), b.bytes());
}

TEST(Ros1Serialize, PoseStamped) {
  Bytes b;
  b.u32(3).u32(5).u32(0).str1("map");
  b.f64(1).f64(2).f64(3).f64(0).f64(0).f64(0).f64(1);
  EXPECT_EQ(ros1(test::pose_stamped(), 3), b.bytes());
}

TEST(Ros1Serialize, Path) {
  Bytes b;
  b.u32(4).u32(5).u32(0).str1("map");                                                  // header, seq 4
  b.u32(2);                                                                            // poses count
  b.u32(0).u32(1).u32(0).str1("map").f64(1).f64(0).f64(0).f64(0).f64(0).f64(0).f64(1);  // poses[0]
  b.u32(0).u32(2).u32(0).str1("map").f64(2).f64(0).f64(0).f64(0).f64(0).f64(1).f64(0);  // poses[1]: z=1 w=0
  EXPECT_EQ(ros1(test::path(), 4), b.bytes());
}

TEST(Ros1Serialize, OccupancyGrid) {
  Bytes b;
  b.u32(0).u32(7).u32(0).str1("map");              // header
  b.u32(6).u32(0);                                 // info.map_load_time
  b.f32(0.5f).u32(2).u32(1);                       // info.resolution, width, height
  b.f64(-1).f64(-2).f64(0).f64(0).f64(0).f64(0).f64(1);  // info.origin
  b.u32(2).hex("ff 64");                           // data: -1, 100
  EXPECT_EQ(ros1(test::occupancy_grid()), b.bytes());
}

TEST(Ros1Serialize, Float64MultiArrayWithEmptyLayout) {
  const std::vector<std::uint8_t> expected = Bytes()
                                                 .hex("00 00 00 00")  // layout.dim count 0
                                                 .hex("00 00 00 00")  // layout.data_offset 0
                                                 .hex("02 00 00 00")  // data count 2
                                                 .hex("00 00 00 00 00 00 f8 3f")  // 1.5
                                                 .hex("00 00 00 00 00 00 00 c0")  // -2.0
                                                 .bytes();
  EXPECT_EQ(ros1(test::float64_multi_array()), expected);
}

TEST(Ros1Serialize, Contacts) {
  Bytes b;
  b.u32(0).u32(1).u32(0).str1("base_link").u32(1).str1("victim_1");
  EXPECT_EQ(ros1(test::contacts()), b.bytes());
}

TEST(Ros1Serialize, String) {
  // std_msgs/String "ab": uint32 length 2, the bytes, no NUL
  EXPECT_EQ(ros1(test::string_msg()), Bytes().hex("02 00 00 00  61 62").bytes());
  EXPECT_EQ(ros1(String{}), Bytes().hex("00 00 00 00").bytes());
}

TEST(Ros1Serialize, Image2x1Rgb8) {
  const std::vector<std::uint8_t> expected = Bytes()
                                                 .hex("00 00 00 00")           // 0  seq
                                                 .hex("01 00 00 00 00 00 00 00")  // 4  stamp 1 s
                                                 .hex("03 00 00 00 63 61 6d")  // 12 frame_id "cam"
                                                 .hex("01 00 00 00")           // 19 height 1
                                                 .hex("02 00 00 00")           // 23 width 2
                                                 .hex("04 00 00 00 72 67 62 38")  // 27 encoding "rgb8"
                                                 .hex("00")                    // 35 is_bigendian
                                                 .hex("06 00 00 00")           // 36 step 6
                                                 .hex("06 00 00 00 01 02 03 04 05 06")  // 40 data; 50 bytes
                                                 .bytes();
  EXPECT_EQ(ros1(test::image()), expected);

  // the same bytes written into a buffer of the caller's (the ROS 1 bridge's path: roscpp's own
  // send buffer), whose 50 bytes ros1_size reports; a buffer of another size is refused
  ASSERT_EQ(ros1_size(test::image()), 50u);
  std::vector<std::uint8_t> own(50, 0xee);
  write_ros1(test::image(), own, 0);
  EXPECT_EQ(own, expected);
  std::vector<std::uint8_t> small(49);
  EXPECT_DEATH(write_ros1(test::image(), small, 0), "does not hold exactly");
  // seq goes into the header, as to_ros1 writes it
  write_ros1(test::image(), own, 7);
  EXPECT_EQ(own[0], 7);
}

TEST(Ros1Serialize, CameraInfo) {
  Bytes b;
  b.u32(0).u32(1).u32(0).str1("cam");
  b.u32(480).u32(640).str1("plumb_bob");
  b.u32(5).f64(0.5).f64(-0.25).f64(0).f64(0).f64(0.125);                    // D
  for (double k : {500., 0., 320., 0., 500., 240., 0., 0., 1.}) b.f64(k);  // K
  for (double r : {1., 0., 0., 0., 1., 0., 0., 0., 1.}) b.f64(r);          // R
  for (double p : {500., 0., 320., 0., 0., 500., 240., 0., 0., 0., 1., 0.}) b.f64(p);  // P
  b.u32(1).u32(0);                                  // binning_x, binning_y
  b.u32(0).u32(0).u32(0).u32(8).u8(1);              // roi x_offset y_offset height width do_rectify
  EXPECT_EQ(ros1(test::camera_info()), b.bytes());
}

TEST(Ros1Serialize, PointCloud2) {
  Bytes b;
  b.u32(0).u32(1).u32(0).str1("cam");
  b.u32(1).u32(1);                          // height, width
  b.u32(3);                                 // fields count
  b.str1("x").u32(0).u8(7).u32(1);          // name offset datatype(FLOAT32) count
  b.str1("y").u32(4).u8(7).u32(1);
  b.str1("z").u32(8).u8(7).u32(1);
  b.u8(0).u32(12).u32(12);                  // is_bigendian, point_step, row_step
  b.u32(12).f32(1).f32(2).f32(-0.5f);       // data
  b.u8(1);                                  // is_dense
  EXPECT_EQ(ros1(test::point_cloud2()), b.bytes());
}

TEST(Ros1Serialize, AppendsToExistingBytes) {
  std::vector<std::uint8_t> out = {0xaa};
  to_ros1(test::clock_msg(), out);
  EXPECT_EQ(out, Bytes().hex("aa 01 00 00 00 00 65 cd 1d").bytes());
}

}  // namespace
}  // namespace rescuesim::msg
