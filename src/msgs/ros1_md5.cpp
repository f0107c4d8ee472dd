// The ROS 1 message checksum as genmsg computes it: parse the .msg text (comments and blank
// lines dropped), write the constants first as "type name=value", then each field as
// "type name" where a message-typed field's type (and its array suffix) is replaced by that
// message's own checksum, join the lines with "\n" and take the MD5.

#include <algorithm>
#include <array>

#include "core/error.h"
#include "msgs/md5.h"
#include "msgs/serialize.h"

namespace rescuesim::msg {

namespace {

constexpr std::array<std::string_view, 16> kBuiltins = {"int8",    "uint8",   "int16", "uint16", "int32",  "uint32",
                                                        "int64",   "uint64",  "float32", "float64", "string", "bool",
                                                        "char",    "byte",    "time",  "duration"};

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// "float64[9]" -> "float64"
std::string_view bare_type(std::string_view t) { return t.substr(0, t.find('[')); }

bool is_builtin(std::string_view t) {
  return std::find(kBuiltins.begin(), kBuiltins.end(), bare_type(t)) != kBuiltins.end();
}

// a field type as genmsg resolves it: Header is std_msgs/Header, a bare name is in this package
std::string resolve(std::string_view bare, std::string_view package) {
  if (bare == "Header") return "std_msgs/Header";
  if (bare.find('/') != std::string_view::npos) return std::string(bare);
  return std::string(package) + "/" + std::string(bare);
}

}  // namespace

std::string ros1_md5_of(std::string_view msg_text, std::string_view package,
                        std::string (*text_of)(std::string_view type)) {
  std::vector<std::string> constants, fields;
  std::size_t start = 0;
  while (start <= msg_text.size()) {
    std::size_t end = msg_text.find('\n', start);
    if (end == std::string_view::npos) end = msg_text.size();
    const std::string_view line = msg_text.substr(start, end - start);
    start = end + 1;

    const std::string_view clean = trim(line.substr(0, line.find('#')));
    if (clean.empty()) continue;
    const auto eq = clean.find('=');
    if (eq != std::string_view::npos) {
      // a constant: "type NAME=value"; a string constant's value is the rest of the raw line
      const auto lhs = words(clean.substr(0, eq));
      if (lhs.size() != 2) throw Error("ros1_md5_of: " + std::string(package) + ": bad constant line '" + std::string(line) + "'");
      const std::string_view value =
          lhs[0] == "string" ? trim(line.substr(line.find('=') + 1)) : trim(clean.substr(eq + 1));
      constants.push_back(std::string(lhs[0]) + " " + std::string(lhs[1]) + "=" + std::string(value));
      continue;
    }
    const auto w = words(clean);
    if (w.size() != 2) throw Error("ros1_md5_of: " + std::string(package) + ": bad field line '" + std::string(line) + "'");
    if (is_builtin(w[0])) {
      fields.push_back(std::string(w[0]) + " " + std::string(w[1]));
    } else {
      const std::string type = resolve(bare_type(w[0]), package);
      const std::string sub_package = type.substr(0, type.find('/'));
      fields.push_back(ros1_md5_of(text_of(type), sub_package, text_of) + " " + std::string(w[1]));
    }
  }

  std::string text;
  for (const auto& c : constants) text += c + "\n";
  for (const auto& f : fields) text += f + "\n";
  if (!text.empty()) text.pop_back();
  return md5_hex(text);
}

}  // namespace rescuesim::msg
