#include "import/scenario/yaml_reader.h"

#include <cmath>
#include <cstdio>

namespace rescuesim {

YamlNode::YamlNode(YAML::Node node, std::string path, std::shared_ptr<const std::string> file)
    : node_(std::move(node)), path_(std::move(path)), file_(std::move(file)), read_(std::make_shared<std::set<std::string>>()) {}

YamlNode YamlNode::parse(const std::string& text, const std::string& file) {
  auto name = std::make_shared<const std::string>(file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error({file, e.mark.line >= 0 ? e.mark.line + 1 : 0, ""}, "YAML syntax error: " + e.msg);
  }
  if (!root || root.IsNull()) throw Error({file, 0, ""}, "the file is empty; expected a YAML mapping of scenario settings");
  if (!root.IsMap()) throw Error({file, root.Mark().line + 1, ""}, "expected a YAML mapping (key: value lines) at the top level");
  return YamlNode(root, "", name);
}

int YamlNode::line() const { return node_ && node_.Mark().line >= 0 ? node_.Mark().line + 1 : 0; }

SourceRef YamlNode::where() const { return {*file_, line(), path_}; }

SourceRef YamlNode::where(const std::string& key) const {
  const YAML::Node n = node_.IsMap() ? node_[key] : YAML::Node();
  const int l = n && n.Mark().line >= 0 ? n.Mark().line + 1 : line();
  return {*file_, l, child_path(key)};
}

std::string YamlNode::child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void YamlNode::fail(const std::string& key, const std::string& message) const { throw Error(where(key), message); }

bool YamlNode::has(const std::string& key) const {
  if (!node_.IsMap()) return false;
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

bool YamlNode::has_sequence(const std::string& key) const { return has(key) && node_[key].IsSequence(); }

std::vector<std::string> YamlNode::strings(const std::string& key, const std::vector<std::string>& fallback) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (n.IsScalar()) return {n.as<std::string>()};
  if (!n.IsSequence()) fail(key, "expected a list of names, e.g. [a, b]");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsScalar()) fail(key, "expected a list of names, e.g. [a, b]");
    out.push_back(n[i].as<std::string>());
  }
  return out;
}

YAML::Node YamlNode::get(const std::string& key) const {
  read_->insert(key);
  if (!node_.IsMap()) return YAML::Node();
  return node_[key];
}

YamlNode YamlNode::map(const std::string& key) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return YamlNode(YAML::Node(YAML::NodeType::Map), child_path(key), file_);
  if (!n.IsMap()) fail(key, "expected a mapping (nested key: value lines)");
  return YamlNode(n, child_path(key), file_);
}

std::vector<YamlNode> YamlNode::sequence(const std::string& key) const {
  YAML::Node n = get(key);
  std::vector<YamlNode> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "expected a list (lines starting with '- ')");
  for (std::size_t i = 0; i < n.size(); ++i) out.emplace_back(n[i], child_path(key) + "[" + std::to_string(i) + "]", file_);
  return out;
}

std::vector<YamlNode> YamlNode::items() const {
  std::vector<YamlNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) out.emplace_back(node_[i], path_ + "[" + std::to_string(i) + "]", file_);
  return out;
}

double YamlNode::number(const std::string& key, double fallback, double lo, double hi) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (!n.IsScalar()) fail(key, "expected a number");
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number, got '" + n.Scalar() + "'");
  }
  if (!std::isfinite(v)) fail(key, "expected a finite number, got '" + n.Scalar() + "'");
  if (v < lo || v > hi) {
    std::string range = lo > -1e300 && hi < 1e300 ? "in [" + message_number(lo) + ", " + message_number(hi) + "]"
                        : lo > -1e300           ? ">= " + message_number(lo)
                                                : "<= " + message_number(hi);
    fail(key, "value " + n.Scalar() + " is out of range; expected a number " + range);
  }
  return v;
}

double YamlNode::required_number(const std::string& key, double lo, double hi) const {
  if (!has(key)) fail(key, "missing required number");
  return number(key, 0, lo, hi);
}

long long YamlNode::integer(const std::string& key, long long fallback, long long lo, long long hi) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  long long v = 0;
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "");
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a whole number, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'");
  }
  if (v < lo || v > hi)
    fail(key, "value " + std::to_string(v) + " is out of range; expected " + std::to_string(lo) + " to " + std::to_string(hi));
  return v;
}

unsigned long long YamlNode::uint64(const std::string& key, unsigned long long fallback) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  try {
    if (!n.IsScalar() || n.Scalar().empty() || n.Scalar()[0] == '-') throw YAML::Exception(n.Mark(), "");
    return n.as<unsigned long long>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a non-negative whole number, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'");
  }
}

bool YamlNode::boolean(const std::string& key, bool fallback) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  try {
    if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "");
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'");
  }
}

std::string YamlNode::string(const std::string& key, const std::string& fallback) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (!n.IsScalar()) fail(key, "expected a text value");
  return n.Scalar();
}

std::string YamlNode::choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const {
  const std::string v = string(key, fallback);
  for (const auto& c : choices) {
    if (c == v) return v;
  }
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "unknown value '" + v + "'; expected one of: " + list);
}

std::vector<double> YamlNode::numbers(const std::string& key, const std::vector<double>& fallback, std::size_t count) const {
  YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) return fallback;
  if (!n.IsSequence() || n.size() != count) fail(key, "expected a list of " + std::to_string(count) + " numbers, like [1, 2]");
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    try {
      out.push_back(n[i].as<double>());
    } catch (const YAML::Exception&) {
      fail(key, "item " + std::to_string(i) + " is not a number");
    }
    if (!std::isfinite(out.back())) fail(key, "item " + std::to_string(i) + " is not a finite number");
  }
  return out;
}

std::string YamlNode::scalar() const {
  if (!node_.IsScalar()) throw Error(where(), "expected a single value");
  return node_.Scalar();
}

void YamlNode::finish() const {
  if (!node_.IsMap()) return;
  std::string known;
  for (const auto& k : *read_) known += (known.empty() ? "" : ", ") + k;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    // a complex key ("? {a: 1}: ...") is legal YAML, but no scenario key is one
    if (!it->first.IsScalar()) throw Error({*file_, it->first.Mark().line + 1, path_}, "a key must be a plain name, not a list or a map");
    const std::string k = it->first.Scalar();
    if (!read_->count(k)) {
      throw Error({*file_, it->first.Mark().line + 1, child_path(k)}, "unknown key '" + k + "'" +
                                                                          (known.empty() ? "" : " (expected one of: " + known + ")"));
    }
  }
}

}  // namespace rescuesim
