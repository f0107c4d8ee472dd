#pragma once
/// Parsers for SVG attribute micro-syntaxes: numbers and lengths, transform lists, path data
/// (flattened to polylines) and colours. Pure functions on strings; the loader (svg_loader.cpp)
/// walks the XML and calls these. All throw `svg::ParseError` with the offending character's
/// offset on malformed input.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose.h"

namespace rescuesim::svg {

/// Malformed attribute text: `what()` says what was expected; `offset` is the 0-based
/// character position in the attribute value where parsing failed.
class ParseError : public std::runtime_error {
 public:
  ParseError(const std::string& message, std::size_t offset) : std::runtime_error(message), offset(offset) {}
  std::size_t offset;
};

/// Largest magnitude accepted for any number in a file (user units); bigger is an error.
inline constexpr double kMaxMagnitude = 1e9;

/// Reads one SVG number (`-1.5e3`, `.5`, `+2`) starting at `pos` after skipping whitespace and
/// at most one comma; advances `pos` past it. Rejects inf/nan spellings, out-of-range values
/// and magnitudes above kMaxMagnitude. Throws ParseError when no number is there.
double read_number(std::string_view s, std::size_t& pos);

/// True when only whitespace and commas remain from `pos`.
bool at_end(std::string_view s, std::size_t pos);

/// Unit of a length attribute.
enum class Unit { none, px, mm, cm, m, in, pt, pc, percent, em, ex };

/// A number with its unit, e.g. "12.5cm".
struct Length {
  double value = 0;
  Unit unit = Unit::none;
  /// True for units with a physical size (mm, cm, m, in, pt, pc).
  bool physical() const;
  /// Value in metres for physical units (throws std::logic_error otherwise).
  double metres() const;
  /// Value in CSS pixels / user units (96 px per inch); percent, em, ex use 16 px per em and
  /// treat percent as 0 (callers check the unit first where it matters).
  double user_units() const;
};

/// Parses a whole attribute as one length; throws ParseError on anything else.
Length parse_length(std::string_view s);

/// Parses a transform list (`translate(10,5) rotate(30 1 1) scale(2) matrix(a b c d e f)
/// skewX(a) skewY(a)`, separated by whitespace and/or commas) into one affine map; the
/// leftmost transform is applied last, as SVG specifies. Empty string → identity.
Eigen::Affine2d parse_transform(std::string_view s);

/// A flattened subpath.
struct Subpath {
  std::vector<Vec2> points;  ///< vertices after mapping through `to_world`
  bool closed = false;       ///< true after Z/z (the closing point is not repeated)
};

/// Parses path data (M L H V C S Q T A Z, absolute and relative, implicit repeats) and
/// flattens curves and arcs so that no point of a flattened segment is farther than
/// `tolerance` from the true curve, measured after mapping through `to_world` (which may
/// scale, rotate, skew and flip). Points are returned mapped through `to_world`.
/// Throws ParseError for unknown commands, missing or malformed numbers, data not starting with
/// a moveto, arc flags other than 0/1, and truncated commands ("M 10 10 L" is an error).
std::vector<Subpath> parse_path(std::string_view d, const Eigen::Affine2d& to_world, double tolerance);

/// An ellipse (cx, cy, rx, ry in user units) flattened to a closed polygon within
/// `tolerance` after mapping through `to_world`, counter-clockwise in user space order.
std::vector<Vec2> ellipse_points(double cx, double cy, double rx, double ry, const Eigen::Affine2d& to_world,
                                 double tolerance);

/// A rectangle with optional rounded corners (rx, ry ≥ 0 already resolved per SVG rules),
/// flattened and mapped through `to_world`.
std::vector<Vec2> rect_points(double x, double y, double w, double h, double rx, double ry,
                              const Eigen::Affine2d& to_world, double tolerance);

/// A colour value.
struct Paint {
  enum class Kind { none, color, current_color, inherit, invalid };
  Kind kind = Kind::none;
  Vec3 rgb = Vec3::Zero();  ///< sRGB in [0, 1] when kind == color
  std::string url;          ///< `url(#id)`: the id (lower case), which may name a ground material; else empty
};

/// Parses a paint/colour: `none`, `#rgb`, `#rrggbb`, `#rgba`/`#rrggbbaa` (alpha ignored),
/// `rgb(r,g,b)` with numbers or percentages, `rgba(...)`, `hsl(...)`, the 147 CSS named
/// colours (case-insensitive), `currentColor`, `inherit`, and `url(#id) fallback` (uses the
/// fallback, else none, and keeps the id). Anything else yields Kind::invalid (the caller warns), never throws.
Paint parse_paint(std::string_view s);

/// What a colour means in a world drawing (docs/worlds.md).
enum class Semantic { wall, raised, victim, start, rubble, background, unknown };

/// Classifies an sRGB colour by the convention in docs/worlds.md.
Semantic classify_color(const Vec3& rgb);

/// A readable name for a semantic ("wall", "raised area", ...).
const char* semantic_name(Semantic s);

}  // namespace rescuesim::svg
