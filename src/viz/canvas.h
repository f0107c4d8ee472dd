#pragma once
/// A small RGB raster for figures (maze previews, run overviews, laser plots, batch plots):
/// antialiased lines, filled polygons and circles, 5x7 bitmap text, and PNG output.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/polygon.h"

namespace rescuesim {

/// An 8-bit sRGB colour.
struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8&) const = default;
};

/// An 8-bit RGB image with drawing primitives in pixel coordinates (x right, y down, pixel
/// centres at integer + 0.5).
class Canvas {
 public:
  Canvas(int width, int height, Rgb8 background = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 c);
  /// Blends `c` over the pixel with coverage `alpha` in [0, 1].
  void blend(int x, int y, Rgb8 c, double alpha);

  /// Antialiased line of the given width (px).
  void line(Vec2 a, Vec2 b, Rgb8 c, double width = 1.0, double alpha = 1.0);
  /// Polyline through the points.
  void polyline(const std::vector<Vec2>& pts, Rgb8 c, double width = 1.0, bool closed = false, double alpha = 1.0);
  /// Filled simple polygon (even-odd, with antialiased edges).
  void fill_polygon(const std::vector<Vec2>& pts, Rgb8 c, double alpha = 1.0);
  /// Filled disc.
  void fill_circle(Vec2 centre, double radius, Rgb8 c, double alpha = 1.0);
  /// Circle outline.
  void circle(Vec2 centre, double radius, Rgb8 c, double width = 1.0, double alpha = 1.0);
  /// Axis-aligned filled rectangle [x0, x1) x [y0, y1) in whole pixels.
  void fill_rect(int x0, int y0, int x1, int y1, Rgb8 c);
  /// Text in a built-in 5x7 pixel font scaled by `scale`; printable ASCII; returns the width drawn.
  int text(int x, int y, std::string_view s, Rgb8 c, int scale = 1);
  /// Copies another canvas in with its top-left corner at (x, y).
  void paste(const Canvas& other, int x, int y);

  /// Raw pixels, row-major, 3 bytes per pixel.
  const std::vector<std::uint8_t>& pixels() const { return px_; }

  /// PNG bytes of the image (8-bit RGB).
  std::string encode_png() const;
  /// Writes the image as PNG atomically; throws `Error` naming the path on failure.
  void write_png(const std::filesystem::path& path) const;

 private:
  int width_, height_;
  std::vector<std::uint8_t> px_;
};

/// Decodes an 8-bit RGB or RGBA PNG (for tests and tools); throws `Error` on anything else.
Canvas decode_png(std::string_view bytes);

/// Width in px that Canvas::text draws for `s` at `scale`: (6 × length − 1) × scale, 0 when empty.
int text_width(std::string_view s, int scale = 1);

/// `s` cut and ended with ".." so that it is at most `max_w` px wide at `scale` (unchanged when
/// it fits).
std::string fit_text(std::string_view s, int max_w, int scale = 1);

/// A round step for axis ticks or colour-bar labels over `span`: the smallest of 1, 2, 5 or 10
/// times a power of ten that gives at most `max_ticks` intervals (span 10, 6 ticks → 2).
double nice_step(double span, int max_ticks);

/// Maps world metres to canvas pixels for top-down plots: north up, a margin around.
struct PlotFrame {
  Box2 world;          ///< region shown (m)
  double px_per_m = 50;
  int margin = 20;     ///< px
  int width() const;
  int height() const;
  Vec2 to_px(const Vec2& p_W) const;
};

}  // namespace rescuesim
