#pragma once
/// MCAP records (https://mcap.dev/spec, major version 0) as plain structs: how each is laid out
/// in bytes (`append`, for the writer) and read back (`parse_*`, bounds-checked, for the
/// reader). Every record is `opcode (u8) | content length (u64) | content`; integers are little
/// endian; strings, maps and arrays are prefixed by their byte length (u32).

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rescuesim::mcap {

/// The 8 bytes at both ends of an MCAP file: 0x89 "MCAP" '0' "\r\n" ('0' = major version 0).
inline constexpr std::array<std::uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

/// Record opcodes.
enum class Op : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  attachment = 0x09,
  attachment_index = 0x0A,
  statistics = 0x0B,
  metadata = 0x0C,
  metadata_index = 0x0D,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

/// "Chunk" for 0x06 and so on; "record 0x42" for opcodes this reader does not know.
std::string op_name(std::uint8_t op);

/// Bytes before a record's content: opcode (1) and content length (8).
inline constexpr std::size_t kRecordPrefix = 9;
/// A whole Footer record: prefix + summary_start + summary_offset_start + summary_crc.
inline constexpr std::size_t kFooterRecordSize = kRecordPrefix + 8 + 8 + 4;
/// A whole Data End record: prefix + data_section_crc.
inline constexpr std::size_t kDataEndRecordSize = kRecordPrefix + 4;

/// Map<string, string> entries in the order they are written (keys unique).
using KeyValues = std::vector<std::pair<std::string, std::string>>;

/// The first record: which profile the file follows ("ros2") and who wrote it.
struct Header {
  std::string profile;
  std::string library;
};

/// The last record: where the summary and summary offset sections start (0: none).
struct Footer {
  std::uint64_t summary_start = 0;         ///< file offset of the first summary record
  std::uint64_t summary_offset_start = 0;  ///< file offset of the first Summary Offset record
  std::uint32_t summary_crc = 0;           ///< CRC-32 from summary_start through the footer's summary_offset_start field
};

/// A message type description (`ros2msg` text for the ros2 profile).
struct Schema {
  std::uint16_t id = 0;        ///< unique in the file, never 0
  std::string name;            ///< "sensor_msgs/msg/LaserScan"
  std::string encoding;        ///< "ros2msg"
  std::vector<std::uint8_t> data;
};

/// A stream of messages on one topic.
struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  ///< "cdr"
  KeyValues metadata;            ///< ros2 profile: offered_qos_profiles
};

/// A message record's fields, with its data viewed in place.
struct MessageView {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;       ///< ns
  std::uint64_t publish_time = 0;   ///< ns
  std::span<const std::uint8_t> data;
};

/// A chunk's fields before its records, and its (still compressed) records viewed in place.
struct ChunkView {
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;          ///< "zstd", "lz4" or "" (none)
  std::span<const std::uint8_t> records;
};

/// Where a chunk's messages on one channel are: (log_time, offset in the uncompressed records).
struct MessageIndex {
  std::uint16_t channel_id = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> entries;
};

/// Where a chunk and its message indexes are (summary section).
struct ChunkIndex {
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;          ///< file offset of the Chunk record
  std::uint64_t chunk_length = 0;                ///< whole record, prefix included
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;  ///< channel -> file offset
  std::uint64_t message_index_length = 0;        ///< all message index records after the chunk
  std::string compression;
  std::uint64_t compressed_size = 0, uncompressed_size = 0;
};

/// A named file stored in the recording.
struct Attachment {
  std::uint64_t log_time = 0, create_time = 0;
  std::string name;
  std::string media_type;          ///< MIME type, e.g. "application/yaml"
  std::vector<std::uint8_t> data;
};

/// Where an attachment is (summary section).
struct AttachmentIndex {
  std::uint64_t offset = 0, length = 0;
  std::uint64_t log_time = 0, create_time = 0, data_size = 0;
  std::string name, media_type;
};

/// Counts over the whole file (summary section).
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0, attachment_count = 0, metadata_count = 0, chunk_count = 0;
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

/// Named key-value pairs (rescuesim writes the scenario, seed and version in one).
struct Metadata {
  std::string name;
  KeyValues entries;
};

/// Where a metadata record is (summary section).
struct MetadataIndex {
  std::uint64_t offset = 0, length = 0;
  std::string name;
};

/// Where the summary records of one opcode are.
struct SummaryOffset {
  std::uint8_t group_opcode = 0;
  std::uint64_t group_start = 0, group_length = 0;
};

/// Appends a whole record (opcode, length, content) to `out`.
void append(std::vector<std::uint8_t>& out, const Header& r);
void append(std::vector<std::uint8_t>& out, const Footer& r);
void append(std::vector<std::uint8_t>& out, const Schema& r);
void append(std::vector<std::uint8_t>& out, const Channel& r);
void append(std::vector<std::uint8_t>& out, const MessageIndex& r);
void append(std::vector<std::uint8_t>& out, const ChunkIndex& r);
void append(std::vector<std::uint8_t>& out, const Attachment& r);
void append(std::vector<std::uint8_t>& out, const AttachmentIndex& r);
void append(std::vector<std::uint8_t>& out, const Statistics& r);
void append(std::vector<std::uint8_t>& out, const Metadata& r);
void append(std::vector<std::uint8_t>& out, const MetadataIndex& r);
void append(std::vector<std::uint8_t>& out, const SummaryOffset& r);
/// A Message record.
void append_message(std::vector<std::uint8_t>& out, std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                    std::uint64_t publish_time, std::span<const std::uint8_t> data);
/// A Chunk record up to its records field: the caller writes the `chunk.records.size()` bytes
/// of (compressed) records right after, so big chunks need not be copied.
void append_chunk_prefix(std::vector<std::uint8_t>& out, const ChunkView& chunk);
/// A Data End record.
void append_data_end(std::vector<std::uint8_t>& out, std::uint32_t data_section_crc);

/// Malformed record content; the message names the record and field ("Channel: topic: string of
/// 4000 bytes, 12 left"). Readers add the file and offset.
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parsers of record content (the bytes after opcode and length). Fields past the known ones
/// are ignored, as the spec asks; missing or overlong fields throw FormatError.
Header parse_header(std::span<const std::uint8_t> content);
Footer parse_footer(std::span<const std::uint8_t> content);
Schema parse_schema(std::span<const std::uint8_t> content);
Channel parse_channel(std::span<const std::uint8_t> content);
MessageView parse_message(std::span<const std::uint8_t> content);
ChunkView parse_chunk(std::span<const std::uint8_t> content);
MessageIndex parse_message_index(std::span<const std::uint8_t> content);
ChunkIndex parse_chunk_index(std::span<const std::uint8_t> content);
/// Also checks the attachment's CRC (when not 0).
Attachment parse_attachment(std::span<const std::uint8_t> content);
AttachmentIndex parse_attachment_index(std::span<const std::uint8_t> content);
Statistics parse_statistics(std::span<const std::uint8_t> content);
Metadata parse_metadata(std::span<const std::uint8_t> content);
MetadataIndex parse_metadata_index(std::span<const std::uint8_t> content);
SummaryOffset parse_summary_offset(std::span<const std::uint8_t> content);
/// The data section CRC of a Data End record.
std::uint32_t parse_data_end(std::span<const std::uint8_t> content);

/// Little-endian integers at a position (the caller has checked the bounds).
std::uint64_t load_u64(const std::uint8_t* p);
std::uint32_t load_u32(const std::uint8_t* p);

}  // namespace rescuesim::mcap
