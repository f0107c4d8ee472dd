/// libFuzzer target for the ROS 1 decoder, from_ros1, on every message type: what a TCPROS
/// peer or a bag can hand us. See msg_decode.h for the input layout and the checks.

#include "msg_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  return fuzz::decode_round_trip(
      data, size, [](const msg::TypeSupport& t, std::span<const std::uint8_t> b) { return msg::from_ros1(t, b); },
      [](const msg::Message& m, std::vector<std::uint8_t>& out) { msg::to_ros1(m, out); });
}
