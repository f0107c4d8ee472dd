#pragma once
/// Where an MCAP writer's bytes go: a file (written as FILE.part and renamed into place when
/// finished) or memory (tests).

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <vector>

namespace rescuesim::mcap {

/// A destination for bytes written in order.
class ByteSink {
 public:
  virtual ~ByteSink() = default;
  /// Appends bytes. Throws rescuesim::Error when they cannot be written.
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  /// Hands what was written to the operating system, so a killed process leaves it behind.
  virtual void flush() = 0;
  /// Makes the written bytes final (a file: fsync, then rename into place).
  virtual void finish() = 0;
};

/// Writes `path` + ".part" while open and renames it to `path` on finish(): a run killed while
/// recording leaves FILE.part (readable by stream readers up to its last complete chunk), never
/// a FILE that looks finished.
class FileSink : public ByteSink {
 public:
  /// Creates parent folders and opens the .part file; throws rescuesim::Error naming the path.
  explicit FileSink(std::filesystem::path path);
  ~FileSink() override;
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;

  void write(std::span<const std::uint8_t> bytes) override;
  void flush() override;
  void finish() override;
  /// The file being written (FILE.part until finish(), then FILE).
  const std::filesystem::path& current_path() const { return finished_ ? path_ : part_; }

 private:
  std::filesystem::path path_, part_;
  std::FILE* file_ = nullptr;
  bool finished_ = false;
};

/// Collects the bytes in a vector.
class MemorySink : public ByteSink {
 public:
  explicit MemorySink(std::vector<std::uint8_t>& out) : out_(out) {}
  void write(std::span<const std::uint8_t> bytes) override { out_.insert(out_.end(), bytes.begin(), bytes.end()); }
  void flush() override {}
  void finish() override {}

 private:
  std::vector<std::uint8_t>& out_;
};

}  // namespace rescuesim::mcap
