#pragma once
/// The texts behind TypeSupport (internal to msgs/): .msg definitions in ROS 1 and ROS 2
/// flavour and JSON Schemas, all generated from the field lists in msgs/message_fields.h.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rescuesim::msg::detail {

/// Which ROS the definition text is for: ROS 1 (`time`, Header with seq) or ROS 2
/// (`builtin_interfaces/Time`, Header without seq, CameraInfo's lowercase d/k/r/p).
enum class Flavour { ros1, ros2 };

/// One message type's own .msg text (comment-free) and its dependencies' texts, the
/// dependencies depth-first in field order, each once (as gendeps emits them).
struct TypeTexts {
  std::string top;                                          ///< the type's own fields
  std::vector<std::pair<std::string, std::string>> deps;    ///< ("pkg/Type", text)
};

/// The definition texts of msg::Message alternative `variant_index`.
TypeTexts definition_texts(std::size_t variant_index, Flavour flavour);
/// The full definition: top text, then per dependency a line of 80 '=', "MSG: pkg/Type" and its text.
std::string full_definition(const TypeTexts& texts);
/// The ROS 1 .msg text of any type our messages use ("std_msgs/Header", "geometry_msgs/Pose"),
/// for ros1_md5_of; throws Error for an unknown type.
std::string ros1_text_of(std::string_view type);
/// The JSON Schema (draft-07) of to_json's output for alternative `variant_index`.
std::string json_schema_of(std::size_t variant_index);

}  // namespace rescuesim::msg::detail
