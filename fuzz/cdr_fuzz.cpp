/// libFuzzer target for the CDR (ROS 2) decoder, from_cdr, on every message type: what a DDS
/// peer or an MCAP file can hand us. See msg_decode.h for the input layout and the checks.

#include "msg_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  return fuzz::decode_round_trip(
      data, size, [](const msg::TypeSupport& t, std::span<const std::uint8_t> b) { return msg::from_cdr(t, b); },
      [](const msg::Message& m, std::vector<std::uint8_t>& out) { msg::to_cdr(m, out); });
}
