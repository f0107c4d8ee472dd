#include "core/error.h"

#include <algorithm>
#include <cstdio>

namespace rescuesim {

std::string message_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

std::string SourceRef::str() const {
  std::string s = file;
  if (line > 0) s += (s.empty() ? "line " : ":") + std::to_string(line);
  if (!element.empty()) s += (s.empty() ? "" : ": ") + element;
  return s;
}

namespace {
std::string compose(const SourceRef& where, const std::string& message) {
  const std::string w = where.str();
  return w.empty() ? message : w + ": " + message;
}
}  // namespace

Error::Error(SourceRef where, std::string message)
    : std::runtime_error(compose(where, message)), where_(std::move(where)), message_(std::move(message)) {}

std::string Diagnostic::str() const {
  return compose(where, std::string(severity == Severity::warning ? "warning: " : "error: ") + message);
}

void Diagnostics::warn(SourceRef where, std::string message) {
  items_.push_back({Severity::warning, std::move(where), std::move(message)});
}

void Diagnostics::error(SourceRef where, std::string message) {
  items_.push_back({Severity::error, std::move(where), std::move(message)});
}

void Diagnostics::append(const Diagnostics& other) {
  items_.insert(items_.end(), other.items_.begin(), other.items_.end());
}

bool Diagnostics::has_errors() const { return error_count() > 0; }

int Diagnostics::error_count() const {
  return static_cast<int>(std::count_if(items_.begin(), items_.end(),
                                        [](const Diagnostic& d) { return d.severity == Severity::error; }));
}

int Diagnostics::warning_count() const { return static_cast<int>(items_.size()) - error_count(); }

void Diagnostics::throw_if_errors() const {
  if (!has_errors()) return;
  // the first error keeps its source reference; the others follow, one per line
  const Diagnostic* first = nullptr;
  std::string rest;
  for (const auto& d : items_) {
    if (d.severity != Severity::error) continue;
    if (!first) {
      first = &d;
    } else {
      rest.push_back('\n');
      rest.append(compose(d.where, d.message));
    }
  }
  throw Error(first->where, first->message + rest);
}

void demand_failed(const char* condition, const char* file, int line, const char* message) {
  std::fprintf(stderr, "rescuesim: internal error at %s:%d: %s (%s)\n", file, line, message, condition);
  std::abort();
}

}  // namespace rescuesim
