#pragma once
/// The three error channels (see docs/style.md): `RS_DEMAND` for bugs, `Error` for bad input at a
/// file or API boundary (its text names the file, line or element and what was expected), and
/// counted warnings in `Diagnostics` for problems a user should hear about but that do not stop
/// the work.

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace rescuesim {

/// Where a problem is: a file, a 1-based line (0 = unknown) and an element or key path.
struct SourceRef {
  std::string file;     ///< path as the user gave it, or "" for in-memory input
  int line = 0;         ///< 1-based line, 0 when unknown
  std::string element;  ///< e.g. `<rect id="w3">` or `robots[0].sensors.lidar.fov`

  /// "file:line: element" with the empty parts left out.
  std::string str() const;
};

/// A number as messages show it: printf's %g (6 significant digits, no trailing zeros).
std::string message_number(double v);

/// Bad input: thrown at file and API boundaries; `what()` reads "file:line: element: message".
class Error : public std::runtime_error {
 public:
  Error(SourceRef where, std::string message);
  explicit Error(std::string message) : Error(SourceRef{}, std::move(message)) {}

  const SourceRef& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceRef where_;
  std::string message_;
};

enum class Severity { warning, error };

/// One problem found while reading or validating input.
struct Diagnostic {
  Severity severity = Severity::error;
  SourceRef where;
  std::string message;

  std::string str() const;  ///< "file:line: element: warning: message"
};

/// Problems collected during one import or validation, so a user sees all of them at once.
class Diagnostics {
 public:
  void warn(SourceRef where, std::string message);
  void error(SourceRef where, std::string message);
  void append(const Diagnostics& other);

  bool has_errors() const;
  int error_count() const;
  int warning_count() const;
  const std::vector<Diagnostic>& items() const { return items_; }

  /// Throws an `Error` holding every error message (one per line) when there are errors.
  void throw_if_errors() const;

 private:
  std::vector<Diagnostic> items_;
};

[[noreturn]] void demand_failed(const char* condition, const char* file, int line, const char* message);

}  // namespace rescuesim

/// Aborts with a message when `cond` is false: for bugs in rescuesim, never for bad input.
#define RS_DEMAND(cond, msg)                                                   \
  do {                                                                         \
    if (!(cond)) ::rescuesim::demand_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
