#pragma once
// Test support for the MCAP tests: small files built in memory, written to disk, bytes read back.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bridges/mcap/mcap_reader.h"
#include "bridges/mcap/mcap_writer.h"
#include "support/command.h"

namespace rescuesim::testing {

inline std::vector<std::uint8_t> read_bytes(const std::filesystem::path& p) {
  const std::string s = slurp(p);
  return {s.begin(), s.end()};
}

inline void write_bytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& b) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

inline std::uint64_t u64_at(const std::vector<std::uint8_t>& b, std::size_t at) { return mcap::load_u64(b.data() + at); }
inline std::uint32_t u32_at(const std::vector<std::uint8_t>& b, std::size_t at) { return mcap::load_u32(b.data() + at); }
inline void put_u32_at(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

/// Offset of the first top-level record with opcode `op` (after the magic), or 0.
inline std::size_t first_record(const std::vector<std::uint8_t>& b, mcap::Op op) {
  std::size_t at = mcap::kMagic.size();
  while (at + mcap::kRecordPrefix <= b.size()) {
    if (b[at] == static_cast<std::uint8_t>(op)) return at;
    at += mcap::kRecordPrefix + static_cast<std::size_t>(u64_at(b, at + 1));
  }
  return 0;
}

/// One message as a reader saw it.
struct ReadMessage {
  std::string topic;
  std::uint32_t sequence;
  std::uint64_t log_time, publish_time;
  std::vector<std::uint8_t> data;
  bool operator==(const ReadMessage&) const = default;
};

/// Every message of a file, in file order.
inline std::vector<ReadMessage> all_messages(mcap::McapReader& reader) {
  std::vector<ReadMessage> out;
  reader.read_messages([&](const mcap::Channel& c, const mcap::MessageView& m) {
    out.push_back({c.topic, m.sequence, m.log_time, m.publish_time, {m.data.begin(), m.data.end()}});
    return true;
  });
  return out;
}

}  // namespace rescuesim::testing
