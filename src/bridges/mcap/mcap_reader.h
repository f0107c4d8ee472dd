#pragma once
/// A strict MCAP reader, for `rescuesim replay` and for tests. Opening a file checks its whole
/// structure before anything is used: the magic at both ends, the Header, the framing of every
/// record in the data section, the data-section CRC, the summary (grouping, CRC, chunk indexes
/// pointing at chunks) and the footer. Reading messages decompresses each chunk (zstd or lz4)
/// and checks its CRC. Every problem is a rescuesim::Error reading
/// "FILE: offset N (Record): what is wrong"; nothing is read out of bounds.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bridges/mcap/mcap_records.h"

namespace rescuesim::mcap {

/// Limits of a reader.
struct ReaderOptions {
  std::uint64_t max_record_bytes = std::uint64_t(1) << 30;  ///< larger records and chunks are refused
};

class McapReader {
 public:
  /// Opens and checks `path`; throws rescuesim::Error naming the file, the offset and the problem.
  explicit McapReader(const std::filesystem::path& path, ReaderOptions options = {});
  ~McapReader();

  const std::filesystem::path& path() const { return path_; }
  std::uint64_t file_size() const { return size_; }
  const Header& header() const { return header_; }
  /// Schemas and channels by id: from the summary, and from the data section outside chunks.
  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  const std::optional<Statistics>& statistics() const { return statistics_; }
  const std::vector<ChunkIndex>& chunk_indexes() const { return chunk_indexes_; }
  /// Every Metadata and Attachment record in the data section, in file order.
  const std::vector<Metadata>& metadata() const { return metadata_; }
  const std::vector<Attachment>& attachments() const { return attachments_; }
  /// The metadata record of that name, or nullptr.
  const Metadata* find_metadata(const std::string& name) const;
  /// The attachment of that name, or nullptr.
  const Attachment* find_attachment(const std::string& name) const;
  /// Number of Chunk records and of messages outside chunks.
  std::size_t chunk_count() const;
  /// The data-section CRC stored in Data End (0: none) and the one computed over the file.
  std::uint32_t stored_data_crc() const { return stored_data_crc_; }
  std::uint32_t computed_data_crc() const { return computed_data_crc_; }

  /// Calls `visit` for every message in file order (which rescuesim writes in log-time order),
  /// with its channel; stops early when `visit` returns false. Checks every chunk's CRC and the
  /// framing of the records inside it.
  void read_messages(const std::function<bool(const Channel&, const MessageView&)>& visit);

 private:
  struct Place {
    std::uint64_t offset;  ///< of the record's opcode
    std::uint8_t op;
    std::uint64_t length;  ///< content bytes
  };
  [[noreturn]] void fail(std::uint64_t offset, const std::string& record, const std::string& what) const;
  void read_at(std::uint64_t offset, std::uint64_t n, std::vector<std::uint8_t>& out);
  std::uint64_t scan_data_section();
  void scan_summary(std::uint64_t data_end);
  void add_schema(const Schema& s, std::uint64_t offset, const char* where);
  void add_channel(const Channel& c, std::uint64_t offset, const char* where, bool schema_needed = true);

  std::filesystem::path path_;
  ReaderOptions options_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  Header header_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::optional<Statistics> statistics_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<Metadata> metadata_;
  std::vector<Attachment> attachments_;
  std::vector<Place> message_records_;  ///< chunks and lone messages, in file order
  std::uint32_t stored_data_crc_ = 0, computed_data_crc_ = 0;
};

}  // namespace rescuesim::mcap
