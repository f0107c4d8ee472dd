#pragma once
/// Strict reading of YAML input: every value is read through a `YamlNode` that knows its key
/// path (e.g. `robots[0].sensors.lidar.fov`) and line, checks types and ranges, and reports
/// keys nobody read as unknown. Errors name the file, line and key path.

#include <yaml-cpp/yaml.h>

#include <array>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"

namespace rescuesim {

/// A YAML mapping or value being read, with its place in the file.
class YamlNode {
 public:
  YamlNode(YAML::Node node, std::string path, std::shared_ptr<const std::string> file);

  /// Parses YAML text; throws Error with file and line on syntax errors.
  static YamlNode parse(const std::string& text, const std::string& file);

  bool has(const std::string& key) const;
  /// True when the value at `key` is a list (without marking it read).
  bool has_sequence(const std::string& key) const;
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_null() const { return !node_ || node_.IsNull(); }
  const std::string& path() const { return path_; }
  int line() const;
  /// Where this node is, for messages.
  SourceRef where() const;
  SourceRef where(const std::string& key) const;

  /// The child mapping at `key` (marks it read); throws when it is not a mapping.
  YamlNode map(const std::string& key) const;
  /// Items of the sequence at `key` (marks it read); throws when it is not a sequence.
  std::vector<YamlNode> sequence(const std::string& key) const;
  /// Items when this node itself is a sequence.
  std::vector<YamlNode> items() const;

  /// Reads a number in [lo, hi]; `fallback` when absent. Throws naming the key otherwise.
  double number(const std::string& key, double fallback, double lo = -1e300, double hi = 1e300) const;
  /// Reads a number that must be present.
  double required_number(const std::string& key, double lo = -1e300, double hi = 1e300) const;
  /// Reads an integer in [lo, hi].
  long long integer(const std::string& key, long long fallback, long long lo, long long hi) const;
  /// Reads an unsigned 64-bit integer (seeds).
  unsigned long long uint64(const std::string& key, unsigned long long fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// Reads a string that must be one of `choices`.
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const;
  /// Reads a list of strings (`fallback` when absent).
  std::vector<std::string> strings(const std::string& key, const std::vector<std::string>& fallback) const;
  /// Reads a fixed-length list of numbers.
  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback, std::size_t count) const;

  /// The value of this node itself as text (for scalars).
  std::string scalar() const;

  /// Throws Error naming the first key of this mapping that was never read.
  void finish() const;

 private:
  YAML::Node get(const std::string& key) const;
  std::string child_path(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<std::set<std::string>> read_;  ///< keys read from this mapping
};

}  // namespace rescuesim
