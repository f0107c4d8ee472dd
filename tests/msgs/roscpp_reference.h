#pragma once
// roscpp's own serialisation of the test samples (tests/msgs/samples.h), from Debian's generated
// ROS 1 message headers. Those headers need C++17 (std::allocator<void>::rebind), so
// roscpp_reference.cpp is compiled apart and this interface uses only standard types.

#include <cstdint>
#include <string>
#include <vector>

namespace rescuesim::msg::test {

/// What roscpp knows about one sample.
struct RoscppSample {
  bool known = false;               ///< false when the type has no roscpp message (our own types)
  std::vector<std::uint8_t> bytes;  ///< roscpp's serialisation (no length prefix)
  std::string md5;                  ///< ros::message_traits::MD5Sum
  std::string datatype;             ///< ros::message_traits::DataType
};

/// roscpp's serialisation of the sample of ROS type `type` ("sensor_msgs/LaserScan") with the
/// same values as samples.h, and `seq` in its own header.
RoscppSample roscpp_sample(const std::string& type, std::uint32_t seq);

}  // namespace rescuesim::msg::test
