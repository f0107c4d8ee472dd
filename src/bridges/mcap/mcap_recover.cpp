#include "bridges/mcap/mcap_recover.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include "bridges/mcap/byte_sink.h"
#include "bridges/mcap/compression.h"
#include "bridges/mcap/crc32.h"
#include "bridges/mcap/mcap_records.h"
#include "bridges/mcap/mcap_writer.h"
#include "core/error.h"

namespace rescuesim::mcap {

namespace {

/// Records over this size are taken for damage rather than read (the reader's limit too).
constexpr std::uint64_t kMaxRecordBytes = std::uint64_t(1) << 30;

/// A chunk's records, checked and ready to copy: schemas, channels and messages in order.
struct ChunkContent {
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<MessageView> messages;  ///< views into the decompressed records
};

/// Reads the input in order; a short read means the input ends there.
class Input {
 public:
  explicit Input(const std::filesystem::path& path) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error({path.string(), 0, ""}, "no such file (or not a regular file)");
    size_ = std::filesystem::file_size(path, ec);
    in_.open(path, std::ios::binary);
    if (ec || !in_) throw Error({path.string(), 0, ""}, "cannot open the file for reading");
  }
  std::uint64_t size() const { return size_; }
  /// Reads `n` bytes at `offset`; false when the file holds fewer.
  bool read(std::uint64_t offset, std::uint64_t n, std::vector<std::uint8_t>& out) {
    if (offset > size_ || n > size_ - offset) return false;
    out.resize(static_cast<std::size_t>(n));
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
    return static_cast<std::uint64_t>(in_.gcount()) == n;
  }

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

std::string at(std::uint64_t offset, const std::string& record) { return "offset " + std::to_string(offset) + " (" + record + ")"; }

}  // namespace

RecoveryReport recover_mcap(const std::filesystem::path& input, const std::filesystem::path& output) {
  const std::string file = input.string();
  Input in(input);
  RecoveryReport report;
  report.input_bytes = in.size();

  // the magic and the Header must be whole, or there is nothing to recover
  std::vector<std::uint8_t> head;
  if (in.size() == 0) throw Error({file, 0, ""}, "the file is empty, not an MCAP recording: nothing to recover");
  in.read(0, std::min<std::uint64_t>(in.size(), kMagic.size()), head);
  if (!std::equal(head.begin(), head.end(), kMagic.begin())) {
    throw Error({file, 0, "offset 0"}, "not an MCAP file: it does not start with the MCAP magic 89 4D 43 41 50 30 0D 0A");
  }
  if (head.size() < kMagic.size()) {
    throw Error({file, 0, "offset 0"},
                "the file ends " + std::to_string(head.size()) + " bytes into the 8-byte MCAP magic: nothing to recover");
  }
  std::vector<std::uint8_t> prefix, content;
  std::uint64_t pos = kMagic.size();
  Header header;
  {
    const bool whole = in.read(pos, kRecordPrefix, prefix) && prefix[0] == static_cast<std::uint8_t>(Op::header) &&
                       in.read(pos + kRecordPrefix, load_u64(prefix.data() + 1), content);
    if (!whole) throw Error({file, 0, at(pos, "Header")}, "no complete Header record after the magic: nothing to recover");
    try {
      header = parse_header(content);
    } catch (const FormatError& e) {
      throw Error({file, 0, at(pos, "Header")}, std::string("the Header record does not parse: ") + e.what());
    }
    pos += kRecordPrefix + content.size();
  }

  // the output: written under a temporary name, renamed into place once closed
  std::filesystem::path temp = output;
  temp += ".recovering";
  WriterOptions wo;
  wo.profile = header.profile;
  wo.library = header.library;
  auto writer = std::make_unique<McapWriter>(std::make_unique<FileSink>(temp), wo);
  std::map<std::uint16_t, std::uint16_t> schema_ids, channel_ids;  // input id -> output id
  const auto add_schema = [&](const Schema& s) {
    if (s.id == 0 || schema_ids.count(s.id)) return;  // id 0 is invalid; a repeated declaration is the same schema
    schema_ids[s.id] =
        writer->add_schema(s.name, s.encoding, std::string_view(reinterpret_cast<const char*>(s.data.data()), s.data.size()));
    ++report.schemas;
  };
  const auto add_channel = [&](const Channel& c) {
    if (channel_ids.count(c.id)) return;
    channel_ids[c.id] = writer->add_channel(c.schema_id == 0 ? 0 : schema_ids.at(c.schema_id), c.topic, c.message_encoding, c.metadata);
    ++report.channels;
  };
  const auto add_message = [&](const MessageView& m) {
    writer->write_message(channel_ids.at(m.channel_id), m.sequence, m.log_time, m.publish_time, m.data);
    if (report.messages == 0) report.start_time = report.end_time = m.log_time;
    report.start_time = std::min(report.start_time, m.log_time);
    report.end_time = std::max(report.end_time, m.log_time);
    ++report.messages;
  };
  std::map<std::uint16_t, std::string> topics;  // input channel id -> topic, for the per-topic counts

  // every record in order, until Data End or the first one that is torn or damaged
  Decompressor decompressor;
  std::vector<std::uint8_t> records;
  const auto stop = [&](std::uint64_t offset, const std::string& record, const std::string& why) {
    report.dropped_reason = at(offset, record) + ": " + why;
  };
  for (;;) {
    report.kept_bytes = pos;
    if (pos == in.size()) {
      stop(pos, "end of file", "the file ends without a Data End record (the run was killed before it finished the recording)");
      break;
    }
    if (!in.read(pos, kRecordPrefix, prefix)) {
      // the opcode byte is there (the file does not end at pos), the length is not
      std::vector<std::uint8_t> op_byte;
      in.read(pos, 1, op_byte);
      stop(pos, op_name(op_byte.at(0)),
           "the file ends " + std::to_string(in.size() - pos) + " bytes into the record's 9-byte opcode and length");
      break;
    }
    const std::uint8_t op = prefix[0];
    const std::uint64_t len = load_u64(prefix.data() + 1);
    const std::string name = op_name(op);
    if (len > kMaxRecordBytes) {
      stop(pos, name, "claims " + std::to_string(len) + " bytes, more than any record rescuesim reads: damaged");
      break;
    }
    if (!in.read(pos + kRecordPrefix, len, content)) {
      stop(pos, name,
           "the record is " + std::to_string(len) + " bytes but the file ends " + std::to_string(in.size() - pos - kRecordPrefix) +
               " bytes later (torn by the kill)");
      break;
    }
    if (op == static_cast<std::uint8_t>(Op::data_end)) {
      report.finished = true;
      report.kept_bytes = pos + kRecordPrefix + len;
      break;
    }
    std::optional<std::string> damage;
    try {
      switch (static_cast<Op>(op)) {
        case Op::schema: add_schema(parse_schema(content)); break;
        case Op::channel: {
          const Channel c = parse_channel(content);
          if (c.schema_id != 0 && !schema_ids.count(c.schema_id)) {
            damage = "channel " + std::to_string(c.id) + " refers to schema " + std::to_string(c.schema_id) + ", not declared before it";
            break;
          }
          topics[c.id] = c.topic;
          add_channel(c);
          break;
        }
        case Op::message: {
          const MessageView m = parse_message(content);
          if (!channel_ids.count(m.channel_id)) {
            damage = "a message on channel " + std::to_string(m.channel_id) + ", not declared before it";
            break;
          }
          add_message(m);
          ++report.messages_per_topic[topics[m.channel_id]];
          break;
        }
        case Op::chunk: {
          // the whole chunk is checked before any of it is copied
          const ChunkView chunk = parse_chunk(content);
          if (chunk.uncompressed_size > kMaxRecordBytes) {
            damage = "claims " + std::to_string(chunk.uncompressed_size) + " uncompressed bytes: damaged";
            break;
          }
          decompressor.decompress(chunk.compression, chunk.records, chunk.uncompressed_size, records);
          if (chunk.uncompressed_crc != 0 && crc32(records) != chunk.uncompressed_crc) {
            damage = "the CRC-32 of its uncompressed records does not match the one the chunk stores";
            break;
          }
          ChunkContent c;
          std::map<std::uint16_t, bool> schemas_known, channels_known;
          for (const auto& [id, out] : schema_ids) schemas_known[id] = true;
          for (const auto& [id, out] : channel_ids) channels_known[id] = true;
          for (std::uint64_t r = 0; r < records.size() && !damage;) {
            if (records.size() - r < kRecordPrefix) {
              damage = "a record's opcode and length run past the chunk's end";
              break;
            }
            const std::uint8_t rop = records[r];
            const std::uint64_t rlen = load_u64(records.data() + r + 1);
            if (rlen > records.size() - r - kRecordPrefix) {
              damage = "a " + op_name(rop) + " record inside runs past the chunk's end";
              break;
            }
            const auto body = std::span<const std::uint8_t>(records).subspan(r + kRecordPrefix, rlen);
            if (rop == static_cast<std::uint8_t>(Op::schema)) {
              c.schemas.push_back(parse_schema(body));
              schemas_known[c.schemas.back().id] = true;
            } else if (rop == static_cast<std::uint8_t>(Op::channel)) {
              c.channels.push_back(parse_channel(body));
              const Channel& ch = c.channels.back();
              if (ch.schema_id != 0 && !schemas_known.count(ch.schema_id)) {
                damage = "channel " + std::to_string(ch.id) + " inside refers to schema " + std::to_string(ch.schema_id) +
                         ", not declared before it";
              }
              channels_known[ch.id] = true;
            } else if (rop == static_cast<std::uint8_t>(Op::message)) {
              c.messages.push_back(parse_message(body));
              if (!channels_known.count(c.messages.back().channel_id)) {
                damage = "a message inside is on channel " + std::to_string(c.messages.back().channel_id) + ", not declared before it";
              }
            } else {
              damage = "a " + op_name(rop) + " record is not allowed inside a chunk";
            }
            r += kRecordPrefix + rlen;
          }
          if (damage) break;
          // whole: copy it, declarations first (they precede their use in the chunk as well)
          for (const Schema& s : c.schemas) add_schema(s);
          for (const Channel& ch : c.channels) {
            topics[ch.id] = ch.topic;
            add_channel(ch);
          }
          for (const MessageView& m : c.messages) {
            add_message(m);
            ++report.messages_per_topic[topics[m.channel_id]];
          }
          ++report.chunks_read;
          break;
        }
        case Op::attachment: {
          writer->write_attachment(parse_attachment(content));
          ++report.attachments;
          break;
        }
        case Op::metadata: {
          writer->write_metadata(parse_metadata(content));
          ++report.metadata;
          break;
        }
        case Op::message_index: break;  // rebuilt by the writer
        case Op::header: damage = "a second Header record"; break;
        case Op::footer:
        case Op::chunk_index:
        case Op::attachment_index:
        case Op::statistics:
        case Op::metadata_index:
        case Op::summary_offset: damage = "a summary record before any Data End record"; break;
        case Op::data_end: break;  // handled above
      }
    } catch (const FormatError& e) {
      damage = e.what();
    }
    if (damage) {
      stop(pos, name, *damage + "; it and everything after it are dropped");
      break;
    }
    pos += kRecordPrefix + len;  // unknown opcodes are skipped, as the spec asks
  }

  // what was kept, and how, beside the messages
  writer->write_metadata({"rescuesim.recovery",
                          {{"source", input.filename().string()},
                           {"kept_bytes", std::to_string(report.kept_bytes)},
                           {"dropped_bytes", std::to_string(report.dropped_bytes())},
                           {"dropped", report.finished ? "nothing (the recording was finished)" : report.dropped_reason}}});
  writer->close();
  writer.reset();
  std::error_code ec;
  std::filesystem::rename(temp, output, ec);
  if (ec) throw Error({output.string(), 0, ""}, "cannot rename " + temp.string() + " into place: " + ec.message());
  return report;
}

}  // namespace rescuesim::mcap
