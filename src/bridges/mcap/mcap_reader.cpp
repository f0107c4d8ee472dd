#include "bridges/mcap/mcap_reader.h"

#include <algorithm>
#include <cstring>
#include <set>

#include "bridges/mcap/compression.h"
#include "bridges/mcap/crc32.h"
#include "core/error.h"

namespace rescuesim::mcap {

namespace {

std::string hex_bytes(std::span<const std::uint8_t> b) {
  static const char* digits = "0123456789ABCDEF";
  std::string s;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (i) s += ' ';
    s += digits[b[i] >> 4];
    s += digits[b[i] & 15];
  }
  return s;
}

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08X", v);
  return buf;
}

bool same(const Schema& a, const Schema& b) { return a.name == b.name && a.encoding == b.encoding && a.data == b.data; }
bool same(const Channel& a, const Channel& b) {
  return a.schema_id == b.schema_id && a.topic == b.topic && a.message_encoding == b.message_encoding && a.metadata == b.metadata;
}

constexpr const char* kTruncatedHint =
    " (a recording whose run was killed? rescuesim leaves such a file as FILE.mcap.part: 'rescuesim recover FILE.mcap.part' "
    "writes an indexed FILE.mcap of it up to its last complete chunk, which replay and Foxglove can open)";

}  // namespace

McapReader::McapReader(const std::filesystem::path& path, ReaderOptions options) : path_(path), options_(options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path_, ec)) throw Error({path_.string(), 0, ""}, "no such file (or not a regular file)");
  size_ = std::filesystem::file_size(path_, ec);
  in_.open(path_, std::ios::binary);
  if (ec || !in_) throw Error({path_.string(), 0, ""}, "cannot open the file for reading");

  // the leading magic says what the file is
  std::vector<std::uint8_t> head;
  read_at(0, std::min<std::uint64_t>(size_, 16), head);
  if (size_ == 0) throw Error({path_.string(), 0, ""}, "the file is empty, not an MCAP recording");
  if (head.size() < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), head.begin())) {
    const std::string start(head.begin(), head.end());
    std::string what = "not an MCAP file: it starts with " + hex_bytes(std::span(head).first(std::min<std::size_t>(head.size(), 8))) +
                       " instead of the MCAP magic 89 4D 43 41 50 30 0D 0A";
    if (start.rfind("#ROSBAG", 0) == 0) what = "not an MCAP file: it is a ROS 1 bag (starts with #ROSBAG)";
    if (start.rfind("SQLite format 3", 0) == 0) what = "not an MCAP file: it is an SQLite database (a ROS 2 sqlite3 bag?)";
    if (head.size() >= 6 && std::memcmp(head.data(), "\x89MCAP", 5) == 0) {
      what = "an MCAP file of major version '" + std::string(1, static_cast<char>(head[5])) + "', this reader knows version '0'";
    }
    throw Error({path_.string(), 0, "offset 0"}, what);
  }
  const std::uint64_t data_end = scan_data_section();
  scan_summary(data_end);
}

McapReader::~McapReader() = default;

void McapReader::fail(std::uint64_t offset, const std::string& record, const std::string& what) const {
  throw Error({path_.string(), 0, "offset " + std::to_string(offset) + (record.empty() ? "" : " (" + record + ")")}, what);
}

void McapReader::read_at(std::uint64_t offset, std::uint64_t n, std::vector<std::uint8_t>& out) {
  out.resize(static_cast<std::size_t>(n));
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
  if (static_cast<std::uint64_t>(in_.gcount()) != n) fail(offset, "", "reading " + std::to_string(n) + " bytes failed (the file changed?)");
}

const Metadata* McapReader::find_metadata(const std::string& name) const {
  for (const auto& m : metadata_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const Attachment* McapReader::find_attachment(const std::string& name) const {
  for (const auto& a : attachments_) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

std::size_t McapReader::chunk_count() const {
  return static_cast<std::size_t>(std::count_if(message_records_.begin(), message_records_.end(),
                                                 [](const Place& p) { return p.op == static_cast<std::uint8_t>(Op::chunk); }));
}

void McapReader::add_schema(const Schema& s, std::uint64_t offset, const char* where) {
  if (s.id == 0) return;  // id 0 is invalid and ignored, as the spec says
  const auto [it, inserted] = schemas_.emplace(s.id, s);
  if (!inserted && !same(it->second, s)) {
    fail(offset, where, "schema " + std::to_string(s.id) + " was declared before with different fields");
  }
}

void McapReader::add_channel(const Channel& c, std::uint64_t offset, const char* where, bool schema_needed) {
  const auto [it, inserted] = channels_.emplace(c.id, c);
  if (!inserted && !same(it->second, c)) {
    fail(offset, where, "channel " + std::to_string(c.id) + " was declared before with different fields");
  }
  if (schema_needed && c.schema_id != 0 && !schemas_.count(c.schema_id)) {
    fail(offset, where, "channel " + std::to_string(c.id) + " (" + c.topic + ") refers to schema " + std::to_string(c.schema_id) +
                            ", which no Schema record declared before it");
  }
}

std::uint64_t McapReader::scan_data_section() {
  // every record's framing, in order, with the CRC of all bytes before Data End
  Crc32 crc;
  crc.update(kMagic);
  std::uint64_t pos = kMagic.size();
  std::vector<std::uint8_t> prefix, content;
  bool header_seen = false;
  for (;;) {
    if (pos == size_) {
      fail(pos, "", std::string("the file ends without a Data End record, summary or footer: it is truncated") + kTruncatedHint);
    }
    if (size_ - pos < kRecordPrefix) {
      fail(pos, "", "the file ends " + std::to_string(size_ - pos) + " bytes into a record's 9-byte opcode and length: it is truncated" +
                        kTruncatedHint);
    }
    read_at(pos, kRecordPrefix, prefix);
    const std::uint8_t op = prefix[0];
    const std::uint64_t len = load_u64(prefix.data() + 1);
    const std::string name = op_name(op);
    const std::uint64_t left = size_ - pos - kRecordPrefix;
    if (len > left) {
      fail(pos, name, "the record's content is " + std::to_string(len) + " bytes but the file ends " + std::to_string(left) +
                          " bytes later: it is truncated" + kTruncatedHint);
    }
    if (len > options_.max_record_bytes) {
      fail(pos, name,
           "a record of " + std::to_string(len) + " bytes is over this reader's limit of " + std::to_string(options_.max_record_bytes));
    }
    read_at(pos + kRecordPrefix, len, content);
    if (!header_seen && op != static_cast<std::uint8_t>(Op::header)) fail(pos, name, "the first record after the magic must be a Header");
    try {
      switch (static_cast<Op>(op)) {
        case Op::header:
          if (header_seen) fail(pos, name, "a second Header record");
          header_ = parse_header(content);
          header_seen = true;
          break;
        case Op::schema: add_schema(parse_schema(content), pos, "Schema"); break;
        case Op::channel: add_channel(parse_channel(content), pos, "Channel"); break;
        case Op::message: {
          const MessageView m = parse_message(content);
          if (!channels_.count(m.channel_id)) {
            fail(pos, name, "refers to channel " + std::to_string(m.channel_id) + ", not declared before it");
          }
          message_records_.push_back({pos, op, len});
          break;
        }
        case Op::chunk: {
          const ChunkView c = parse_chunk(content);
          if (c.uncompressed_size > options_.max_record_bytes) {
            fail(pos, name, "claims " + std::to_string(c.uncompressed_size) + " uncompressed bytes, over this reader's limit of " +
                                std::to_string(options_.max_record_bytes));
          }
          if (!c.compression.empty() && c.compression != "zstd" && c.compression != "lz4") {
            fail(pos, name, "unsupported compression '" + c.compression + "' (this reader knows zstd and lz4)");
          }
          message_records_.push_back({pos, op, len});
          break;
        }
        case Op::message_index: parse_message_index(content); break;
        case Op::attachment: attachments_.push_back(parse_attachment(content)); break;
        case Op::metadata: metadata_.push_back(parse_metadata(content)); break;
        case Op::data_end: {
          stored_data_crc_ = parse_data_end(content);
          computed_data_crc_ = crc.value();
          if (stored_data_crc_ != 0 && stored_data_crc_ != computed_data_crc_) {
            fail(pos, name, "the data section's CRC-32 is " + hex32(computed_data_crc_) + " but Data End says " + hex32(stored_data_crc_) +
                                ": bytes between offset 0 and " + std::to_string(pos) + " are corrupt");
          }
          return pos + kRecordPrefix + len;
        }
        case Op::footer: fail(pos, name, "a Footer before any Data End record (the data section must end with Data End)");
        case Op::chunk_index:
        case Op::attachment_index:
        case Op::statistics:
        case Op::metadata_index:
        case Op::summary_offset: fail(pos, name, "this record belongs in the summary section, not the data section");
      }
    } catch (const FormatError& e) {
      fail(pos, name, e.what());
    }
    // unknown opcodes are skipped, as the spec asks
    crc.update(prefix);
    crc.update(content);
    pos += kRecordPrefix + len;
  }
}

void McapReader::scan_summary(std::uint64_t data_end) {
  // the footer and closing magic at the very end
  const std::uint64_t tail = kFooterRecordSize + kMagic.size();
  if (size_ - data_end < tail) {
    fail(data_end, "Footer", "the file ends " + std::to_string(size_ - data_end) + " bytes after Data End, too few for a Footer and the "
                             "closing magic: it is truncated" + kTruncatedHint);
  }
  std::vector<std::uint8_t> bytes;
  read_at(size_ - kMagic.size(), kMagic.size(), bytes);
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
    fail(size_ - kMagic.size(), "magic",
         "the file does not end with the MCAP magic (it ends with " + hex_bytes(bytes) + "): it is truncated or damaged" + kTruncatedHint);
  }
  const std::uint64_t footer_at = size_ - tail;
  read_at(footer_at, kFooterRecordSize, bytes);
  if (bytes[0] != static_cast<std::uint8_t>(Op::footer) || load_u64(bytes.data() + 1) != kFooterRecordSize - kRecordPrefix) {
    fail(footer_at, "Footer", "expected the Footer record (opcode 02, length 20) just before the closing magic, found opcode " +
                                  hex_bytes(std::span(bytes).first(1)) + " length " + std::to_string(load_u64(bytes.data() + 1)));
  }
  const Footer footer = parse_footer(std::span(bytes).subspan(kRecordPrefix));
  if (footer.summary_start != 0 && footer.summary_start != data_end) {
    fail(footer_at, "Footer",
         "summary_start is " + std::to_string(footer.summary_start) + " but the summary starts right after Data End, at " +
             std::to_string(data_end));
  }
  const std::uint64_t offsets_at = footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_at;
  if (offsets_at < data_end || offsets_at > footer_at) {
    fail(footer_at, "Footer", "summary_offset_start " + std::to_string(footer.summary_offset_start) + " is outside the summary (" +
                                  std::to_string(data_end) + ".." + std::to_string(footer_at) + ")");
  }
  if (footer.summary_start == 0 && offsets_at != data_end) {
    fail(data_end, "", "records after Data End but the Footer says there is no summary (summary_start 0)");
  }

  // the summary CRC covers the summary, the summary offsets and the footer up to the CRC itself
  std::vector<std::uint8_t> summary;
  read_at(data_end, footer_at - data_end, summary);
  if (footer.summary_crc != 0) {
    Crc32 crc;
    crc.update(summary);
    crc.update(std::span(bytes).first(kFooterRecordSize - 4));
    if (crc.value() != footer.summary_crc) {
      fail(footer_at, "Footer", "the summary's CRC-32 is " + hex32(crc.value()) + " but the Footer says " + hex32(footer.summary_crc) +
                                    ": bytes between offset " + std::to_string(data_end) + " and the footer are corrupt");
    }
  }

  // summary records grouped by opcode, then summary offsets
  std::set<std::uint8_t> groups_done;
  std::map<std::uint64_t, std::uint8_t> record_ops;
  std::vector<SummaryOffset> offsets;
  std::uint8_t current = 0;
  std::uint64_t pos = data_end;
  while (pos < footer_at) {
    const std::uint64_t at = pos - data_end;
    if (footer_at - pos < kRecordPrefix) fail(pos, "", "a record's opcode and length run into the Footer");
    const std::uint8_t op = summary[at];
    const std::uint64_t len = load_u64(summary.data() + at + 1);
    const std::string name = op_name(op);
    if (len > footer_at - pos - kRecordPrefix) fail(pos, name, "the record's " + std::to_string(len) + " bytes run into the Footer");
    const auto content = std::span(summary).subspan(at + kRecordPrefix, len);
    const bool in_offsets = pos >= offsets_at;
    if (op != current) {
      if (groups_done.count(op)) fail(pos, name, "summary records must be grouped by opcode; this group appeared before");
      if (current) groups_done.insert(current);
      current = op;
    }
    record_ops[pos] = op;
    try {
      if (in_offsets) {
        if (op != static_cast<std::uint8_t>(Op::summary_offset)) {
          fail(pos, name, "only Summary Offset records may follow summary_offset_start");
        }
        offsets.push_back(parse_summary_offset(content));
      } else {
        switch (static_cast<Op>(op)) {
          case Op::schema: add_schema(parse_schema(content), pos, "Schema"); break;
          case Op::channel: add_channel(parse_channel(content), pos, "Channel", false); break;
          case Op::chunk_index: chunk_indexes_.push_back(parse_chunk_index(content)); break;
          case Op::attachment_index: parse_attachment_index(content); break;
          case Op::metadata_index: parse_metadata_index(content); break;
          case Op::statistics:
            if (statistics_) fail(pos, name, "a second Statistics record");
            statistics_ = parse_statistics(content);
            break;
          case Op::header:
          case Op::footer:
          case Op::message:
          case Op::chunk:
          case Op::message_index:
          case Op::attachment:
          case Op::metadata:
          case Op::data_end:
          case Op::summary_offset: fail(pos, name, "this record is not allowed in the summary section");
        }
      }
    } catch (const FormatError& e) {
      fail(pos, name, e.what());
    }
    pos += kRecordPrefix + len;
  }

  // channels must name known schemas (the summary's groups may come in any order)
  for (const auto& [id, c] : channels_) {
    if (c.schema_id != 0 && !schemas_.count(c.schema_id)) {
      fail(data_end, "Channel", "channel " + std::to_string(id) + " (" + c.topic + ") refers to schema " + std::to_string(c.schema_id) +
                                    ", which the summary does not declare");
    }
  }
  // indexes must point where they say
  for (const auto& o : offsets) {
    const auto it = record_ops.find(o.group_start);
    if (it == record_ops.end() || it->second != o.group_opcode) {
      fail(offsets_at, "Summary Offset", "the group of " + op_name(o.group_opcode) + " records is said to start at " +
                                             std::to_string(o.group_start) + ", where there is no such record");
    }
  }
  std::map<std::uint64_t, std::uint64_t> chunks;
  for (const auto& p : message_records_) {
    if (p.op == static_cast<std::uint8_t>(Op::chunk)) chunks[p.offset] = p.length + kRecordPrefix;
  }
  for (const auto& ci : chunk_indexes_) {
    const auto it = chunks.find(ci.chunk_start_offset);
    if (it == chunks.end() || it->second != ci.chunk_length) {
      fail(data_end, "Chunk Index", "a chunk index points at offset " + std::to_string(ci.chunk_start_offset) + " (" +
                                        std::to_string(ci.chunk_length) + " bytes), where there is no such Chunk record");
    }
    for (const auto& [channel, offset] : ci.message_index_offsets) {
      const std::uint64_t begin = ci.chunk_start_offset + ci.chunk_length;
      if (offset < begin || offset >= begin + ci.message_index_length) {
        fail(data_end, "Chunk Index", "the message index of channel " + std::to_string(channel) + " for the chunk at " +
                                          std::to_string(ci.chunk_start_offset) + " is said to be at " + std::to_string(offset) +
                                          ", outside the chunk's message indexes");
      }
    }
  }
  if (statistics_ && !chunk_indexes_.empty() && statistics_->chunk_count != chunks.size()) {
    fail(data_end, "Statistics", "chunk_count is " + std::to_string(statistics_->chunk_count) + " but the file has " +
                                     std::to_string(chunks.size()) + " chunks");
  }
}

void McapReader::read_messages(const std::function<bool(const Channel&, const MessageView&)>& visit) {
  Decompressor decompressor;
  std::vector<std::uint8_t> content, records;
  const auto deliver = [&](const MessageView& m, std::uint64_t offset, const std::string& where) {
    const auto it = channels_.find(m.channel_id);
    if (it == channels_.end()) fail(offset, where, "a message on channel " + std::to_string(m.channel_id) + ", which was never declared");
    return visit(it->second, m);
  };
  for (const Place& p : message_records_) {
    read_at(p.offset + kRecordPrefix, p.length, content);
    if (p.op == static_cast<std::uint8_t>(Op::message)) {
      if (!deliver(parse_message(content), p.offset, "Message")) return;
      continue;
    }
    // a chunk: decompress, check the CRC, walk its records
    ChunkView chunk;
    try {
      chunk = parse_chunk(content);
      decompressor.decompress(chunk.compression, chunk.records, chunk.uncompressed_size, records);
    } catch (const FormatError& e) {
      fail(p.offset, "Chunk", e.what());
    }
    if (chunk.uncompressed_crc != 0) {
      const std::uint32_t actual = crc32(records);
      if (actual != chunk.uncompressed_crc) {
        fail(p.offset, "Chunk",
             "the CRC-32 of its uncompressed records is " + hex32(actual) + " but the chunk says " + hex32(chunk.uncompressed_crc));
      }
    }
    std::uint64_t at = 0;
    while (at < records.size()) {
      const std::string where = "Chunk, record at byte " + std::to_string(at) + " of its records";
      if (records.size() - at < kRecordPrefix) fail(p.offset, where, "a record's opcode and length run past the chunk's end");
      const std::uint8_t op = records[at];
      const std::uint64_t len = load_u64(records.data() + at + 1);
      if (len > records.size() - at - kRecordPrefix) {
        fail(p.offset, where, "a " + op_name(op) + " record of " + std::to_string(len) + " bytes runs past the chunk's end");
      }
      const auto body = std::span(records).subspan(at + kRecordPrefix, len);
      try {
        switch (static_cast<Op>(op)) {
          case Op::schema: add_schema(parse_schema(body), p.offset, where.c_str()); break;
          case Op::channel: add_channel(parse_channel(body), p.offset, where.c_str()); break;
          case Op::message:
            if (!deliver(parse_message(body), p.offset, where)) return;
            break;
          case Op::header:
          case Op::footer:
          case Op::chunk:
          case Op::message_index:
          case Op::chunk_index:
          case Op::attachment:
          case Op::attachment_index:
          case Op::statistics:
          case Op::metadata:
          case Op::metadata_index:
          case Op::summary_offset:
          case Op::data_end: fail(p.offset, where, "a " + op_name(op) + " record is not allowed inside a chunk");
        }
      } catch (const FormatError& e) {
        fail(p.offset, where, e.what());
      }
      at += kRecordPrefix + len;
    }
  }
}

}  // namespace rescuesim::mcap
