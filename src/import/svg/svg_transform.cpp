/// SVG transform lists: `translate(10,5) rotate(30 1 1) scale(2) matrix(...) skewX(a) skewY(a)`.

#include <cmath>
#include <string>

#include "import/svg/svg_detail.h"
#include "import/svg/svg_parse.h"

namespace rescuesim::svg {

namespace detail {

// exact right angles so that rotate(90) maps integer points to integer points
void sincos_degrees(double degrees, double& s, double& c) {
  double r = std::fmod(degrees, 360.0);
  if (r < 0) r += 360.0;
  if (r >= 360.0) r = 0.0;
  if (r == 0.0) {
    s = 0.0, c = 1.0;
  } else if (r == 90.0) {
    s = 1.0, c = 0.0;
  } else if (r == 180.0) {
    s = 0.0, c = -1.0;
  } else if (r == 270.0) {
    s = -1.0, c = 0.0;
  } else {
    const double a = r * M_PI / 180.0;
    s = std::sin(a), c = std::cos(a);
  }
}

}  // namespace detail

namespace {

using detail::quote;
using detail::sincos_degrees;

/// An affine map from the six SVG matrix entries (a b c d e f).
Eigen::Affine2d matrix(double a, double b, double c, double d, double e, double f) {
  Eigen::Affine2d m = Eigen::Affine2d::Identity();
  m.linear() << a, c, b, d;
  m.translation() << e, f;
  return m;
}

/// Tangent of a skew angle; a right angle would make the map infinite.
double skew_tangent(double degrees, std::string_view name, std::size_t offset) {
  double s = 0, c = 1;
  sincos_degrees(degrees, s, c);
  if (std::abs(c) < 1e-12)
    throw ParseError(std::string(name) + " angle " + std::to_string(degrees) + " makes the transform infinite", offset);
  return s / c;
}

/// Case-insensitive comparison of a scanned name with a lower-case keyword.
bool name_is(std::string_view name, std::string_view keyword) {
  if (name.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < name.size(); ++i)
    if (detail::to_lower(name[i]) != keyword[i]) return false;
  return true;
}

/// One transform function, its arguments already read, as an affine map.
Eigen::Affine2d function_map(std::string_view name, const double* v, int n, std::size_t offset) {
  auto count_error = [&](const char* expected) {
    return ParseError(std::string(name) + " takes " + expected + " numbers, found " + std::to_string(n), offset);
  };
  if (name_is(name, "matrix")) {
    if (n != 6) throw count_error("6");
    return matrix(v[0], v[1], v[2], v[3], v[4], v[5]);
  }
  if (name_is(name, "translate")) {
    if (n != 1 && n != 2) throw count_error("1 or 2");
    return matrix(1, 0, 0, 1, v[0], n == 2 ? v[1] : 0.0);
  }
  if (name_is(name, "scale")) {
    if (n != 1 && n != 2) throw count_error("1 or 2");
    return matrix(v[0], 0, 0, n == 2 ? v[1] : v[0], 0, 0);
  }
  if (name_is(name, "rotate")) {
    if (n != 1 && n != 3) throw count_error("1 or 3");
    double s = 0, c = 1;
    sincos_degrees(v[0], s, c);
    // rotate(a cx cy) = translate(cx cy) rotate(a) translate(-cx -cy)
    const double cx = n == 3 ? v[1] : 0.0, cy = n == 3 ? v[2] : 0.0;
    return matrix(c, s, -s, c, cx - c * cx + s * cy, cy - s * cx - c * cy);
  }
  if (name_is(name, "skewx")) {
    if (n != 1) throw count_error("1");
    return matrix(1, 0, skew_tangent(v[0], name, offset), 1, 0, 0);
  }
  if (name_is(name, "skewy")) {
    if (n != 1) throw count_error("1");
    return matrix(1, skew_tangent(v[0], name, offset), 0, 1, 0, 0);
  }
  throw ParseError("unknown transform function '" + std::string(name) +
                       "' (expected matrix, translate, scale, rotate, skewX or skewY)",
                   offset);
}

}  // namespace

Eigen::Affine2d parse_transform(std::string_view s) {
  Eigen::Affine2d result = Eigen::Affine2d::Identity();
  std::size_t pos = 0;
  bool first = true;
  while (true) {
    // separators: whitespace and at most one comma between functions
    detail::skip_space(s, pos);
    if (!first && pos < s.size() && s[pos] == ',') {
      ++pos;
      detail::skip_space(s, pos);
      if (pos == s.size()) throw ParseError("expected a transform function after ','", pos);
    }
    if (pos == s.size()) break;

    // function name, then '('
    const std::size_t name_begin = pos;
    while (pos < s.size() && ((s[pos] >= 'a' && s[pos] <= 'z') || (s[pos] >= 'A' && s[pos] <= 'Z'))) ++pos;
    const std::string_view name = s.substr(name_begin, pos - name_begin);
    if (name.empty())
      throw ParseError("expected a transform function (matrix, translate, scale, rotate, skewX, skewY), found " +
                           quote(s, pos),
                       pos);
    detail::skip_space(s, pos);
    if (pos == s.size() || s[pos] != '(')
      throw ParseError("expected '(' after '" + std::string(name) + "', found " + quote(s, pos), pos);
    ++pos;

    // arguments up to ')': at most six are ever valid, a seventh is already an error
    double values[7] = {};
    int count = 0;
    while (true) {
      detail::skip_space(s, pos);
      if (pos == s.size())
        throw ParseError("expected ')' to close '" + std::string(name) + "(', found the end", pos);
      if (s[pos] == ')') break;
      if (count == 0 && s[pos] == ',')
        throw ParseError("expected a number after '" + std::string(name) + "(', found ','", pos);
      if (count == 7) break;
      values[count++] = read_number(s, pos);
    }
    ++pos;

    // the leftmost function is applied last: compose on the right
    result = result * function_map(name, values, count, name_begin);
    if (!result.matrix().allFinite())
      throw ParseError("transform list overflows (the combined matrix is not finite)", name_begin);
    first = false;
  }
  return result;
}

}  // namespace rescuesim::svg
