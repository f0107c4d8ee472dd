/// libFuzzer target for the SVG attribute micro-parsers: every input goes through the path,
/// transform, paint and length parsers. ParseError is the only failure they may report; any
/// other exception, a crash or a sanitizer finding is a bug.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "import/svg/svg_parse.h"

namespace {

using namespace rescuesim;
using namespace rescuesim::svg;

/// Runs `f`, swallowing the one exception the parsers are allowed to throw.
template <typename F>
void expect_only_parse_errors(F&& f) {
  try {
    f();
  } catch (const ParseError&) {
  }
}

/// A skewed, flipped, scaled map like a real loader's to_world, to exercise the world-space
/// segment counts.
Eigen::Affine2d skewed_world() {
  Eigen::Affine2d w = Eigen::Affine2d::Identity();
  w.linear() << 0.01, 0.004, 0.0, -0.01;
  w.translation() << 1.0, 8.0;
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const Eigen::Affine2d identity = Eigen::Affine2d::Identity();
  static const Eigen::Affine2d skewed = skewed_world();

  // the whole input as each kind of attribute
  expect_only_parse_errors([&] { parse_path(text, identity, 0.5); });
  expect_only_parse_errors([&] { parse_path(text, skewed, 0.005); });
  expect_only_parse_errors([&] { parse_transform(text); });
  expect_only_parse_errors([&] { parse_length(text); });
  const Paint paint = parse_paint(text);
  if (paint.kind == Paint::Kind::color) classify_color(paint.rgb);

  // "transform;path": the path flattened through the parsed transform
  const std::size_t split = text.find(';');
  if (split != std::string_view::npos) {
    expect_only_parse_errors([&] {
      const Eigen::Affine2d w = parse_transform(text.substr(0, split));
      parse_path(text.substr(split + 1), w, 0.01);
    });
  }

  // leading numbers as ellipse and rounded-rectangle parameters
  expect_only_parse_errors([&] {
    double v[6] = {};
    std::size_t pos = 0;
    for (double& x : v) x = read_number(text, pos);
    ellipse_points(v[0], v[1], v[2], v[3], skewed, 0.005);
    rect_points(v[0], v[1], v[2], v[3], v[4], v[5], skewed, 0.005);
  });
  return 0;
}
