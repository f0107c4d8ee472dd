/// libFuzzer target for the MCAP reader (what `rescuesim replay` opens): every input is written
/// to a scratch file and opened with McapReader — magic, header, record framing, data-section
/// and summary CRCs, chunk indexes, footer — and, when it opens, all its messages are read
/// (zstd / lz4 chunks decompressed and checked). rescuesim::Error is the only failure the
/// reader may report; any other exception, a crash or a sanitizer finding is a bug. Records are
/// capped at 16 MiB (the reader's option) so that a forged length is refused instead of
/// allocated; the 1 GiB default is a limit by design, not a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "bridges/mcap/mcap_reader.h"
#include "core/error.h"

namespace {

/// One scratch file per process (libFuzzer's -jobs run several), in memory when /dev/shm is there.
const std::filesystem::path& scratch_file() {
  static const std::filesystem::path path = [] {
    const std::filesystem::path dir =
        std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    return dir / ("rescuesim_mcap_fuzz_" + std::to_string(::getpid()) + ".mcap");
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  const std::filesystem::path& file = scratch_file();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    mcap::ReaderOptions options;
    options.max_record_bytes = std::uint64_t(16) << 20;
    mcap::McapReader reader(file, options);
    std::size_t bytes = 0;
    reader.read_messages([&](const mcap::Channel&, const mcap::MessageView& m) {
      bytes += m.data.size();
      return true;
    });
  } catch (const Error&) {
  }
  return 0;
}
