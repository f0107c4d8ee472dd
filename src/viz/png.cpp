// PNG encoding and decoding with libpng on memory buffers.
//
// libpng reports errors by longjmp to a setjmp point. A longjmp must not skip C++ objects
// with destructors, so every libpng call sits in a small function whose only locals are
// trivial (ints and pointers); buffers, messages and the libpng structs live in a job
// object owned by the caller, which frees everything whether the work succeeded or not.

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "viz/canvas.h"

namespace rescuesim {

namespace {

// largest image decode_png accepts (matches the Canvas limits)
constexpr png_uint_32 kMaxSide = 32768;
constexpr unsigned long long kMaxPixels = 1ULL << 27;

// the last libpng error message, kept in a fixed buffer so the error path never allocates
struct ErrorText {
  char text[256] = "unknown libpng error";
};

void on_error(png_structp png, png_const_charp message) {
  auto* err = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::snprintf(err->text, sizeof err->text, "%s", message ? message : "unknown libpng error");
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// encoding: libpng hands out compressed bytes through on_write, which appends to `out`
struct EncodeJob {
  ErrorText error;
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::string out;
  bool out_of_memory = false;
  ~EncodeJob() {
    if (png) png_destroy_write_struct(&png, info ? &info : nullptr);
  }
};

void on_write(png_structp png, png_bytep data, size_t n) {
  auto* job = static_cast<EncodeJob*>(png_get_io_ptr(png));
  // an exception must not cross libpng's C frames: note it here, report it outside
  try {
    job->out.append(reinterpret_cast<const char*>(data), n);
  } catch (...) {
    job->out_of_memory = true;
  }
  if (job->out_of_memory) png_error(png, "out of memory while encoding");
}

void on_flush(png_structp) {}

bool run_encode(EncodeJob* job, const std::uint8_t* pixels, int width, int height) {
  if (setjmp(png_jmpbuf(job->png))) return false;
  png_set_write_fn(job->png, job, on_write, on_flush);
  png_set_IHDR(job->png, job->info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(job->png, job->info);
  const size_t stride = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    // libpng's row type is not const, but it only reads the rows it writes
    png_write_row(job->png, const_cast<png_bytep>(pixels + static_cast<size_t>(y) * stride));
  }
  png_write_end(job->png, job->info);
  return true;
}

// decoding: libpng pulls bytes through on_read from the input span
struct DecodeJob {
  ErrorText error;
  png_structp png = nullptr;
  png_infop info = nullptr;
  const unsigned char* data = nullptr;
  size_t size = 0, pos = 0;
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0, interlace = 0;
  std::vector<std::uint8_t> pixels;
  std::vector<png_bytep> rows;
  ~DecodeJob() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  }
};

void on_read(png_structp png, png_bytep out, size_t n) {
  auto* job = static_cast<DecodeJob*>(png_get_io_ptr(png));
  if (n > job->size - job->pos) png_error(png, "unexpected end of data (truncated PNG)");
  std::memcpy(out, job->data + job->pos, n);
  job->pos += n;
}

bool read_header(DecodeJob* job) {
  if (setjmp(png_jmpbuf(job->png))) return false;
  png_set_read_fn(job->png, job, on_read);
  png_set_user_limits(job->png, kMaxSide, kMaxSide);
  png_read_info(job->png, job->info);
  png_get_IHDR(job->png, job->info, &job->width, &job->height, &job->bit_depth, &job->color_type, &job->interlace,
               nullptr, nullptr);
  return true;
}

bool read_pixels(DecodeJob* job) {
  if (setjmp(png_jmpbuf(job->png))) return false;
  if (job->color_type == PNG_COLOR_TYPE_RGB_ALPHA) png_set_strip_alpha(job->png);
  png_set_interlace_handling(job->png);
  png_read_update_info(job->png, job->info);
  png_read_image(job->png, job->rows.data());
  // reading on to IEND checks the rest of the file (a PNG cut after its pixels fails here)
  png_read_end(job->png, nullptr);
  return true;
}

const char* color_type_name(int t) {
  switch (t) {
    case PNG_COLOR_TYPE_GRAY: return "grey";
    case PNG_COLOR_TYPE_GRAY_ALPHA: return "grey+alpha";
    case PNG_COLOR_TYPE_PALETTE: return "palette";
    case PNG_COLOR_TYPE_RGB: return "RGB";
    case PNG_COLOR_TYPE_RGB_ALPHA: return "RGBA";
    default: return "unknown";
  }
}

}  // namespace

std::string Canvas::encode_png() const {
  if (width_ <= 0 || height_ <= 0) {
    throw Error("encode_png: cannot encode an empty " + std::to_string(width_) + "x" + std::to_string(height_) +
                " image");
  }
  EncodeJob job;
  job.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job.error, on_error, on_warning);
  if (job.png) job.info = png_create_info_struct(job.png);
  if (!job.png || !job.info) throw Error("encode_png: libpng could not start (out of memory)");
  job.out.reserve(px_.size() / 4 + 1024);
  if (!run_encode(&job, px_.data(), width_, height_)) throw Error(std::string("encode_png: ") + job.error.text);
  return std::move(job.out);
}

void Canvas::write_png(const std::filesystem::path& path) const {
  std::string bytes;
  try {
    bytes = encode_png();
  } catch (const Error& e) {
    throw Error({path.string(), 0, ""}, e.message());
  }
  write_file_atomic(path, bytes);
}

Canvas decode_png(std::string_view bytes) {
  // the signature first, so plain garbage gets a plain message
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0) {
    throw Error("decode_png: not a PNG file (missing PNG signature)");
  }
  DecodeJob job;
  job.data = reinterpret_cast<const unsigned char*>(bytes.data());
  job.size = bytes.size();
  job.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job.error, on_error, on_warning);
  if (job.png) job.info = png_create_info_struct(job.png);
  if (!job.png || !job.info) throw Error("decode_png: libpng could not start (out of memory)");

  if (!read_header(&job)) throw Error(std::string("decode_png: bad PNG header: ") + job.error.text);
  const bool rgb = job.color_type == PNG_COLOR_TYPE_RGB || job.color_type == PNG_COLOR_TYPE_RGB_ALPHA;
  if (job.bit_depth != 8 || !rgb) {
    throw Error("decode_png: unsupported PNG format (" + std::to_string(job.bit_depth) + "-bit " +
                color_type_name(job.color_type) + "); only 8-bit RGB and RGBA are read");
  }
  if (static_cast<unsigned long long>(job.width) * job.height > kMaxPixels) {
    throw Error("decode_png: image of " + std::to_string(job.width) + "x" + std::to_string(job.height) +
                " pixels is too large");
  }

  // decode into a buffer the job owns (alpha is stripped, so 3 bytes per pixel), then copy
  const size_t stride = static_cast<size_t>(job.width) * 3;
  job.pixels.resize(stride * job.height);
  job.rows.resize(job.height);
  for (png_uint_32 y = 0; y < job.height; ++y) job.rows[y] = job.pixels.data() + y * stride;
  if (!read_pixels(&job)) throw Error(std::string("decode_png: corrupt PNG data: ") + job.error.text);

  Canvas canvas(static_cast<int>(job.width), static_cast<int>(job.height));
  for (int y = 0; y < canvas.height(); ++y) {
    const std::uint8_t* row = job.rows[static_cast<size_t>(y)];
    for (int x = 0; x < canvas.width(); ++x) canvas.set(x, y, {row[3 * x], row[3 * x + 1], row[3 * x + 2]});
  }
  return canvas;
}

}  // namespace rescuesim
