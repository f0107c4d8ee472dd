#include "bridges/ros1/ros1_endpoint.h"

#include <algorithm>
#include <cctype>

namespace rescuesim {

namespace {

bool set(const char* v) { return v != nullptr && *v != '\0'; }

/// The host part of "scheme://host:port/path" (brackets kept off IPv6 literals).
std::string host_of(const std::string& uri) {
  std::string rest = uri;
  if (const auto scheme = rest.find("://"); scheme != std::string::npos) rest = rest.substr(scheme + 3);
  rest = rest.substr(0, rest.find('/'));
  if (!rest.empty() && rest[0] == '[') return rest.substr(1, rest.find(']') - 1);
  return rest.substr(0, rest.find(':'));
}

}  // namespace

bool is_loopback_uri(const std::string& uri) {
  std::string host = host_of(uri);
  std::transform(host.begin(), host.end(), host.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0 || host.rfind("localhost.", 0) == 0;
}

Ros1Endpoint resolve_ros1_endpoint(const char* master_uri_env, const char* hostname_env, const char* ip_env) {
  Ros1Endpoint e;
  e.master_uri = set(master_uri_env) ? master_uri_env : "http://localhost:11311";
  // the user's own choice wins; else a local master means a local node
  if (!set(hostname_env) && !set(ip_env) && is_loopback_uri(e.master_uri)) e.hostname = "localhost";
  return e;
}

}  // namespace rescuesim
