// .msg definition texts from the field lists: each field becomes "type name", each nested
// message a dependency whose text is built the first time it is met (so the dependency list
// comes out depth-first in field order, each type once, as gendeps writes it).

#include <map>

#include "core/error.h"
#include "msgs/message_fields.h"
#include "msgs/type_texts.h"

namespace rescuesim::msg::detail {

namespace {

using fields::Name;

template <class T>
constexpr const char* primitive_name() {
  if constexpr (std::is_same_v<T, std::string>) return "string";
  else if constexpr (std::is_same_v<T, bool>) return "bool";
  else if constexpr (std::is_same_v<T, float>) return "float32";
  else if constexpr (std::is_same_v<T, double>) return "float64";
  else if constexpr (std::is_same_v<T, std::int8_t>) return "int8";
  else if constexpr (std::is_same_v<T, std::uint8_t>) return "uint8";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "int32";
  else if constexpr (std::is_same_v<T, std::uint32_t>) return "uint32";
  else static_assert(sizeof(T) == 0, "no ROS name for this field type");
}

std::string package_of(std::string_view type) { return std::string(type.substr(0, type.find('/'))); }

class DefinitionBuilder {
 public:
  DefinitionBuilder(Flavour flavour, std::string package, TypeTexts& texts)
      : flavour_(flavour), package_(std::move(package)), texts_(texts) {}

  std::string text() const {
    std::string t;
    for (const auto& l : lines_) t += l + "\n";
    if (!t.empty()) t.pop_back();
    return t;
  }

  template <class T>
  void value(Name n, const T&) {
    line(primitive_name<T>(), n);
  }
  void time(Name n, const SimTime&) {
    if (flavour_ == Flavour::ros1) {
      line("time", n);
    } else {
      line(ref("builtin_interfaces/Time"), n);
      dependency("builtin_interfaces/Time", [](DefinitionBuilder& b) {
        b.lines_.push_back("int32 sec");
        b.lines_.push_back("uint32 nanosec");
      });
    }
  }
  void header(Name n, const Header&) {
    line(flavour_ == Flavour::ros1 ? "Header" : ref("std_msgs/Header"), n);
    dependency("std_msgs/Header", [](DefinitionBuilder& b) {
      if (b.flavour_ == Flavour::ros1) b.lines_.push_back("uint32 seq");
      b.time("stamp", SimTime{});
      b.value("frame_id", std::string());
    });
  }
  template <class T, std::size_t N>
  void array(Name n, const std::array<T, N>&) {
    line(std::string(primitive_name<T>()) + "[" + std::to_string(N) + "]", n);
  }
  template <class T>
  void sequence(Name n, const std::vector<T>&) {
    line(std::string(primitive_name<T>()) + "[]", n);
  }
  template <class F>
  void message(Name n, const char* type, F&& f) {
    line(ref(type), n);
    dependency(type, f);
  }
  template <class E, class F>
  void messages(Name n, const char* type, const std::vector<E>&, F&& f) {
    line(ref(type) + "[]", n);
    dependency(type, [&](DefinitionBuilder& b) {
      E e{};
      f(b, e);
    });
  }
  void constant(const char* type, const char* name, const char* value) {
    lines_.push_back(std::string(type) + " " + name + "=" + value);
  }

 private:
  // a type as a .msg names it: short inside its own package, qualified elsewhere
  std::string ref(std::string_view type) const {
    return package_of(type) == package_ ? std::string(type.substr(type.find('/') + 1)) : std::string(type);
  }
  void line(const std::string& type, Name n) {
    lines_.push_back(type + " " + (flavour_ == Flavour::ros1 ? n.ros1 : n.ros2));
  }
  // records `type`'s text the first time it is met; its slot is taken before its own
  // dependencies are visited, which gives gendeps' depth-first order
  template <class F>
  void dependency(std::string_view type, F&& f) {
    for (const auto& d : texts_.deps) {
      if (d.first == type) return;
    }
    const std::size_t slot = texts_.deps.size();
    texts_.deps.emplace_back(std::string(type), std::string());
    DefinitionBuilder child(flavour_, package_of(type), texts_);
    f(child);
    texts_.deps[slot].second = child.text();
  }

  Flavour flavour_;
  std::string package_;
  TypeTexts& texts_;
  std::vector<std::string> lines_;
};

}  // namespace

TypeTexts definition_texts(std::size_t variant_index, Flavour flavour) {
  RS_DEMAND(variant_index < std::variant_size_v<Message>, "definition_texts: variant index out of range");
  return fields::with_alternative(variant_index, [&](auto id) {
    using T = typename decltype(id)::type;
    TypeTexts texts;
    DefinitionBuilder b(flavour, package_of(type_name_of<T>()), texts);
    const T m{};
    fields::visit_fields(b, m);
    texts.top = b.text();
    return texts;
  });
}

std::string full_definition(const TypeTexts& texts) {
  std::string out = texts.top + "\n";
  for (const auto& [name, text] : texts.deps) {
    out += std::string(80, '=') + "\nMSG: " + name + "\n" + text + "\n";
  }
  return out;
}

std::string ros1_text_of(std::string_view type) {
  // every type's own text and its dependencies', gathered once
  static const std::map<std::string, std::string, std::less<>> texts = [] {
    std::map<std::string, std::string, std::less<>> all;
    for (std::size_t i = 0; i < std::variant_size_v<Message>; ++i) {
      TypeTexts t = definition_texts(i, Flavour::ros1);
      fields::with_alternative(i, [&](auto id) {
        using T = typename decltype(id)::type;
        all.emplace(type_name_of<T>(), t.top);
      });
      for (auto& [name, text] : t.deps) all.emplace(name, text);
    }
    return all;
  }();
  const auto it = texts.find(type);
  if (it == texts.end()) throw Error("ros1_text_of: unknown message type '" + std::string(type) + "'");
  return it->second;
}

}  // namespace rescuesim::msg::detail
