#pragma once
/// Internal helpers shared by the SVG micro-parsers (svg_number.cpp, svg_transform.cpp,
/// svg_path.cpp, svg_flatten.cpp, svg_color.cpp): character classes and curve flattening.
/// Not part of the public API; include svg_parse.h instead.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "import/svg/svg_parse.h"

namespace rescuesim::svg::detail {

/// SVG whitespace (space, tab, CR, LF) plus form feed.
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// ASCII lower case, leaving other bytes alone (no locale).
inline char to_lower(char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; }

/// Advances `pos` over whitespace.
inline void skip_space(std::string_view s, std::size_t& pos) {
  while (pos < s.size() && is_space(s[pos])) ++pos;
}

/// True when the character at `pos` can begin a number (digit, sign or point).
inline bool starts_number(std::string_view s, std::size_t pos) {
  return pos < s.size() && (is_digit(s[pos]) || s[pos] == '.' || s[pos] == '-' || s[pos] == '+');
}

/// Sine and cosine of an angle in degrees, exact at multiples of 90°.
void sincos_degrees(double degrees, double& s, double& c);

/// Up to `max_chars` characters of `s` from `pos`, for quoting in messages ("end" if none).
std::string quote(std::string_view s, std::size_t pos, std::size_t max_chars = 12);

/// Reads a number exactly at `pos` (no whitespace or comma skipping) and advances past it.
/// Same rules and errors as read_number.
double scan_number(std::string_view s, std::size_t& pos);

/// Curve flattening in world space. Every function appends the points after the start point
/// (the caller has already emitted it), mapped through `W`, with consecutive duplicates
/// dropped; the last point appended is exactly the mapped end point.
struct Flattener {
  Eigen::Affine2d W;  ///< user space → world
  double tolerance;   ///< largest chord error in world units

  /// Appends a mapped point unless it repeats the last one.
  void point(std::vector<Vec2>& out, const Vec2& p_user) const;
  /// Quadratic Bézier from p0 through control c to p1 (user space).
  void quad(std::vector<Vec2>& out, const Vec2& p0, const Vec2& c, const Vec2& p1) const;
  /// Cubic Bézier from p0 with controls c0, c1 to p1 (user space).
  void cubic(std::vector<Vec2>& out, const Vec2& p0, const Vec2& c0, const Vec2& c1, const Vec2& p1) const;
  /// SVG endpoint arc from p0 to p1 (radii, x-axis rotation in degrees, flags as in `A`).
  void arc(std::vector<Vec2>& out, const Vec2& p0, double rx, double ry, double phi_deg, bool large, bool sweep,
           const Vec2& p1) const;
  /// Centre-parameterised elliptic arc c + axes * (cos t, sin t) (user space) for t from t0 to
  /// t0 + dt; appends the points after t0. `end` (user space), if given, replaces the last point.
  void centre_arc(std::vector<Vec2>& out, const Vec2& c, const Eigen::Matrix2d& axes, double t0, double dt,
                  const Vec2* end) const;
};

/// Largest singular value of a 2x2 matrix (its largest stretch of any direction).
double largest_singular_value(const Eigen::Matrix2d& m);

/// True when two world points are the same up to rounding.
bool same_point(const Vec2& a, const Vec2& b);

/// Number of chords for a curve whose ideal (real-valued) count is `ideal`: ceil, clamped to
/// [1, 1000]; NaN and infinity give 1000.
int segment_count(double ideal);

}  // namespace rescuesim::svg::detail
