#pragma once
/// Recovering a recording whose writer was killed (`rescuesim recover`). The recorder writes
/// FILE.mcap.part and flushes it after every chunk, so a killed run leaves a data section that
/// is whole up to its last complete chunk and then a torn tail (part of a chunk or of its
/// message indexes), with no Data End, summary or footer. Recovery reads the records in order,
/// keeps every complete one (a chunk only when it decompresses, its CRC matches and every record
/// inside parses), stops at the first torn or damaged record, and writes what it kept as a
/// proper indexed MCAP file (chunks, message indexes, statistics, summary, footer) with the
/// strict writer, atomically. A finished file recovers to an equivalent one (nothing dropped).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace rescuesim::mcap {

/// What a recovery kept and what it dropped.
struct RecoveryReport {
  std::uint64_t messages = 0;       ///< messages written to the output
  std::uint64_t chunks_read = 0;    ///< complete chunks of the input that were kept
  std::uint64_t schemas = 0, channels = 0;
  std::uint64_t metadata = 0, attachments = 0;
  std::uint64_t start_time = 0, end_time = 0;  ///< log times (ns) of the first and last message (0 when none)
  std::map<std::string, std::uint64_t> messages_per_topic;
  std::uint64_t input_bytes = 0;    ///< size of the input
  std::uint64_t kept_bytes = 0;     ///< the input's bytes up to the end of the last record kept
  bool finished = false;            ///< the input had its Data End record (it was not cut)
  /// Why reading stopped before the end of the input ("" when it reached Data End), naming the
  /// offset and record: a torn tail or a damaged chunk. Everything from there on was dropped.
  std::string dropped_reason;
  std::uint64_t dropped_bytes() const { return input_bytes - kept_bytes; }
};

/// Recovers `input` into `output` (see the file comment). The output is written beside its
/// final name and renamed into place only when complete; `output` may be `input` minus ".part".
/// Throws rescuesim::Error naming the input when there is nothing to recover: no such file, an
/// empty file, not MCAP (or only part of the magic), or no complete Header record.
RecoveryReport recover_mcap(const std::filesystem::path& input, const std::filesystem::path& output);

}  // namespace rescuesim::mcap
