#include "bridges/mcap/byte_sink.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace rescuesim::mcap {

FileSink::FileSink(std::filesystem::path path) : path_(std::move(path)) {
  part_ = path_;
  part_ += ".part";
  std::error_code ec;
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path(), ec);
  file_ = std::fopen(part_.c_str(), "wb");
  if (!file_) throw Error({path_.string(), 0, ""}, std::string("cannot create the recording: ") + std::strerror(errno));
}

FileSink::~FileSink() {
  if (file_) std::fclose(file_);
}

void FileSink::write(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    throw Error({part_.string(), 0, ""}, std::string("writing the recording failed: ") + std::strerror(errno));
  }
}

void FileSink::flush() {
  if (std::fflush(file_) != 0) throw Error({part_.string(), 0, ""}, std::string("writing the recording failed: ") + std::strerror(errno));
}

void FileSink::finish() {
  if (finished_) return;
  flush();
  // on disk before it takes the final name, as core/atomic_file does
  ::fsync(::fileno(file_));
  std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  std::filesystem::rename(part_, path_, ec);
  if (ec) throw Error({path_.string(), 0, ""}, "cannot rename " + part_.string() + " into place: " + ec.message());
  finished_ = true;
}

}  // namespace rescuesim::mcap
