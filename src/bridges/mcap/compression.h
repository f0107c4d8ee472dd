#pragma once
/// Chunk compression as MCAP names it: "zstd" (libzstd frames), "lz4" (LZ4 frame format,
/// liblz4) or "" (none). Contexts are reused across chunks; each object belongs to one thread.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rescuesim::mcap {

/// A chunk compression.
enum class Compression { none, zstd, lz4 };

/// The name MCAP stores in a chunk: "", "zstd" or "lz4".
const char* compression_name(Compression c);
/// The compression of a name ("none" and "" are none); throws std::invalid_argument for others.
Compression compression_from_name(const std::string& name);

/// Compresses chunks with one algorithm and level.
class Compressor {
 public:
  /// `level`: zstd 1..19 (3 is zstd's default: fast with a good ratio); ignored for lz4 and none.
  Compressor(Compression compression, int level = 3);
  ~Compressor();
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  Compression compression() const { return compression_; }
  /// Replaces `out` with the compressed form of `in`.
  void compress(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out);

 private:
  struct Contexts;
  Compression compression_;
  int level_;
  std::unique_ptr<Contexts> contexts_;
};

/// Decompresses chunks of any supported compression.
class Decompressor {
 public:
  Decompressor();
  ~Decompressor();
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;

  /// Replaces `out` with the `size` bytes that `in` decompresses to. Throws FormatError when
  /// the compression is unknown, the data is corrupt, or it holds more or fewer bytes than `size`.
  void decompress(const std::string& compression, std::span<const std::uint8_t> in, std::uint64_t size,
                  std::vector<std::uint8_t>& out);

 private:
  struct Contexts;
  std::unique_ptr<Contexts> contexts_;
};

}  // namespace rescuesim::mcap
