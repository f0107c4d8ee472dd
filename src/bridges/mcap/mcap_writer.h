#pragma once
/// A plain MCAP writer (https://mcap.dev/spec): header, schemas and channels, messages batched
/// into compressed chunks (each followed by its message indexes and flushed to the sink), a
/// data-section CRC, and on close a summary (schemas, channels, statistics, chunk, attachment
/// and metadata indexes), summary offsets and the footer with the summary CRC, so indexed
/// readers (Foxglove, McapIndexedReader) can seek. Single-threaded: one thread calls it.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bridges/mcap/byte_sink.h"
#include "bridges/mcap/compression.h"
#include "bridges/mcap/crc32.h"
#include "bridges/mcap/mcap_records.h"

namespace rescuesim::mcap {

/// Settings of a writer. A chunk is written (and flushed to the sink) as soon as any of its
/// three budgets is spent, so a killed writer loses at most the open chunk; 0 switches a
/// time budget off. The budgets are checked after each message is added.
struct WriterOptions {
  std::string profile = "ros2";               ///< Header.profile
  std::string library = "rescuesim";          ///< Header.library, e.g. "rescuesim 0.1.0"
  Compression compression = Compression::zstd;
  int compression_level = 3;                  ///< zstd level
  std::size_t chunk_size = std::size_t(1) << 20;  ///< uncompressed bytes after which a chunk is written
  /// Log-time budget (s): the chunk is written once a message's log time is this far past the
  /// chunk's first message. Deterministic (a function of the messages alone).
  double chunk_log_seconds = 0;
  /// Wall-time budget (s): the chunk is written once a message arrives this long after the
  /// chunk's first message did. Not deterministic: chunk boundaries then depend on the machine.
  double chunk_wall_seconds = 0;
  /// The wall clock in seconds for chunk_wall_seconds (empty: std::chrono::steady_clock); tests set it.
  std::function<double()> wall_clock;
};

/// What a writer has done so far.
struct WriterStats {
  std::uint64_t messages = 0;
  std::uint64_t chunks = 0;
  std::uint64_t message_bytes = 0;       ///< message payloads
  std::uint64_t uncompressed_bytes = 0;  ///< chunk records before compression
  std::uint64_t compressed_bytes = 0;    ///< chunk records after compression
  std::uint64_t file_bytes = 0;          ///< everything written to the sink
  double compress_seconds = 0;           ///< wall time spent compressing
};

class McapWriter {
 public:
  /// Writes the magic and the Header record.
  McapWriter(std::unique_ptr<ByteSink> sink, WriterOptions options = {});
  /// Closes the file if close() was not called (errors are swallowed there: call close()).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Declares a schema (ids count up from 1); its record goes into the current chunk.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, std::string_view data);
  /// Declares a channel on a schema (ids count up from 1); its record goes into the current chunk.
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            KeyValues metadata = {});
  /// Adds a message (times in ns). Writes the chunk once it holds chunk_size bytes or has spent
  /// a time budget (see WriterOptions).
  void write_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
                     std::span<const std::uint8_t> data);
  /// Writes a Metadata record to the data section at once (outside any chunk).
  void write_metadata(const Metadata& metadata);
  /// Writes an Attachment record to the data section at once (outside any chunk).
  void write_attachment(const Attachment& attachment);
  /// Writes the open chunk now (also done by close()).
  void flush_chunk();
  /// Finishes the file: last chunk, Data End, summary, summary offsets, footer, magic.
  void close();

  const WriterStats& stats() const { return stats_; }
  bool closed() const { return closed_; }

 private:
  /// Writes bytes to the sink, counting them and, in the data section, adding them to its CRC.
  void emit(std::span<const std::uint8_t> bytes);
  void write_summary();
  double wall_now() const;

  std::unique_ptr<ByteSink> sink_;
  WriterOptions options_;
  Compressor compressor_;
  WriterStats stats_;
  std::uint64_t position_ = 0;
  Crc32 data_crc_;
  bool in_data_section_ = true;
  bool closed_ = false;

  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<std::uint64_t> channel_counts_;  ///< per channel id - 1
  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<AttachmentIndex> attachment_indexes_;
  std::vector<MetadataIndex> metadata_indexes_;
  std::uint64_t start_time_ = 0, end_time_ = 0;

  // the open chunk
  std::vector<std::uint8_t> chunk_;
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_entries_;  ///< per channel id - 1
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::uint64_t chunk_first_log_time_ = 0;  ///< log time of the chunk's first message (the log-time budget's origin)
  double chunk_first_wall_ = 0;             ///< wall clock when that message was added
  bool chunk_has_messages_ = false;
  std::vector<std::uint8_t> compressed_, scratch_;
};

}  // namespace rescuesim::mcap
