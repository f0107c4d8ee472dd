#pragma once
/// The decoders of bridges/common/control_cdr.h as a numbered list of cases, shared by the
/// control_cdr fuzz target (the first input byte picks a case, modulo their number) and by
/// fuzz_make_seeds (one seed per case, with that first byte). A case is one body of one
/// interface in one wire version: every service's request and response, every action topic's
/// message, each in 1.x and 2.x. Decoding may only fail with a message (Decoded::problem); a
/// body that decodes must encode again, and its encoding must decode to a value that encodes
/// to the same bytes (stable after one pass: the first drops padding and what a struct has no
/// place for, such as SpawnEntity's initial_pose stamp).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "bridges/common/control_cdr.h"

namespace rescuesim::fuzz {

struct ControlCase {
  std::string name;  ///< file-name safe: "ResetSimulation_Request_v1"
  /// Decodes `bytes`; on success checks the round trip (aborts when it is not stable).
  void (*run)(std::span<const std::uint8_t> bytes);
  /// The encoding of a default-constructed body (a seed).
  void (*encode_default)(std::vector<std::uint8_t>& out);
};

namespace control_cases_detail {

using control::WireVersion;

template <class T, class Decode, class Encode>
void round_trip(const char* what, std::span<const std::uint8_t> bytes, Decode decode, Encode encode) {
  const control::Decoded<T> d = decode(bytes);
  if (!d.value) {
    if (d.problem.empty()) {
      std::fprintf(stderr, "%s: refused without a reason\n", what);
      std::abort();
    }
    return;
  }
  std::vector<std::uint8_t> once, twice;
  encode(*d.value, once);
  const control::Decoded<T> again = decode(std::span<const std::uint8_t>(once));
  if (!again.value) {
    std::fprintf(stderr, "%s: its own encoding does not decode: %s\n", what, again.problem.c_str());
    std::abort();
  }
  encode(*again.value, twice);
  if (once != twice) {
    std::fprintf(stderr, "%s: re-encoding is not stable (%zu bytes, then %zu)\n", what, once.size(), twice.size());
    std::abort();
  }
}

template <class S, WireVersion V>
void run_request(std::span<const std::uint8_t> b) {
  round_trip<typename S::Request>(
      control::info(S::id).ros_type, b, [](auto s) { return control::decode_request<S>(s, V); },
      [](const auto& x, std::vector<std::uint8_t>& out) { control::encode_request<S>(x, V, out); });
}
template <class S, WireVersion V>
void run_response(std::span<const std::uint8_t> b) {
  round_trip<typename S::Response>(
      control::info(S::id).ros_type, b, [](auto s) { return control::decode_response<S>(s, V); },
      [](const auto& x, std::vector<std::uint8_t>& out) { control::encode_response<S>(x, V, out); });
}
template <class M, WireVersion V>
void run_message(std::span<const std::uint8_t> b) {
  round_trip<typename M::Message>(
      control::info(M::id).ros_type, b, [](auto s) { return control::decode_message<M>(s, V); },
      [](const auto& x, std::vector<std::uint8_t>& out) { control::encode_message<M>(x, V, out); });
}
template <class S, WireVersion V>
void default_request(std::vector<std::uint8_t>& out) {
  control::encode_request<S>({}, V, out);
}
template <class S, WireVersion V>
void default_response(std::vector<std::uint8_t>& out) {
  control::encode_response<S>({}, V, out);
}
template <class M, WireVersion V>
void default_message(std::vector<std::uint8_t>& out) {
  control::encode_message<M>({}, V, out);
}

/// "simulation_interfaces/srv/ResetSimulation" -> "ResetSimulation"
inline std::string short_name(const char* ros_type) {
  const std::string s = ros_type;
  return s.substr(s.rfind('/') + 1);
}

template <WireVersion V>
void add_version(std::vector<ControlCase>& cases) {
  const std::string v = V == WireVersion::v1 ? "_v1" : "_v2";
  std::apply(
      [&](auto... s) {
        ((cases.push_back({short_name(control::info(decltype(s)::id).ros_type) + "_Request" + v,
                           &run_request<decltype(s), V>, &default_request<decltype(s), V>}),
          cases.push_back({short_name(control::info(decltype(s)::id).ros_type) + "_Response" + v,
                           &run_response<decltype(s), V>, &default_response<decltype(s), V>})),
         ...);
      },
      control::AllServices{});
  std::apply(
      [&](auto... m) {
        (cases.push_back({short_name(control::info(decltype(m)::id).ros_type) + v, &run_message<decltype(m), V>,
                          &default_message<decltype(m), V>}),
         ...);
      },
      control::AllMessages{});
}

}  // namespace control_cases_detail

/// Every case, in a fixed order (1.x first, then 2.x; services in AllServices order).
inline const std::vector<ControlCase>& control_cases() {
  static const std::vector<ControlCase> cases = [] {
    std::vector<ControlCase> c;
    control_cases_detail::add_version<control::WireVersion::v1>(c);
    control_cases_detail::add_version<control::WireVersion::v2>(c);
    return c;
  }();
  return cases;
}

/// The index of the case named `name`, or -1.
inline int control_case_index(const std::string& name) {
  const auto& c = control_cases();
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace rescuesim::fuzz
