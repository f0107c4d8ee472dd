// JSON Schemas (draft-07) of to_json's output, from the same field lists. Kept to the subset
// Foxglove reads (one "type" string per property, "contentEncoding": "base64" for bytes): so a
// float that is written as null (non-finite) is still declared "number", as the description says.

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "msgs/message_fields.h"
#include "msgs/type_texts.h"

namespace rescuesim::msg::detail {

namespace {

using fields::Name;
using Json = nlohmann::ordered_json;

template <class T>
Json scalar_schema() {
  if constexpr (std::is_same_v<T, std::string>) return {{"type", "string"}};
  else if constexpr (std::is_same_v<T, bool>) return {{"type", "boolean"}};
  else if constexpr (std::is_floating_point_v<T>) return {{"type", "number"}};
  else return {{"type", "integer"}};
}

Json time_schema() {
  return {{"type", "object"},
          {"properties", {{"sec", {{"type", "integer"}}}, {"nsec", {{"type", "integer"}}}}},
          {"required", {"sec", "nsec"}}};
}

class SchemaBuilder {
 public:
  Json object(const std::string& title) const {
    return {{"title", title}, {"type", "object"}, {"properties", properties_}, {"required", required_}};
  }

  template <class T>
  void value(Name n, const T&) {
    property(n, scalar_schema<T>());
  }
  void time(Name n, const SimTime&) { property(n, time_schema()); }
  void header(Name n, const Header&) {
    SchemaBuilder h;
    h.time("stamp", SimTime{});
    h.value("frame_id", std::string());
    property(n, h.object("std_msgs/Header"));
  }
  template <class T, std::size_t N>
  void array(Name n, const std::array<T, N>&) {
    property(n, {{"type", "array"}, {"items", scalar_schema<T>()}, {"minItems", N}, {"maxItems", N}});
  }
  template <class T>
  void sequence(Name n, const std::vector<T>&) {
    if constexpr (std::is_same_v<T, std::uint8_t>) {
      property(n, {{"type", "string"}, {"contentEncoding", "base64"}});
    } else {
      property(n, {{"type", "array"}, {"items", scalar_schema<T>()}});
    }
  }
  template <class F>
  void message(Name n, const char* type, F&& f) {
    SchemaBuilder child;
    f(child);
    property(n, child.object(type));
  }
  template <class E, class F>
  void messages(Name n, const char* type, const std::vector<E>&, F&& f) {
    SchemaBuilder child;
    E e{};
    f(child, e);
    property(n, {{"type", "array"}, {"items", child.object(type)}});
  }
  void constant(const char*, const char*, const char*) {}

 private:
  void property(Name n, Json schema) {
    properties_[n.ros1] = std::move(schema);
    required_.push_back(n.ros1);
  }

  Json properties_ = Json::object();
  Json required_ = Json::array();
};

}  // namespace

std::string json_schema_of(std::size_t variant_index) {
  RS_DEMAND(variant_index < std::variant_size_v<Message>, "json_schema_of: variant index out of range");
  return fields::with_alternative(variant_index, [&](auto id) {
    using T = typename decltype(id)::type;
    SchemaBuilder b;
    static const T m{};  // a prototype: only the field types matter
    fields::visit_fields(b, m);
    Json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"}};
    schema.update(b.object(type_name_of<T>()));
    schema["description"] = std::string(type_name_of<T>()) +
                            " as rescuesim writes it in JSON: ROS 1 field names, stamps as {sec, nsec}, "
                            "uint8[] as base64, non-finite floats as null";
    return schema.dump();
  });
}

}  // namespace rescuesim::msg::detail
