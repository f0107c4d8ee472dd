#pragma once
/// The Foxglove WebSocket protocol v1 (subprotocol `foxglove.websocket.v1`) as data: the JSON
/// messages the server sends, the binary frame layouts (little endian), and parsers for what
/// clients send. Parsers throw rescuesim::Error with a message fit for a `status` reply
/// ("subscribe: subscriptions[1].channelId: expected an unsigned 32-bit integer").

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/error.h"
#include "msgs/messages.h"
#include "msgs/serialize.h"

namespace rescuesim::foxglove {

/// The subprotocol clients must offer.
inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

/// A server channel as advertised.
struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;          ///< "cdr" or "json"
  std::string schema_name;       ///< "sensor_msgs/msg/LaserScan", "foxglove.SceneUpdate"
  std::string schema;            ///< ros2msg text or JSON Schema
  std::string schema_encoding;   ///< "ros2msg" or "jsonschema"
};

/// Status levels.
enum class StatusLevel { info = 0, warning = 1, error = 2 };

/// {"op":"serverInfo",...} with the given capabilities and client-publish encodings.
std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::vector<std::string>& encodings, const std::vector<std::pair<std::string, std::string>>& metadata,
                        const std::string& session_id);
/// {"op":"advertise","channels":[...]}.
std::string advertise(const std::vector<Channel>& channels);
/// {"op":"unadvertise","channelIds":[...]}: those channels are gone (with every subscription to them).
std::string unadvertise(const std::vector<std::uint32_t>& channel_ids);
/// {"op":"status","level":..,"message":..}.
std::string status(StatusLevel level, const std::string& message);

/// How a service's request or its response is encoded, with its schema (advertiseServices).
struct ServiceMessage {
  std::string encoding;         ///< "json"
  std::string schema_name;      ///< "simulation_interfaces/srv/ResetSimulation_Request"
  std::string schema_encoding;  ///< "jsonschema"
  std::string schema;
};

/// A service the server offers (capability `services`).
struct Service {
  std::uint32_t id = 0;
  std::string name;  ///< "/reset_simulation"
  std::string type;  ///< "simulation_interfaces/srv/ResetSimulation"
  ServiceMessage request, response;
};

/// {"op":"advertiseServices","services":[{id,name,type,request:{encoding,schemaName,
/// schemaEncoding,schema},response:{...}}]}: the current form only. The older
/// requestSchema/responseSchema strings are left out on purpose: a client reads them in the
/// first of the server's supportedEncodings it knows ("cdr" here), not in the service's own.
std::string advertise_services(const std::vector<Service>& services);
/// {"op":"serviceCallFailure","serviceId":..,"callId":..,"message":..}.
std::string service_call_failure(std::uint32_t service, std::uint32_t call, const std::string& message);
/// Binary service call response: 0x03 | u32 service id | u32 call id | u32 encoding length |
/// encoding | payload.
std::vector<std::uint8_t> service_call_response(std::uint32_t service, std::uint32_t call, std::string_view encoding,
                                                std::string_view payload);

/// Binary message data header: 0x01 | u32 subscription id | u64 timestamp (ns).
std::vector<std::uint8_t> message_data_header(std::uint32_t subscription, std::uint64_t timestamp_ns);
/// Binary time: 0x02 | u64 timestamp (ns).
std::vector<std::uint8_t> time_frame(std::uint64_t timestamp_ns);

/// A channel a client advertises for publishing.
struct ClientChannel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;
  std::string schema_name;       ///< may be empty
};

/// Client requests (text frames).
struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  ///< (subscription id, channel id)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct ClientAdvertise {
  std::vector<ClientChannel> channels;
};
struct ClientUnadvertise {
  std::vector<std::uint32_t> channel_ids;
};
/// An op this server knows but does not offer (parameters, connection graph, assets).
struct Unsupported {
  std::string op;
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, ClientAdvertise, ClientUnadvertise, Unsupported>;

/// Parses a client text frame; throws Error for malformed JSON, a missing or unknown `op`, or
/// fields of the wrong type.
ClientRequest parse_client_text(std::string_view text);

/// A client binary frame 0x01 | u32 channel id | payload.
struct ClientMessage {
  std::uint32_t channel = 0;
  std::span<const std::uint8_t> payload;
};
/// A client binary frame 0x02 | u32 service id | u32 call id | u32 encoding length | encoding |
/// payload: a service call request.
struct ServiceCallRequest {
  std::uint32_t service = 0;
  std::uint32_t call = 0;
  std::string encoding;  ///< "json"
  std::span<const std::uint8_t> payload;
};
/// A malformed service call request whose service and call ids could be read, so that it can be
/// answered with a serviceCallFailure.
class ServiceCallError : public Error {
 public:
  ServiceCallError(std::uint32_t service_id, std::uint32_t call_id, std::string message)
      : Error(std::move(message)), service(service_id), call(call_id) {}
  std::uint32_t service, call;
};
using ClientBinary = std::variant<ClientMessage, ServiceCallRequest>;
/// Parses a client binary frame (opcode 0x01 or 0x02); throws Error for an empty frame, an
/// unknown opcode or a frame too short for its header, and ServiceCallError for a service call
/// request whose ids are there but whose encoding length runs past the frame's end.
ClientBinary parse_client_binary(std::span<const std::uint8_t> bytes);

/// Decodes a message of `type` in `encoding` ("cdr" or "json": msg::from_cdr, msg::from_json);
/// throws Error when malformed.
msg::Message decode_message(std::string_view encoding, const msg::TypeSupport& type, std::span<const std::uint8_t> payload);
/// Decodes a geometry_msgs/Twist in `encoding` ("cdr" or "json"); throws Error when malformed.
msg::Twist decode_twist(std::string_view encoding, std::span<const std::uint8_t> payload);
/// Decodes a std_msgs/Float64MultiArray in `encoding`; throws Error when malformed.
msg::Float64MultiArray decode_multi_array(std::string_view encoding, std::span<const std::uint8_t> payload);
/// Decodes a sensor_msgs/JointState in `encoding` ("cdr" or "json"); throws Error when
/// malformed. JSON: `{"name":["lift"],"position":[0.15]}`; `name` is required, `position`,
/// `velocity` and `effort` may be left out (empty).
msg::JointState decode_joint_state(std::string_view encoding, std::span<const std::uint8_t> payload);

}  // namespace rescuesim::foxglove
