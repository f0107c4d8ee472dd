#include "bridges/mcap/compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include <stdexcept>

#include "bridges/mcap/mcap_records.h"

namespace rescuesim::mcap {

const char* compression_name(Compression c) {
  switch (c) {
    case Compression::none: return "";
    case Compression::zstd: return "zstd";
    case Compression::lz4: return "lz4";
  }
  return "";
}

Compression compression_from_name(const std::string& name) {
  if (name.empty() || name == "none") return Compression::none;
  if (name == "zstd") return Compression::zstd;
  if (name == "lz4") return Compression::lz4;
  throw std::invalid_argument("unknown compression '" + name + "' (zstd, lz4 or none)");
}

struct Compressor::Contexts {
  ZSTD_CCtx* zstd = nullptr;
  ~Contexts() { ZSTD_freeCCtx(zstd); }
};

Compressor::Compressor(Compression compression, int level)
    : compression_(compression), level_(level), contexts_(std::make_unique<Contexts>()) {
  if (compression_ == Compression::zstd) contexts_->zstd = ZSTD_createCCtx();
}

Compressor::~Compressor() = default;

void Compressor::compress(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out) {
  switch (compression_) {
    case Compression::none:
      out.assign(in.begin(), in.end());
      return;
    case Compression::zstd: {
      out.resize(ZSTD_compressBound(in.size()));
      const std::size_t n = ZSTD_compressCCtx(contexts_->zstd, out.data(), out.size(), in.data(), in.size(), level_);
      if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
      out.resize(n);
      return;
    }
    case Compression::lz4: {
      LZ4F_preferences_t prefs{};
      prefs.frameInfo.contentSize = in.size();
      out.resize(LZ4F_compressFrameBound(in.size(), &prefs));
      const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
      if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
      out.resize(n);
      return;
    }
  }
}

struct Decompressor::Contexts {
  ZSTD_DCtx* zstd = nullptr;
  LZ4F_dctx* lz4 = nullptr;
  ~Contexts() {
    ZSTD_freeDCtx(zstd);
    if (lz4) LZ4F_freeDecompressionContext(lz4);
  }
};

Decompressor::Decompressor() : contexts_(std::make_unique<Contexts>()) {}
Decompressor::~Decompressor() = default;

void Decompressor::decompress(const std::string& compression, std::span<const std::uint8_t> in, std::uint64_t size,
                              std::vector<std::uint8_t>& out) {
  const std::string sz = std::to_string(size);
  if (compression.empty()) {
    if (in.size() != size) throw FormatError("uncompressed chunk holds " + std::to_string(in.size()) + " bytes, its header says " + sz);
    out.assign(in.begin(), in.end());
    return;
  }
  out.resize(static_cast<std::size_t>(size));
  if (compression == "zstd") {
    if (!contexts_->zstd) contexts_->zstd = ZSTD_createDCtx();
    const std::size_t n = ZSTD_decompressDCtx(contexts_->zstd, out.data(), out.size(), in.data(), in.size());
    if (ZSTD_isError(n)) throw FormatError(std::string("zstd data is corrupt (") + ZSTD_getErrorName(n) + "; expected " + sz + " bytes)");
    if (n != size) throw FormatError("zstd data decompresses to " + std::to_string(n) + " bytes, the chunk says " + sz);
    return;
  }
  if (compression == "lz4") {
    if (!contexts_->lz4 && LZ4F_isError(LZ4F_createDecompressionContext(&contexts_->lz4, LZ4F_VERSION))) {
      throw std::runtime_error("lz4: cannot create a decompression context");
    }
    LZ4F_resetDecompressionContext(contexts_->lz4);
    std::size_t done_in = 0, done_out = 0;
    while (done_in < in.size()) {
      std::size_t n_in = in.size() - done_in, n_out = out.size() - done_out;
      const std::size_t hint =
          LZ4F_decompress(contexts_->lz4, out.data() + done_out, &n_out, in.data() + done_in, &n_in, nullptr);
      if (LZ4F_isError(hint)) throw FormatError(std::string("lz4 data is corrupt (") + LZ4F_getErrorName(hint) + ")");
      done_in += n_in;
      done_out += n_out;
      if (hint == 0) break;                                      // frame complete
      if (n_in == 0 && n_out == 0) throw FormatError("lz4 data decompresses to more than the " + sz + " bytes the chunk says");
    }
    if (done_out != size || done_in != in.size()) {
      throw FormatError("lz4 data decompresses to " + std::to_string(done_out) + " bytes, the chunk says " + sz);
    }
    return;
  }
  throw FormatError("unsupported chunk compression '" + compression + "' (this reader knows zstd and lz4)");
}

}  // namespace rescuesim::mcap
