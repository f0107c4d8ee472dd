#pragma once
/// Writing result files atomically: data goes to a temporary file beside the target, is
/// flushed, then renamed over it, so a killed run never leaves a half-written file that
/// looks complete.

#include <filesystem>
#include <string_view>

namespace rescuesim {

/// Writes `data` to `path` atomically (temp file + fsync + rename). Creates parent folders.
/// Throws `Error` naming the path when the file cannot be written.
void write_file_atomic(const std::filesystem::path& path, std::string_view data);

/// Reads a whole file. Throws `Error` naming the path when it cannot be read or is larger
/// than `max_bytes`.
std::string read_file(const std::filesystem::path& path, std::size_t max_bytes = std::size_t(1) << 30);

}  // namespace rescuesim
