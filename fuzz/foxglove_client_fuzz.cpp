/// libFuzzer target for what a Foxglove WebSocket client sends (foxglove.websocket.v1): the
/// first input byte picks the frame kind, the rest is the frame.
///   even: a text frame for parse_client_text (JSON: subscribe, advertise, ...);
///   odd:  a binary frame for parse_client_binary. Client message data (0x01): its payload goes
///         through the command decoders (Twist, Float64MultiArray, JointState) and the decoder
///         of every message type (a mission's reports, datagrams and map are PoseStamped, String
///         and OccupancyGrid) in both client encodings, cdr and json, as the bridge does for a
///         client channel; what json reads, msg::to_json writes back to text that reads to the
///         same text again. A service call request (0x02): its payload goes through the request
///         decoder of every Simulation Interfaces service, and what decodes is answered (a
///         response encoded from it) as the bridge would.
/// rescuesim::Error is the only failure these may report; an escaping nlohmann::json exception,
/// a crash or a sanitizer finding is a bug.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string_view>

#include "bridges/foxglove/protocol.h"
#include "bridges/foxglove/sim_services.h"
#include "core/error.h"

namespace {

/// Runs `f`, swallowing the one exception the parsers are allowed to throw.
template <typename F>
void expect_only_errors(F&& f) {
  try {
    f();
  } catch (const rescuesim::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim::foxglove;
  if (size == 0) return 0;
  const std::span<const std::uint8_t> frame(data + 1, size - 1);
  if (data[0] % 2 == 0) {
    const std::string_view text(reinterpret_cast<const char*>(frame.data()), frame.size());
    expect_only_errors([&] { parse_client_text(text); });
    return 0;
  }
  expect_only_errors([&] {
    const ClientBinary parsed = parse_client_binary(frame);
    if (const auto* call = std::get_if<ServiceCallRequest>(&parsed)) {
      for (std::size_t i = 0; i < kSimServiceCount; ++i) {
        expect_only_errors([&] {
          const SimRequest request = decode_sim_request(static_cast<SimService>(i), call->payload);
          SimResponse response;
          response.service = static_cast<SimService>(request.index());
          if (const auto* get = std::get_if<GetEntityStateRequest>(&request)) response.result.error_message = "no entity '" + get->entity + "'";
          if (const auto* set = std::get_if<SetEntityStateRequest>(&request)) response.entity_state = set->state;
          (void)service_call_response(call->service, call->call, call->encoding, encode_sim_response(response));
        });
      }
      return;
    }
    const ClientMessage& m = std::get<ClientMessage>(parsed);
    for (const std::string_view encoding : {"cdr", "json"}) {
      expect_only_errors([&] { decode_twist(encoding, m.payload); });
      expect_only_errors([&] { decode_multi_array(encoding, m.payload); });
      expect_only_errors([&] { decode_joint_state(encoding, m.payload); });
    }
    for (const rescuesim::msg::TypeSupport& type : rescuesim::msg::all_types()) {
      expect_only_errors([&] { decode_message("cdr", type, m.payload); });
      expect_only_errors([&] {
        const std::string once = rescuesim::msg::to_json(decode_message("json", type, m.payload));
        if (rescuesim::msg::to_json(rescuesim::msg::from_json(type, once)) != once) std::abort();
      });
    }
  });
  return 0;
}
