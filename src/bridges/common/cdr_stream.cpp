#include "bridges/common/cdr_stream.h"

#include <cstdio>

namespace rescuesim::cdr {

namespace {
constexpr std::int64_t kNsPerSec = 1'000'000'000;
}

Writer::Writer(std::vector<std::uint8_t>& out, const char* type) : out_(&out), type_(type) {
  // CDR_LE: representation identifier 0x0001 (big-endian on the wire); options: no padding
  out.insert(out.end(), {0x00, 0x01, 0x00, 0x00});
  base_ = out.size();
}

void Writer::string(const char* name, const std::string& s) {
  put<std::uint32_t>(count(name, s.size() + 1, kUnbounded));
  if (out_ != nullptr) {
    std::uint8_t* p = reserve(s.size() + 1);
    if (!s.empty()) std::memcpy(p, s.data(), s.size());
    p[s.size()] = 0;
  }
  pos_ += s.size() + 1;
}

void Writer::stamp(const char*, std::int64_t ns) {
  // floor division, so that a negative stamp keeps 0 <= nanosec < 1e9
  std::int64_t sec = ns / kNsPerSec;
  std::int64_t nsec = ns % kNsPerSec;
  if (nsec < 0) {
    sec -= 1;
    nsec += kNsPerSec;
  }
  constexpr std::int64_t lo = std::numeric_limits<std::int32_t>::min(), hi = std::numeric_limits<std::int32_t>::max();
  if (sec < lo) {
    sec = lo;
    nsec = 0;
  } else if (sec > hi) {
    sec = hi;
    nsec = kNsPerSec - 1;
  }
  put<std::int32_t>(static_cast<std::int32_t>(sec));
  put<std::uint32_t>(static_cast<std::uint32_t>(nsec));
}

std::uint32_t Writer::count(const char* name, std::size_t n, std::uint32_t bound) const {
  const char* field = name != nullptr ? name : "";
  if (n >= std::numeric_limits<std::uint32_t>::max()) {
    throw Error(std::string(type_) + ": " + field + ": " + std::to_string(n) + " elements do not fit a uint32 length");
  }
  if (bound != kUnbounded && n > bound) {
    throw Error(std::string(type_) + ": " + field + ": " + std::to_string(n) +
                " elements in a sequence bounded to " + std::to_string(bound));
  }
  return static_cast<std::uint32_t>(n);
}

std::optional<std::endian> xcdr1_byte_order(std::span<const std::uint8_t> cdr) {
  if (cdr.size() < kEncapsulationSize || cdr[0] != 0x00 || cdr[1] > 0x01) return std::nullopt;
  return cdr[1] == 0x01 ? std::endian::little : std::endian::big;
}

Reader::Reader(std::span<const std::uint8_t> cdr, const char* type, Encapsulations accept) : type_(type) {
  if (cdr.size() < kEncapsulationSize) {
    throw Error(std::string(type) + ": CDR data of " + std::to_string(cdr.size()) +
                " bytes is shorter than the 4-byte encapsulation header");
  }
  const std::optional<std::endian> order = xcdr1_byte_order(cdr);
  const bool either = accept == Encapsulations::either_endian;
  if (!order || (*order == std::endian::big && !either)) {
    char id[8];
    std::snprintf(id, sizeof id, "%02x %02x", cdr[0], cdr[1]);
    throw Error(std::string(type) + ": encapsulation " + id +
                (order ? " (big-endian CDR) is not supported" : " is not supported") +
                "; expected 00 01 (XCDR1 little endian)" + (either ? " or 00 00 (XCDR1 big endian)" : ""));
  }
  order_ = *order;
  padding_ = cdr[3] & 0x03u;
  p_ = cdr.data() + kEncapsulationSize;
  n_ = cdr.size() - kEncapsulationSize;
}

void Reader::string(const char* name, std::string& s) {
  const std::uint32_t len = get<std::uint32_t>(name);
  if (len == 0) fail(name, "string length 0 (a CDR string counts its terminating NUL)");
  need(name, len, 0);
  if (p_[pos_ + len - 1] != 0) fail(name, "string of " + std::to_string(len) + " bytes does not end in NUL");
  s.assign(reinterpret_cast<const char*>(p_ + pos_), len - 1);
  pos_ += len;
}

void Reader::stamp(const char* name, std::int64_t& ns) {
  path_.push_back({name, -1});
  const auto sec = get<std::int32_t>("sec");
  const auto nanosec = get<std::uint32_t>("nanosec");
  path_.pop_back();
  ns = std::int64_t{sec} * kNsPerSec + std::int64_t{nanosec};
}

void Reader::finish() const {
  const std::size_t trailing = left();
  if (trailing == 0 || trailing <= padding_) return;
  // rmw_cyclonedds's unannounced zeros up to the next multiple of 4
  if (trailing < 4 && (pos_ + trailing) % 4 == 0) {
    bool zeros = true;
    for (std::size_t i = pos_; i < n_; ++i) zeros = zeros && p_[i] == 0;
    if (zeros) return;
  }
  fail(nullptr, std::to_string(trailing) + " trailing bytes after the message" +
                    (padding_ != 0 ? " (the encapsulation options allow " + std::to_string(padding_) + ")" : ""));
}

void Reader::fail(const char* field, const std::string& what) const {
  std::string path;
  for (const auto& s : path_) {
    if (s.name != nullptr && *s.name != '\0') {
      if (!path.empty()) path += '.';
      path += s.name;
    }
    if (s.index >= 0) path += '[' + std::to_string(s.index) + ']';
  }
  if (field != nullptr && *field != '\0') {
    if (!path.empty()) path += '.';
    path += field;
  }
  throw Error(std::string(type_) + ": " + (path.empty() ? "" : path + ": ") + what);
}

void Reader::need(const char* field, std::size_t bytes, std::size_t pad) const {
  if (bytes > left()) {
    fail(field, std::to_string(bytes) + (bytes == 1 ? " byte needed" : " bytes needed") +
                    (pad != 0 ? " (" + std::to_string(pad) + " of them alignment padding)" : std::string()) + ", " +
                    std::to_string(left()) + " left");
  }
}

std::uint32_t Reader::count(const char* field, std::size_t min_size, std::uint32_t bound, bool exact) {
  const std::uint32_t n = get<std::uint32_t>(field);
  if (bound != kUnbounded && n > bound) {
    fail(field, "sequence of " + std::to_string(n) + " elements, but it is bounded to " + std::to_string(bound));
  }
  const std::uint64_t bytes = std::uint64_t{n} * min_size;
  if (bytes > left()) {
    fail(field, "sequence of " + std::to_string(n) + " elements needs " + (exact ? "" : "at least ") +
                    std::to_string(bytes) + " bytes, " + std::to_string(left()) + " left");
  }
  return n;
}

}  // namespace rescuesim::cdr
