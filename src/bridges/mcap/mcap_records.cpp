#include "bridges/mcap/mcap_records.h"

#include <cstring>

#include "bridges/mcap/crc32.h"

namespace rescuesim::mcap {

namespace {

// writing: little-endian fields appended to a byte vector

void put_u8(std::vector<std::uint8_t>& o, std::uint8_t v) { o.push_back(v); }
void put_u16(std::vector<std::uint8_t>& o, std::uint16_t v) {
  o.push_back(static_cast<std::uint8_t>(v));
  o.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::vector<std::uint8_t>& o, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) o.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_u64(std::vector<std::uint8_t>& o, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) o.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_bytes(std::vector<std::uint8_t>& o, std::span<const std::uint8_t> b) { o.insert(o.end(), b.begin(), b.end()); }
void put_str(std::vector<std::uint8_t>& o, const std::string& s) {
  put_u32(o, static_cast<std::uint32_t>(s.size()));
  o.insert(o.end(), s.begin(), s.end());
}
void patch_u32(std::vector<std::uint8_t>& o, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) o[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}
void patch_u64(std::vector<std::uint8_t>& o, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) o[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}

/// Writes opcode and a placeholder length; returns where the length goes.
std::size_t begin_record(std::vector<std::uint8_t>& o, Op op) {
  put_u8(o, static_cast<std::uint8_t>(op));
  const std::size_t at = o.size();
  put_u64(o, 0);
  return at;
}
void end_record(std::vector<std::uint8_t>& o, std::size_t length_at) { patch_u64(o, length_at, o.size() - length_at - 8); }

/// A u32 byte-length prefix, patched by end_prefixed.
std::size_t begin_prefixed(std::vector<std::uint8_t>& o) {
  const std::size_t at = o.size();
  put_u32(o, 0);
  return at;
}
void end_prefixed(std::vector<std::uint8_t>& o, std::size_t at) { patch_u32(o, at, static_cast<std::uint32_t>(o.size() - at - 4)); }

void put_key_values(std::vector<std::uint8_t>& o, const KeyValues& kv) {
  const std::size_t at = begin_prefixed(o);
  for (const auto& [k, v] : kv) {
    put_str(o, k);
    put_str(o, v);
  }
  end_prefixed(o, at);
}
void put_u16_u64_map(std::vector<std::uint8_t>& o, const std::map<std::uint16_t, std::uint64_t>& m) {
  const std::size_t at = begin_prefixed(o);
  for (const auto& [k, v] : m) {
    put_u16(o, k);
    put_u64(o, v);
  }
  end_prefixed(o, at);
}

// reading: a bounds-checked cursor over one record's content

class Cursor {
 public:
  Cursor(std::span<const std::uint8_t> bytes, const char* record) : bytes_(bytes), record_(record) {}

  std::uint8_t u8(const char* field) { return *take(1, field); }
  std::uint16_t u16(const char* field) {
    const std::uint8_t* p = take(2, field);
    return static_cast<std::uint16_t>(p[0] | p[1] << 8);
  }
  std::uint32_t u32(const char* field) { return load_u32(take(4, field)); }
  std::uint64_t u64(const char* field) { return load_u64(take(8, field)); }
  std::span<const std::uint8_t> bytes(std::uint64_t n, const char* field) {
    if (n > left()) fail(field, "needs " + std::to_string(n) + " bytes, " + std::to_string(left()) + " left");
    const std::uint8_t* p = take(static_cast<std::size_t>(n), field);
    return {p, static_cast<std::size_t>(n)};
  }
  std::string str(const char* field) {
    const std::uint32_t n = u32(field);
    if (n > left()) fail(field, "string of " + std::to_string(n) + " bytes, " + std::to_string(left()) + " left");
    const auto b = bytes(n, field);
    return std::string(reinterpret_cast<const char*>(b.data()), b.size());
  }
  /// The content of a u32 byte-length prefixed map or array.
  Cursor prefixed(const char* field) {
    const std::uint32_t n = u32(field);
    if (n > left()) fail(field, "needs " + std::to_string(n) + " bytes, " + std::to_string(left()) + " left");
    return Cursor(bytes(n, field), record_);
  }
  KeyValues key_values(const char* field) {
    Cursor c = prefixed(field);
    KeyValues kv;
    while (c.left() > 0) {
      std::string k = c.str(field);
      std::string v = c.str(field);
      kv.emplace_back(std::move(k), std::move(v));
    }
    return kv;
  }
  std::map<std::uint16_t, std::uint64_t> u16_u64_map(const char* field) {
    Cursor c = prefixed(field);
    std::map<std::uint16_t, std::uint64_t> m;
    while (c.left() > 0) {
      const std::uint16_t k = c.u16(field);
      m[k] = c.u64(field);
    }
    return m;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  std::size_t offset() const { return at_; }
  std::span<const std::uint8_t> rest() const { return bytes_.subspan(at_); }

  [[noreturn]] void fail(const char* field, const std::string& what) const {
    throw FormatError(std::string(record_) + " record: " + field + ": " + what);
  }

 private:
  const std::uint8_t* take(std::size_t n, const char* field) {
    if (n > left()) fail(field, "needs " + std::to_string(n) + " bytes, " + std::to_string(left()) + " left");
    const std::uint8_t* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  const char* record_;
};

}  // namespace

std::uint64_t load_u64(const std::uint8_t* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | p[i];
  return v;
}
std::uint32_t load_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]) << 16 |
         static_cast<std::uint32_t>(p[3]) << 24;
}

std::string op_name(std::uint8_t op) {
  switch (static_cast<Op>(op)) {
    case Op::header: return "Header";
    case Op::footer: return "Footer";
    case Op::schema: return "Schema";
    case Op::channel: return "Channel";
    case Op::message: return "Message";
    case Op::chunk: return "Chunk";
    case Op::message_index: return "Message Index";
    case Op::chunk_index: return "Chunk Index";
    case Op::attachment: return "Attachment";
    case Op::attachment_index: return "Attachment Index";
    case Op::statistics: return "Statistics";
    case Op::metadata: return "Metadata";
    case Op::metadata_index: return "Metadata Index";
    case Op::summary_offset: return "Summary Offset";
    case Op::data_end: return "Data End";
  }
  static const char* hex = "0123456789ABCDEF";
  return std::string("record 0x") + hex[op >> 4] + hex[op & 15];
}

void append(std::vector<std::uint8_t>& o, const Header& r) {
  const std::size_t at = begin_record(o, Op::header);
  put_str(o, r.profile);
  put_str(o, r.library);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Footer& r) {
  const std::size_t at = begin_record(o, Op::footer);
  put_u64(o, r.summary_start);
  put_u64(o, r.summary_offset_start);
  put_u32(o, r.summary_crc);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Schema& r) {
  const std::size_t at = begin_record(o, Op::schema);
  put_u16(o, r.id);
  put_str(o, r.name);
  put_str(o, r.encoding);
  put_u32(o, static_cast<std::uint32_t>(r.data.size()));
  put_bytes(o, r.data);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Channel& r) {
  const std::size_t at = begin_record(o, Op::channel);
  put_u16(o, r.id);
  put_u16(o, r.schema_id);
  put_str(o, r.topic);
  put_str(o, r.message_encoding);
  put_key_values(o, r.metadata);
  end_record(o, at);
}

void append_message(std::vector<std::uint8_t>& o, std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                    std::uint64_t publish_time, std::span<const std::uint8_t> data) {
  put_u8(o, static_cast<std::uint8_t>(Op::message));
  put_u64(o, 2 + 4 + 8 + 8 + data.size());
  put_u16(o, channel_id);
  put_u32(o, sequence);
  put_u64(o, log_time);
  put_u64(o, publish_time);
  put_bytes(o, data);
}

void append_chunk_prefix(std::vector<std::uint8_t>& o, const ChunkView& c) {
  const std::size_t at = begin_record(o, Op::chunk);
  put_u64(o, c.message_start_time);
  put_u64(o, c.message_end_time);
  put_u64(o, c.uncompressed_size);
  put_u32(o, c.uncompressed_crc);
  put_str(o, c.compression);
  put_u64(o, c.records.size());
  // the length counts the records that follow
  patch_u64(o, at, o.size() - at - 8 + c.records.size());
}

void append(std::vector<std::uint8_t>& o, const MessageIndex& r) {
  const std::size_t at = begin_record(o, Op::message_index);
  put_u16(o, r.channel_id);
  put_u32(o, static_cast<std::uint32_t>(r.entries.size() * 16));
  for (const auto& [t, off] : r.entries) {
    put_u64(o, t);
    put_u64(o, off);
  }
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const ChunkIndex& r) {
  const std::size_t at = begin_record(o, Op::chunk_index);
  put_u64(o, r.message_start_time);
  put_u64(o, r.message_end_time);
  put_u64(o, r.chunk_start_offset);
  put_u64(o, r.chunk_length);
  put_u16_u64_map(o, r.message_index_offsets);
  put_u64(o, r.message_index_length);
  put_str(o, r.compression);
  put_u64(o, r.compressed_size);
  put_u64(o, r.uncompressed_size);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Attachment& r) {
  const std::size_t at = begin_record(o, Op::attachment);
  put_u64(o, r.log_time);
  put_u64(o, r.create_time);
  put_str(o, r.name);
  put_str(o, r.media_type);
  put_u64(o, r.data.size());
  put_bytes(o, r.data);
  // the CRC covers every field before it
  put_u32(o, crc32(std::span(o).subspan(at + 8)));
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const AttachmentIndex& r) {
  const std::size_t at = begin_record(o, Op::attachment_index);
  put_u64(o, r.offset);
  put_u64(o, r.length);
  put_u64(o, r.log_time);
  put_u64(o, r.create_time);
  put_u64(o, r.data_size);
  put_str(o, r.name);
  put_str(o, r.media_type);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Statistics& r) {
  const std::size_t at = begin_record(o, Op::statistics);
  put_u64(o, r.message_count);
  put_u16(o, r.schema_count);
  put_u32(o, r.channel_count);
  put_u32(o, r.attachment_count);
  put_u32(o, r.metadata_count);
  put_u32(o, r.chunk_count);
  put_u64(o, r.message_start_time);
  put_u64(o, r.message_end_time);
  put_u16_u64_map(o, r.channel_message_counts);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const Metadata& r) {
  const std::size_t at = begin_record(o, Op::metadata);
  put_str(o, r.name);
  put_key_values(o, r.entries);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const MetadataIndex& r) {
  const std::size_t at = begin_record(o, Op::metadata_index);
  put_u64(o, r.offset);
  put_u64(o, r.length);
  put_str(o, r.name);
  end_record(o, at);
}

void append(std::vector<std::uint8_t>& o, const SummaryOffset& r) {
  const std::size_t at = begin_record(o, Op::summary_offset);
  put_u8(o, r.group_opcode);
  put_u64(o, r.group_start);
  put_u64(o, r.group_length);
  end_record(o, at);
}

void append_data_end(std::vector<std::uint8_t>& o, std::uint32_t data_section_crc) {
  const std::size_t at = begin_record(o, Op::data_end);
  put_u32(o, data_section_crc);
  end_record(o, at);
}

Header parse_header(std::span<const std::uint8_t> content) {
  Cursor c(content, "Header");
  Header h;
  h.profile = c.str("profile");
  h.library = c.str("library");
  return h;
}

Footer parse_footer(std::span<const std::uint8_t> content) {
  Cursor c(content, "Footer");
  Footer f;
  f.summary_start = c.u64("summary_start");
  f.summary_offset_start = c.u64("summary_offset_start");
  f.summary_crc = c.u32("summary_crc");
  return f;
}

Schema parse_schema(std::span<const std::uint8_t> content) {
  Cursor c(content, "Schema");
  Schema s;
  s.id = c.u16("id");
  s.name = c.str("name");
  s.encoding = c.str("encoding");
  const std::uint32_t n = c.u32("data");
  const auto d = c.bytes(n, "data");
  s.data.assign(d.begin(), d.end());
  return s;
}

Channel parse_channel(std::span<const std::uint8_t> content) {
  Cursor c(content, "Channel");
  Channel ch;
  ch.id = c.u16("id");
  ch.schema_id = c.u16("schema_id");
  ch.topic = c.str("topic");
  ch.message_encoding = c.str("message_encoding");
  ch.metadata = c.key_values("metadata");
  return ch;
}

MessageView parse_message(std::span<const std::uint8_t> content) {
  Cursor c(content, "Message");
  MessageView m;
  m.channel_id = c.u16("channel_id");
  m.sequence = c.u32("sequence");
  m.log_time = c.u64("log_time");
  m.publish_time = c.u64("publish_time");
  m.data = c.rest();
  return m;
}

ChunkView parse_chunk(std::span<const std::uint8_t> content) {
  Cursor c(content, "Chunk");
  ChunkView k;
  k.message_start_time = c.u64("message_start_time");
  k.message_end_time = c.u64("message_end_time");
  k.uncompressed_size = c.u64("uncompressed_size");
  k.uncompressed_crc = c.u32("uncompressed_crc");
  k.compression = c.str("compression");
  const std::uint64_t n = c.u64("records");
  k.records = c.bytes(n, "records");
  return k;
}

MessageIndex parse_message_index(std::span<const std::uint8_t> content) {
  Cursor c(content, "Message Index");
  MessageIndex m;
  m.channel_id = c.u16("channel_id");
  Cursor a = c.prefixed("records");
  if (a.left() % 16 != 0) a.fail("records", "array of " + std::to_string(a.left()) + " bytes is not a whole number of 16-byte entries");
  while (a.left() > 0) {
    const std::uint64_t t = a.u64("records");
    m.entries.emplace_back(t, a.u64("records"));
  }
  return m;
}

ChunkIndex parse_chunk_index(std::span<const std::uint8_t> content) {
  Cursor c(content, "Chunk Index");
  ChunkIndex k;
  k.message_start_time = c.u64("message_start_time");
  k.message_end_time = c.u64("message_end_time");
  k.chunk_start_offset = c.u64("chunk_start_offset");
  k.chunk_length = c.u64("chunk_length");
  k.message_index_offsets = c.u16_u64_map("message_index_offsets");
  k.message_index_length = c.u64("message_index_length");
  k.compression = c.str("compression");
  k.compressed_size = c.u64("compressed_size");
  k.uncompressed_size = c.u64("uncompressed_size");
  return k;
}

Attachment parse_attachment(std::span<const std::uint8_t> content) {
  Cursor c(content, "Attachment");
  Attachment a;
  a.log_time = c.u64("log_time");
  a.create_time = c.u64("create_time");
  a.name = c.str("name");
  a.media_type = c.str("media_type");
  const std::uint64_t n = c.u64("data");
  const auto d = c.bytes(n, "data");
  a.data.assign(d.begin(), d.end());
  const std::size_t covered = c.offset();
  const std::uint32_t stored = c.u32("crc");
  const std::uint32_t actual = crc32(content.first(covered));
  if (stored != 0 && stored != actual) {
    c.fail("crc", "CRC-32 of the attachment is " + std::to_string(actual) + " but the record says " + std::to_string(stored));
  }
  return a;
}

AttachmentIndex parse_attachment_index(std::span<const std::uint8_t> content) {
  Cursor c(content, "Attachment Index");
  AttachmentIndex a;
  a.offset = c.u64("offset");
  a.length = c.u64("length");
  a.log_time = c.u64("log_time");
  a.create_time = c.u64("create_time");
  a.data_size = c.u64("data_size");
  a.name = c.str("name");
  a.media_type = c.str("media_type");
  return a;
}

Statistics parse_statistics(std::span<const std::uint8_t> content) {
  Cursor c(content, "Statistics");
  Statistics s;
  s.message_count = c.u64("message_count");
  s.schema_count = c.u16("schema_count");
  s.channel_count = c.u32("channel_count");
  s.attachment_count = c.u32("attachment_count");
  s.metadata_count = c.u32("metadata_count");
  s.chunk_count = c.u32("chunk_count");
  s.message_start_time = c.u64("message_start_time");
  s.message_end_time = c.u64("message_end_time");
  s.channel_message_counts = c.u16_u64_map("channel_message_counts");
  return s;
}

Metadata parse_metadata(std::span<const std::uint8_t> content) {
  Cursor c(content, "Metadata");
  Metadata m;
  m.name = c.str("name");
  m.entries = c.key_values("metadata");
  return m;
}

MetadataIndex parse_metadata_index(std::span<const std::uint8_t> content) {
  Cursor c(content, "Metadata Index");
  MetadataIndex m;
  m.offset = c.u64("offset");
  m.length = c.u64("length");
  m.name = c.str("name");
  return m;
}

SummaryOffset parse_summary_offset(std::span<const std::uint8_t> content) {
  Cursor c(content, "Summary Offset");
  SummaryOffset s;
  s.group_opcode = c.u8("group_opcode");
  s.group_start = c.u64("group_start");
  s.group_length = c.u64("group_length");
  return s;
}

std::uint32_t parse_data_end(std::span<const std::uint8_t> content) {
  Cursor c(content, "Data End");
  return c.u32("data_section_crc");
}

}  // namespace rescuesim::mcap
