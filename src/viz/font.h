#pragma once
/// The built-in 5x7 bitmap font behind `Canvas::text` (private to the viz module and its tests).

#include <array>
#include <cstdint>
#include <string_view>

namespace rescuesim::font {

constexpr int kGlyphWidth = 5;   ///< px per glyph, before scaling
constexpr int kGlyphHeight = 7;  ///< px per glyph, before scaling
constexpr int kAdvance = 6;      ///< glyph width plus one pixel of spacing
constexpr int kMaxScale = 256;   ///< largest text scale; larger ones are clamped

/// One glyph: seven rows, top first; bit 4 of a row is its leftmost pixel.
using Glyph = std::array<std::uint8_t, kGlyphHeight>;

/// The glyph of a printable ASCII character (32..126); anything else gets the glyph of '?'.
const Glyph& glyph(char c);

/// The scale text is really drawn at: `scale` clamped to 1..kMaxScale.
int clamp_scale(int scale);

/// Width in px that `Canvas::text` draws for `s` at `scale`: (6 x length - 1) x scale.
int text_width(std::string_view s, int scale = 1);

}  // namespace rescuesim::font
