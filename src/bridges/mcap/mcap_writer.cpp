#include "bridges/mcap/mcap_writer.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"
#include "core/log.h"

namespace rescuesim::mcap {

McapWriter::McapWriter(std::unique_ptr<ByteSink> sink, WriterOptions options)
    : sink_(std::move(sink)), options_(std::move(options)), compressor_(options_.compression, options_.compression_level) {
  scratch_.assign(kMagic.begin(), kMagic.end());
  append(scratch_, Header{options_.profile, options_.library});
  emit(scratch_);
}

McapWriter::~McapWriter() {
  if (closed_) return;
  try {
    close();
  } catch (const std::exception& e) {
    log::error("mcap: closing the recording failed: {}", e.what());
  }
}

void McapWriter::emit(std::span<const std::uint8_t> bytes) {
  sink_->write(bytes);
  if (in_data_section_) data_crc_.update(bytes);
  position_ += bytes.size();
  stats_.file_bytes = position_;
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding, std::string_view data) {
  RS_DEMAND(!closed_ && schemas_.size() < 0xFFFF, "McapWriter::add_schema: closed, or too many schemas");
  Schema s;
  s.id = static_cast<std::uint16_t>(schemas_.size() + 1);
  s.name = name;
  s.encoding = encoding;
  s.data.assign(data.begin(), data.end());
  append(chunk_, s);
  schemas_.push_back(std::move(s));
  return schemas_.back().id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                      KeyValues metadata) {
  RS_DEMAND(!closed_ && channels_.size() < 0xFFFF, "McapWriter::add_channel: closed, or too many channels");
  RS_DEMAND(schema_id <= schemas_.size(), "McapWriter::add_channel: unknown schema id");
  Channel c;
  c.id = static_cast<std::uint16_t>(channels_.size() + 1);
  c.schema_id = schema_id;
  c.topic = topic;
  c.message_encoding = message_encoding;
  c.metadata = std::move(metadata);
  append(chunk_, c);
  channels_.push_back(std::move(c));
  channel_counts_.push_back(0);
  chunk_entries_.emplace_back();
  return channels_.back().id;
}

void McapWriter::write_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                               std::uint64_t publish_time, std::span<const std::uint8_t> data) {
  RS_DEMAND(!closed_ && channel_id >= 1 && channel_id <= channels_.size(), "McapWriter::write_message: closed, or unknown channel");
  const std::size_t c = channel_id - 1u;
  chunk_entries_[c].emplace_back(log_time, chunk_.size());
  append_message(chunk_, channel_id, sequence, log_time, publish_time, data);
  if (!chunk_has_messages_) {
    chunk_start_ = chunk_end_ = chunk_first_log_time_ = log_time;
    if (options_.chunk_wall_seconds > 0) chunk_first_wall_ = wall_now();
    chunk_has_messages_ = true;
  }
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  if (stats_.messages == 0) start_time_ = end_time_ = log_time;
  start_time_ = std::min(start_time_, log_time);
  end_time_ = std::max(end_time_, log_time);
  ++channel_counts_[c];
  ++stats_.messages;
  stats_.message_bytes += data.size();
  // a full chunk, or one that has spent its log-time or wall-time budget, goes to the sink
  const bool full = chunk_.size() >= options_.chunk_size;
  const bool log_spent = options_.chunk_log_seconds > 0 && log_time >= chunk_first_log_time_ &&
                         static_cast<double>(log_time - chunk_first_log_time_) >= options_.chunk_log_seconds * 1e9;
  const bool wall_spent = options_.chunk_wall_seconds > 0 && wall_now() - chunk_first_wall_ >= options_.chunk_wall_seconds;
  if (full || log_spent || wall_spent) flush_chunk();
}

double McapWriter::wall_now() const {
  if (options_.wall_clock) return options_.wall_clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty() || closed_) return;
  // compress the records, CRC their uncompressed form
  const auto t0 = std::chrono::steady_clock::now();
  compressor_.compress(chunk_, compressed_);
  stats_.compress_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ChunkView view;
  view.message_start_time = chunk_has_messages_ ? chunk_start_ : 0;
  view.message_end_time = chunk_has_messages_ ? chunk_end_ : 0;
  view.uncompressed_size = chunk_.size();
  view.uncompressed_crc = crc32(chunk_);
  view.compression = compression_name(options_.compression);
  view.records = compressed_;

  // the chunk record, then one message index per channel that has messages in it
  ChunkIndex index;
  index.message_start_time = view.message_start_time;
  index.message_end_time = view.message_end_time;
  index.chunk_start_offset = position_;
  index.compression = view.compression;
  index.compressed_size = compressed_.size();
  index.uncompressed_size = chunk_.size();
  scratch_.clear();
  append_chunk_prefix(scratch_, view);
  index.chunk_length = scratch_.size() + compressed_.size();
  emit(scratch_);
  emit(compressed_);
  scratch_.clear();
  const std::uint64_t indexes_start = position_;
  for (std::size_t c = 0; c < chunk_entries_.size(); ++c) {
    if (chunk_entries_[c].empty()) continue;
    index.message_index_offsets[static_cast<std::uint16_t>(c + 1)] = indexes_start + scratch_.size();
    MessageIndex mi;
    mi.channel_id = static_cast<std::uint16_t>(c + 1);
    mi.entries = std::move(chunk_entries_[c]);
    append(scratch_, mi);
    chunk_entries_[c].clear();
  }
  index.message_index_length = scratch_.size();
  emit(scratch_);
  chunk_indexes_.push_back(std::move(index));
  ++stats_.chunks;
  stats_.uncompressed_bytes += chunk_.size();
  stats_.compressed_bytes += compressed_.size();
  chunk_.clear();
  chunk_has_messages_ = false;
  // a killed process leaves every chunk written so far readable
  sink_->flush();
}

void McapWriter::write_metadata(const Metadata& metadata) {
  RS_DEMAND(!closed_, "McapWriter::write_metadata: closed");
  scratch_.clear();
  append(scratch_, metadata);
  metadata_indexes_.push_back({position_, scratch_.size(), metadata.name});
  emit(scratch_);
}

void McapWriter::write_attachment(const Attachment& attachment) {
  RS_DEMAND(!closed_, "McapWriter::write_attachment: closed");
  scratch_.clear();
  append(scratch_, attachment);
  attachment_indexes_.push_back({position_, scratch_.size(), attachment.log_time, attachment.create_time, attachment.data.size(),
                                 attachment.name, attachment.media_type});
  emit(scratch_);
}

void McapWriter::close() {
  if (closed_) return;
  flush_chunk();
  scratch_.clear();
  append_data_end(scratch_, data_crc_.value());
  in_data_section_ = false;
  emit(scratch_);
  write_summary();
  closed_ = true;
  sink_->finish();
}

void McapWriter::write_summary() {
  // records grouped by opcode, each group remembered for the summary offsets
  std::vector<SummaryOffset> groups;
  const std::uint64_t summary_start = position_;
  scratch_.clear();
  const auto group = [&](Op op, auto&& records) {
    const std::size_t begin = scratch_.size();
    for (const auto& r : records) append(scratch_, r);
    if (scratch_.size() > begin) groups.push_back({static_cast<std::uint8_t>(op), summary_start + begin, scratch_.size() - begin});
  };
  group(Op::schema, schemas_);
  group(Op::channel, channels_);
  Statistics st;
  st.message_count = stats_.messages;
  st.schema_count = static_cast<std::uint16_t>(schemas_.size());
  st.channel_count = static_cast<std::uint32_t>(channels_.size());
  st.attachment_count = static_cast<std::uint32_t>(attachment_indexes_.size());
  st.metadata_count = static_cast<std::uint32_t>(metadata_indexes_.size());
  st.chunk_count = static_cast<std::uint32_t>(chunk_indexes_.size());
  st.message_start_time = start_time_;
  st.message_end_time = end_time_;
  for (std::size_t c = 0; c < channels_.size(); ++c) st.channel_message_counts[static_cast<std::uint16_t>(c + 1)] = channel_counts_[c];
  group(Op::statistics, std::vector<Statistics>{st});
  group(Op::chunk_index, chunk_indexes_);
  group(Op::attachment_index, attachment_indexes_);
  group(Op::metadata_index, metadata_indexes_);
  const std::uint64_t summary_offset_start = summary_start + scratch_.size();
  for (const auto& g : groups) append(scratch_, g);

  // the summary CRC runs from the summary's first byte through the footer's offsets
  Footer footer{summary_start, summary_offset_start, 0};
  std::vector<std::uint8_t> tail;
  append(tail, footer);
  Crc32 crc;
  crc.update(scratch_);
  crc.update(std::span(tail).first(kFooterRecordSize - 4));
  footer.summary_crc = crc.value();
  tail.clear();
  append(tail, footer);
  tail.insert(tail.end(), kMagic.begin(), kMagic.end());
  emit(scratch_);
  emit(tail);
}

}  // namespace rescuesim::mcap
