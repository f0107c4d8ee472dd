// The table of TypeSupport, one per msg::Message alternative, built once from the field
// lists: names, definitions in both ROS flavours, the ROS 1 MD5 and the JSON Schema.

#include "core/error.h"
#include "msgs/message_fields.h"
#include "msgs/serialize.h"
#include "msgs/type_texts.h"

namespace rescuesim::msg {

namespace {

TypeSupport make_type_support(std::size_t index) {
  TypeSupport t;
  t.variant_index = index;
  t.ros1_name = fields::with_alternative(index, [](auto id) -> std::string {
    return type_name_of<typename decltype(id)::type>();
  });
  const auto slash = t.ros1_name.find('/');
  const std::string package = t.ros1_name.substr(0, slash);
  const std::string type = t.ros1_name.substr(slash + 1);
  t.ros2_name = package + "/msg/" + type;
  t.dds_name = package + "::msg::dds_::" + type + "_";

  const detail::TypeTexts ros1 = detail::definition_texts(index, detail::Flavour::ros1);
  t.ros1_definition = detail::full_definition(ros1);
  t.ros1_md5 = ros1_md5_of(ros1.top, package, [](std::string_view dep) { return detail::ros1_text_of(dep); });
  t.ros2_definition = detail::full_definition(detail::definition_texts(index, detail::Flavour::ros2));
  t.json_schema = detail::json_schema_of(index);
  return t;
}

}  // namespace

const std::vector<TypeSupport>& all_types() {
  static const std::vector<TypeSupport> types = [] {
    std::vector<TypeSupport> v;
    for (std::size_t i = 0; i < std::variant_size_v<Message>; ++i) v.push_back(make_type_support(i));
    return v;
  }();
  return types;
}

const TypeSupport* find_type(std::string_view name) {
  for (const auto& t : all_types()) {
    if (t.ros1_name == name || t.ros2_name == name) return &t;
  }
  return nullptr;
}

const TypeSupport& type_of(const Message& m) { return all_types()[m.index()]; }

}  // namespace rescuesim::msg
