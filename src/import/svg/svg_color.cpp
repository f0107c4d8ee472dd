/// SVG paints and colours, and what a colour means in a world drawing (docs/worlds.md).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

#include "import/svg/svg_detail.h"
#include "import/svg/svg_parse.h"

namespace rescuesim::svg {

namespace {

struct NamedColor {
  std::string_view name;
  std::uint32_t rgb;
};

// the 147 keywords of CSS Color Module Level 3 (both gray and grey spellings), sorted by name
constexpr NamedColor kNamedColors[] = {
    {"aliceblue", 0xf0f8ff}, {"antiquewhite", 0xfaebd7}, {"aqua", 0x00ffff}, {"aquamarine", 0x7fffd4},
    {"azure", 0xf0ffff}, {"beige", 0xf5f5dc}, {"bisque", 0xffe4c4}, {"black", 0x000000},
    {"blanchedalmond", 0xffebcd}, {"blue", 0x0000ff}, {"blueviolet", 0x8a2be2}, {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887}, {"cadetblue", 0x5f9ea0}, {"chartreuse", 0x7fff00}, {"chocolate", 0xd2691e},
    {"coral", 0xff7f50}, {"cornflowerblue", 0x6495ed}, {"cornsilk", 0xfff8dc}, {"crimson", 0xdc143c},
    {"cyan", 0x00ffff}, {"darkblue", 0x00008b}, {"darkcyan", 0x008b8b}, {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9}, {"darkgreen", 0x006400}, {"darkgrey", 0xa9a9a9}, {"darkkhaki", 0xbdb76b},
    {"darkmagenta", 0x8b008b}, {"darkolivegreen", 0x556b2f}, {"darkorange", 0xff8c00}, {"darkorchid", 0x9932cc},
    {"darkred", 0x8b0000}, {"darksalmon", 0xe9967a}, {"darkseagreen", 0x8fbc8f}, {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f}, {"darkslategrey", 0x2f4f4f}, {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3}, {"deeppink", 0xff1493}, {"deepskyblue", 0x00bfff}, {"dimgray", 0x696969},
    {"dimgrey", 0x696969}, {"dodgerblue", 0x1e90ff}, {"firebrick", 0xb22222}, {"floralwhite", 0xfffaf0},
    {"forestgreen", 0x228b22}, {"fuchsia", 0xff00ff}, {"gainsboro", 0xdcdcdc}, {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700}, {"goldenrod", 0xdaa520}, {"gray", 0x808080}, {"green", 0x008000},
    {"greenyellow", 0xadff2f}, {"grey", 0x808080}, {"honeydew", 0xf0fff0}, {"hotpink", 0xff69b4},
    {"indianred", 0xcd5c5c}, {"indigo", 0x4b0082}, {"ivory", 0xfffff0}, {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa}, {"lavenderblush", 0xfff0f5}, {"lawngreen", 0x7cfc00}, {"lemonchiffon", 0xfffacd},
    {"lightblue", 0xadd8e6}, {"lightcoral", 0xf08080}, {"lightcyan", 0xe0ffff},
    {"lightgoldenrodyellow", 0xfafad2}, {"lightgray", 0xd3d3d3}, {"lightgreen", 0x90ee90},
    {"lightgrey", 0xd3d3d3}, {"lightpink", 0xffb6c1}, {"lightsalmon", 0xffa07a}, {"lightseagreen", 0x20b2aa},
    {"lightskyblue", 0x87cefa}, {"lightslategray", 0x778899}, {"lightslategrey", 0x778899},
    {"lightsteelblue", 0xb0c4de}, {"lightyellow", 0xffffe0}, {"lime", 0x00ff00}, {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6}, {"magenta", 0xff00ff}, {"maroon", 0x800000}, {"mediumaquamarine", 0x66cdaa},
    {"mediumblue", 0x0000cd}, {"mediumorchid", 0xba55d3}, {"mediumpurple", 0x9370db},
    {"mediumseagreen", 0x3cb371}, {"mediumslateblue", 0x7b68ee}, {"mediumspringgreen", 0x00fa9a},
    {"mediumturquoise", 0x48d1cc}, {"mediumvioletred", 0xc71585}, {"midnightblue", 0x191970},
    {"mintcream", 0xf5fffa}, {"mistyrose", 0xffe4e1}, {"moccasin", 0xffe4b5}, {"navajowhite", 0xffdead},
    {"navy", 0x000080}, {"oldlace", 0xfdf5e6}, {"olive", 0x808000}, {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500}, {"orangered", 0xff4500}, {"orchid", 0xda70d6}, {"palegoldenrod", 0xeee8aa},
    {"palegreen", 0x98fb98}, {"paleturquoise", 0xafeeee}, {"palevioletred", 0xdb7093}, {"papayawhip", 0xffefd5},
    {"peachpuff", 0xffdab9}, {"peru", 0xcd853f}, {"pink", 0xffc0cb}, {"plum", 0xdda0dd},
    {"powderblue", 0xb0e0e6}, {"purple", 0x800080}, {"red", 0xff0000}, {"rosybrown", 0xbc8f8f},
    {"royalblue", 0x4169e1}, {"saddlebrown", 0x8b4513}, {"salmon", 0xfa8072}, {"sandybrown", 0xf4a460},
    {"seagreen", 0x2e8b57}, {"seashell", 0xfff5ee}, {"sienna", 0xa0522d}, {"silver", 0xc0c0c0},
    {"skyblue", 0x87ceeb}, {"slateblue", 0x6a5acd}, {"slategray", 0x708090}, {"slategrey", 0x708090},
    {"snow", 0xfffafa}, {"springgreen", 0x00ff7f}, {"steelblue", 0x4682b4}, {"tan", 0xd2b48c},
    {"teal", 0x008080}, {"thistle", 0xd8bfd8}, {"tomato", 0xff6347}, {"turquoise", 0x40e0d0},
    {"violet", 0xee82ee}, {"wheat", 0xf5deb3}, {"white", 0xffffff}, {"whitesmoke", 0xf5f5f5},
    {"yellow", 0xffff00}, {"yellowgreen", 0x9acd32},
};

static_assert(std::size(kNamedColors) == 147, "CSS3 defines 147 colour keywords");
static_assert(std::is_sorted(std::begin(kNamedColors), std::end(kNamedColors),
                             [](const NamedColor& a, const NamedColor& b) { return a.name < b.name; }),
              "binary search needs the table sorted");

Paint color(double r, double g, double b) {
  Paint p;
  p.kind = Paint::Kind::color;
  p.rgb = Vec3(r, g, b);
  return p;
}

Paint invalid() {
  Paint p;
  p.kind = Paint::Kind::invalid;
  return p;
}

std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && detail::is_space(s[b])) ++b;
  while (e > b && detail::is_space(s[e - 1])) --e;
  return s.substr(b, e - b);
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

double clamp01(double v) { return v > 0.0 ? std::min(v, 1.0) : 0.0; }

/// `#rgb`, `#rgba`, `#rrggbb`, `#rrggbbaa` (lower-cased, without the '#'); alpha is ignored.
Paint parse_hex(std::string_view h) {
  int d[8] = {};
  if (h.size() != 3 && h.size() != 4 && h.size() != 6 && h.size() != 8) return invalid();
  for (std::size_t i = 0; i < h.size(); ++i)
    if ((d[i] = hex_digit(h[i])) < 0) return invalid();
  if (h.size() <= 4) return color(d[0] * 17 / 255.0, d[1] * 17 / 255.0, d[2] * 17 / 255.0);
  return color((d[0] * 16 + d[1]) / 255.0, (d[2] * 16 + d[3]) / 255.0, (d[4] * 16 + d[5]) / 255.0);
}

/// One argument of rgb()/hsl(): a number with an optional `%` or angle unit.
struct Component {
  double value = 0;
  std::string unit;
};

/// Splits the inside of a colour function: components separated by commas, whitespace, or
/// `/` before the alpha (CSS Color 4 syntax). False on any malformed piece.
bool parse_components(std::string_view inner, std::vector<Component>& out) {
  inner = trim(inner);
  std::size_t pos = 0;
  while (pos < inner.size()) {
    if (!out.empty()) {
      const std::size_t before = pos;
      detail::skip_space(inner, pos);
      if (pos < inner.size() && (inner[pos] == ',' || (inner[pos] == '/' && out.size() == 3))) {
        ++pos;
        detail::skip_space(inner, pos);
      } else if (pos == before) {
        return false;
      }
      if (pos == inner.size()) return false;
    }
    if (out.size() == 4) return false;
    Component c;
    try {
      c.value = detail::scan_number(inner, pos);
    } catch (const ParseError&) {
      return false;
    }
    while (pos < inner.size() && ((inner[pos] >= 'a' && inner[pos] <= 'z') || inner[pos] == '%')) c.unit += inner[pos++];
    out.push_back(std::move(c));
  }
  return true;
}

/// A channel of rgb(): 0–255 or a percentage, clamped.
bool rgb_channel(const Component& c, double& v) {
  if (c.unit == "%") v = clamp01(c.value / 100.0);
  else if (c.unit.empty()) v = clamp01(c.value / 255.0);
  else return false;
  return true;
}

/// An alpha value: checked for syntax, then ignored.
bool alpha_ok(const Component& c) { return c.unit.empty() || c.unit == "%"; }

/// CSS3's HSL to RGB helper.
double hue_to_rgb(double m1, double m2, double h) {
  if (h < 0) h += 1;
  if (h > 1) h -= 1;
  if (h * 6 < 1) return m1 + (m2 - m1) * h * 6;
  if (h * 2 < 1) return m2;
  if (h * 3 < 2) return m1 + (m2 - m1) * (2.0 / 3.0 - h) * 6;
  return m1;
}

Paint parse_function(std::string_view name, std::string_view inner) {
  std::vector<Component> c;
  if (!parse_components(inner, c) || c.size() < 3) return invalid();
  if (c.size() == 4 && !alpha_ok(c[3])) return invalid();

  if (name == "rgb" || name == "rgba") {
    double r = 0, g = 0, b = 0;
    if (!rgb_channel(c[0], r) || !rgb_channel(c[1], g) || !rgb_channel(c[2], b)) return invalid();
    return color(r, g, b);
  }

  // hsl: hue in degrees (or another angle unit), saturation and lightness in percent
  double degrees = c[0].value;
  if (c[0].unit == "rad") degrees = c[0].value * 180.0 / M_PI;
  else if (c[0].unit == "grad") degrees = c[0].value * 0.9;
  else if (c[0].unit == "turn") degrees = c[0].value * 360.0;
  else if (!c[0].unit.empty() && c[0].unit != "deg") return invalid();
  if (c[1].unit != "%" || c[2].unit != "%") return invalid();
  double h = std::fmod(degrees, 360.0) / 360.0;
  if (h < 0) h += 1.0;
  const double s = clamp01(c[1].value / 100.0), l = clamp01(c[2].value / 100.0);
  const double m2 = l <= 0.5 ? l * (s + 1) : l + s - l * s;
  const double m1 = l * 2 - m2;
  return color(clamp01(hue_to_rgb(m1, m2, h + 1.0 / 3.0)), clamp01(hue_to_rgb(m1, m2, h)),
               clamp01(hue_to_rgb(m1, m2, h - 1.0 / 3.0)));
}

/// A paint without `url(...)`: keyword, hex, function or named colour (already lower-case).
Paint parse_plain(std::string_view t) {
  if (t == "none" || t == "transparent") return Paint{};
  if (t == "currentcolor") return Paint{Paint::Kind::current_color, Vec3::Zero(), {}};
  if (t == "inherit") return Paint{Paint::Kind::inherit, Vec3::Zero(), {}};
  if (t.empty()) return invalid();
  if (t.front() == '#') return parse_hex(t.substr(1));

  // functional notation: name, optional space, '(' ... ')'
  const std::size_t open = t.find('(');
  if (open != std::string_view::npos) {
    const std::string_view name = trim(t.substr(0, open));
    if (t.back() != ')' || (name != "rgb" && name != "rgba" && name != "hsl" && name != "hsla")) return invalid();
    return parse_function(name, t.substr(open + 1, t.size() - open - 2));
  }

  const auto* end = std::end(kNamedColors);
  const auto* it = std::lower_bound(std::begin(kNamedColors), end, t,
                                    [](const NamedColor& a, std::string_view n) { return a.name < n; });
  if (it == end || it->name != t) return invalid();
  return color(((it->rgb >> 16) & 0xff) / 255.0, ((it->rgb >> 8) & 0xff) / 255.0, (it->rgb & 0xff) / 255.0);
}

}  // namespace

Paint parse_paint(std::string_view s) {
  // case-insensitive: lower-case once (ASCII only, no locale)
  std::string t;
  t.reserve(s.size());
  for (char c : trim(s)) t += detail::to_lower(c);

  // url(#id) [fallback]: gradients and patterns are not followed, so the fallback decides
  if (t.rfind("url(", 0) == 0) {
    const std::size_t close = t.find(')');
    if (close == std::string::npos) return invalid();
    const std::string_view fallback = trim(std::string_view(t).substr(close + 1));
    if (fallback.rfind("url(", 0) == 0) return invalid();
    Paint p = fallback.empty() ? Paint{} : parse_plain(fallback);
    const std::string_view ref = trim(std::string_view(t).substr(4, close - 4));
    if (ref.size() > 1 && ref.front() == '#') p.url = std::string(ref.substr(1));
    return p;
  }
  return parse_plain(t);
}

Semantic classify_color(const Vec3& rgb) {
  // HSV from the clamped channels; NaN counts as 0
  const double r = clamp01(rgb.x()), g = clamp01(rgb.y()), b = clamp01(rgb.z());
  const double v = std::max({r, g, b}), lo = std::min({r, g, b});
  const double chroma = v - lo;
  const double s = v > 0 ? chroma / v : 0.0;
  if (v <= 0.25) return Semantic::wall;
  if (s < 0.15 && v >= 0.85) return Semantic::background;
  if (s < 0.40) return Semantic::unknown;

  double hue = 0;
  if (v == r) hue = 60.0 * (g - b) / chroma;
  else if (v == g) hue = 60.0 * (b - r) / chroma + 120.0;
  else hue = 60.0 * (r - g) / chroma + 240.0;
  if (hue < 0) hue += 360.0;

  if (hue <= 20.0 || hue >= 340.0) return Semantic::raised;
  if (hue >= 25.0 && hue <= 65.0) return Semantic::rubble;
  if (hue >= 80.0 && hue <= 160.0) return Semantic::start;
  if (hue >= 200.0 && hue <= 260.0) return Semantic::victim;
  return Semantic::unknown;
}

const char* semantic_name(Semantic s) {
  switch (s) {
    case Semantic::wall: return "wall";
    case Semantic::raised: return "raised area";
    case Semantic::victim: return "victim";
    case Semantic::start: return "robot start";
    case Semantic::rubble: return "rubble";
    case Semantic::background: return "background";
    case Semantic::unknown: return "unknown";
  }
  return "unknown";
}

}  // namespace rescuesim::svg
