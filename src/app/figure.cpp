// The Fig. 2 composite: layout, false colours, the laser plot and the main camera's placement,
// all on CPU images (no graphics calls).

#include "app/figure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "raycast/ray_scene.h"

namespace rescuesim {

namespace {

constexpr Rgb8 kBackground{255, 255, 255};
constexpr Rgb8 kInk{28, 30, 34};
constexpr Rgb8 kSoftInk{90, 94, 100};
constexpr Rgb8 kFrame{150, 154, 160};
constexpr Rgb8 kEmpty{232, 234, 237};

/// Linear interpolation through evenly spaced colour stops.
template <std::size_t N>
Rgb8 ramp(const std::array<Rgb8, N>& stops, double f) {
  if (!std::isfinite(f)) f = 0;
  f = std::clamp(f, 0.0, 1.0) * (N - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(f), N - 2);
  const double t = f - static_cast<double>(i);
  auto mix = [t](std::uint8_t a, std::uint8_t b) { return static_cast<std::uint8_t>(std::lround(a + (b - a) * t)); };
  return {mix(stops[i].r, stops[i + 1].r), mix(stops[i].g, stops[i + 1].g), mix(stops[i].b, stops[i + 1].b)};
}

/// A 1 px frame just outside a rectangle.
void frame(Canvas& c, const PixelRect& r) {
  c.fill_rect(r.x - 1, r.y - 1, r.x + r.w + 1, r.y, kFrame);
  c.fill_rect(r.x - 1, r.y + r.h, r.x + r.w + 1, r.y + r.h + 1, kFrame);
  c.fill_rect(r.x - 1, r.y, r.x, r.y + r.h, kFrame);
  c.fill_rect(r.x + r.w, r.y, r.x + r.w + 1, r.y + r.h, kFrame);
}

/// Pastes `img` into `r`, or a grey box saying `missing` when there is no image.
void place(Canvas& c, const PixelRect& r, const Canvas* img, const std::string& missing, int scale) {
  if (img != nullptr) {
    c.paste(*img, r.x, r.y);
  } else {
    c.fill_rect(r.x, r.y, r.x + r.w, r.y + r.h, kEmpty);
    const std::string s = fit_text(missing, r.w - 8, scale);
    c.text(r.x + (r.w - text_width(s, scale)) / 2, r.y + (r.h - 7 * scale) / 2, s, kSoftInk, scale);
  }
  frame(c, r);
}

/// A tick on a colour bar: where (0..1 along it) and its label.
struct Tick {
  double f;
  std::string label;
};

/// A horizontal colour bar under a panel with tick labels below it.
void colour_bar(Canvas& c, const PixelRect& bar, Rgb8 (*colour)(double), const std::vector<Tick>& ticks, int scale) {
  for (int x = 0; x < bar.w; ++x) {
    const Rgb8 col = colour((x + 0.5) / bar.w);
    c.fill_rect(bar.x + x, bar.y, bar.x + x + 1, bar.y + bar.h, col);
  }
  frame(c, bar);
  // the end labels first, then the inner ones wherever they do not crowd a label already drawn
  std::vector<std::pair<int, int>> taken;
  auto draw = [&](const Tick& t) {
    const int x = bar.x + static_cast<int>(std::lround(t.f * (bar.w - 1)));
    c.fill_rect(x, bar.y + bar.h, x + 1, bar.y + bar.h + scale + 1, kInk);
    const int w = text_width(t.label, scale);
    const int left = std::clamp(x - w / 2, bar.x, bar.x + bar.w - w);
    for (const auto& [l, r] : taken) {
      if (left < r + 5 * scale && left + w + 5 * scale > l) return;
    }
    c.text(left, bar.y + bar.h + scale + 2, t.label, kSoftInk, scale);
    taken.emplace_back(left, left + w);
  };
  if (ticks.empty()) return;
  draw(ticks.front());
  if (ticks.size() > 1) draw(ticks.back());
  for (std::size_t i = 1; i + 1 < ticks.size(); ++i) draw(ticks[i]);
}

/// Tick marks every `step` units over [lo, hi] (display units), the last label carrying `unit`.
std::vector<Tick> ticks_over(double lo, double hi, double step, const char* unit) {
  std::vector<Tick> out;
  if (!(hi > lo)) return out;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9; v += step) {
    out.push_back({(v - lo) / (hi - lo), fmt::format("{:g}", std::abs(v) < 1e-9 ? 0.0 : v)});
  }
  if (!out.empty()) out.back().label += unit;
  return out;
}

}  // namespace

FigureSensors figure_sensors(const RobotSpec& robot) {
  FigureSensors f;
  for (const SensorSpec& s : robot.sensors) {
    const SensorSpec** slot = s.type == SensorSpec::Type::lidar            ? &f.laser
                              : s.type == SensorSpec::Type::color_camera   ? &f.color
                              : s.type == SensorSpec::Type::depth_camera   ? &f.depth
                              : s.type == SensorSpec::Type::thermal_camera ? &f.thermal
                                                                           : nullptr;
    if (slot != nullptr && *slot == nullptr) *slot = &s;
  }
  return f;
}

FigureLayout figure_layout(int width) {
  if (width < kFigureMinWidth || width > kFigureMaxWidth) {
    throw Error(SourceRef{"", 0, "figure_layout"},
                fmt::format("figure width {} px is outside [{}, {}]", width, kFigureMinWidth, kFigureMaxWidth));
  }
  const double u = width / 1600.0;
  FigureLayout l;
  l.width = width;
  l.text_scale = std::max(1, static_cast<int>(std::lround(2 * u)));
  const int s = l.text_scale;
  const int m = static_cast<int>(std::lround(20 * u));
  const int g = static_cast<int>(std::lround(12 * u));
  const int c = static_cast<int>(std::lround(0.2 * width));
  const int ch = static_cast<int>(std::lround(0.75 * c));
  l.caption = 28 * s;
  const int t = m + 7 * (s + 1) + g;
  l.title = {0, 0, width, t};
  const int x_r = width - m - 2 * c - g;
  l.laser = {x_r, t, c, ch};
  l.color = {x_r + c + g, t, c, ch};
  l.depth = {x_r, t + ch + l.caption + g, c, ch};
  l.thermal = {x_r + c + g, t + ch + l.caption + g, c, ch};
  l.main = {m, t, x_r - g - m, 2 * (ch + l.caption) + g - l.caption};
  l.height = t + 2 * (ch + l.caption) + 2 * g;
  return l;
}

Canvas to_canvas(const ColorImage& image) {
  Canvas c(image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 3;
      c.set(x, y, {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]});
    }
  }
  return c;
}

Canvas fit_canvas(const Canvas& src, int w, int h) {
  Canvas out(w, h, kEmpty);
  if (src.width() == 0 || src.height() == 0 || w == 0 || h == 0) return out;
  // the centred part of the source with the destination's aspect
  double sw = src.width(), sh = src.height(), x0 = 0, y0 = 0;
  if (sw * h > sh * w) {
    const double cw = sh * w / h;
    x0 = (sw - cw) / 2;
    sw = cw;
  } else {
    const double crop_h = sw * h / w;
    y0 = (sh - crop_h) / 2;
    sh = crop_h;
  }
  const double sx = sw / w, sy = sh / h;
  const auto& px = src.pixels();
  auto at = [&](int x, int y, int ch) {
    x = std::clamp(x, 0, src.width() - 1);
    y = std::clamp(y, 0, src.height() - 1);
    return static_cast<double>(px[(static_cast<std::size_t>(y) * src.width() + x) * 3 + ch]);
  };
  const bool shrink = sx >= 1 && sy >= 1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double rgb[3] = {0, 0, 0};
      if (shrink) {
        // average the source pixels whose centres fall in this pixel's footprint
        const int i0 = static_cast<int>(std::ceil(x0 + x * sx - 0.5)),
                  i1 = std::max(i0 + 1, static_cast<int>(std::ceil(x0 + (x + 1) * sx - 0.5)));
        const int j0 = static_cast<int>(std::ceil(y0 + y * sy - 0.5)),
                  j1 = std::max(j0 + 1, static_cast<int>(std::ceil(y0 + (y + 1) * sy - 0.5)));
        for (int j = j0; j < j1; ++j) {
          for (int i = i0; i < i1; ++i) {
            for (int k = 0; k < 3; ++k) rgb[k] += at(i, j, k);
          }
        }
        for (double& v : rgb) v /= static_cast<double>((i1 - i0) * (j1 - j0));
      } else {
        // bilinear between the four nearest source pixel centres
        const double u = x0 + (x + 0.5) * sx - 0.5, v = y0 + (y + 0.5) * sy - 0.5;
        const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
        const double fu = u - i, fv = v - j;
        for (int k = 0; k < 3; ++k) {
          rgb[k] =
              (at(i, j, k) * (1 - fu) + at(i + 1, j, k) * fu) * (1 - fv) + (at(i, j + 1, k) * (1 - fu) + at(i + 1, j + 1, k) * fu) * fv;
        }
      }
      auto b = [](double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); };
      out.set(x, y, {b(rgb[0]), b(rgb[1]), b(rgb[2])});
    }
  }
  return out;
}

Rgb8 iron_color(double f) {
  static constexpr std::array<Rgb8, 7> stops{
      {{0, 0, 12}, {42, 6, 100}, {128, 10, 148}, {208, 46, 76}, {246, 122, 20}, {255, 204, 44}, {255, 252, 220}}};
  return ramp(stops, f);
}

Rgb8 depth_color(double f) {
  static constexpr std::array<Rgb8, 6> stops{
      {{214, 48, 39}, {248, 141, 60}, {238, 222, 80}, {102, 194, 120}, {50, 136, 196}, {62, 48, 150}}};
  return ramp(stops, f);
}

Canvas thermal_canvas(const ThermalImage& image, double t_min, double t_max) {
  Canvas c(image.width, image.height);
  const double span = std::max(1e-6, t_max - t_min);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      c.set(x, y, iron_color((image.kelvin[static_cast<std::size_t>(y) * image.width + x] - t_min) / span));
    }
  }
  return c;
}

Canvas depth_canvas(const DepthImage& image, double z_min, double z_max) {
  Canvas c(image.width, image.height, {0, 0, 0});
  const double span = std::max(1e-6, z_max - z_min);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double z = image.z[static_cast<std::size_t>(y) * image.width + x];
      if (std::isfinite(z) && z >= z_min && z <= z_max) c.set(x, y, depth_color((z - z_min) / span));
    }
  }
  return c;
}

Canvas laser_canvas(const msg::LaserScan& scan, int w, int h, double radius, int text_scale) {
  Canvas c(w, h, {246, 248, 251});
  const Vec2 o(w / 2.0, h / 2.0);
  const double scale = (std::min(w, h) / 2.0 - 2) / std::max(radius, 0.1);  // px per m
  // x forward points up the image, y left points left
  auto to_px = [&](double angle, double r) { return Vec2(o.x() - std::sin(angle) * r * scale, o.y() - std::cos(angle) * r * scale); };

  // the swept free space, then rings every metre, labelled straight behind (the blind side)
  std::vector<Vec2> fan{o};
  std::vector<Vec2> hits;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const float r = scan.ranges[i];
    if (std::isnan(r)) continue;
    const bool hit = std::isfinite(r) && r > 0;
    const double reach = hit ? r : (r > 0 ? static_cast<double>(scan.range_max) : 0.0);
    fan.push_back(to_px(a, std::min(reach, 2.0 * radius)));
    if (hit) hits.push_back(to_px(a, r));
  }
  if (fan.size() > 2) c.fill_polygon(fan, {206, 226, 247});
  const double corner = std::hypot(w, h) / 2 / scale;
  for (int ring = 1; ring <= static_cast<int>(corner); ++ring) {
    c.circle(o, ring * scale, {196, 202, 212}, 1.0);
    const std::string label = fmt::format("{} m", ring);
    const int ly = static_cast<int>(o.y() + ring * scale) - 7 * text_scale - 2;
    if (ly + 7 * text_scale < h) c.text(static_cast<int>(o.x()) + 3, ly, label, {120, 126, 136}, text_scale);
  }
  c.line({o.x(), 0}, {o.x(), static_cast<double>(h)}, {222, 226, 232});
  c.line({0, o.y()}, {static_cast<double>(w), o.y()}, {222, 226, 232});
  for (const Vec2& p : hits) c.fill_circle(p, 1.1 + 0.5 * text_scale, {196, 30, 36});
  // the robot: a green arrowhead pointing forward, 0.4 m long
  const double a = 0.2 * scale;
  c.fill_polygon({{o.x(), o.y() - a}, {o.x() + 0.7 * a, o.y() + 0.7 * a}, {o.x(), o.y() + 0.35 * a}, {o.x() - 0.7 * a, o.y() + 0.7 * a}},
                 {34, 150, 60});
  if (scan.ranges.empty()) {
    const char* none = "no scan yet";
    c.text((w - text_width(none, text_scale)) / 2, h / 4, none, kSoftInk, text_scale);
  }
  return c;
}

Canvas compose_figure(const FigureInputs& in) {
  const FigureLayout l = figure_layout(in.width);
  const int s = l.text_scale;
  Canvas fig(l.width, l.height, kBackground);

  // title band
  const int m = l.main.x;
  fig.text(m, m, fit_text(in.title, l.width - 2 * m, s + 1), kInk, s + 1);

  // the main view and its caption
  const Canvas main = fit_canvas(to_canvas(in.main), l.main.w, l.main.h);
  place(fig, l.main, in.main.width > 0 ? &main : nullptr, "no image", s);
  auto caption = [&](const PixelRect& r, const std::string& text) {
    fig.text(r.x, r.y + r.h + 3 * s, fit_text(text, r.w, s), kInk, s);
  };
  caption(l.main, in.main_caption);

  // colour camera
  const Canvas color = fit_canvas(to_canvas(in.color), l.color.w, l.color.h);
  place(fig, l.color, in.color.width > 0 ? &color : nullptr, "no image", s);
  caption(l.color, in.color_caption);

  // thermal camera with a colour bar in degrees Celsius
  const Canvas thermal = fit_canvas(thermal_canvas(in.thermal, in.thermal_min, in.thermal_max), l.thermal.w, l.thermal.h);
  place(fig, l.thermal, in.thermal.width > 0 ? &thermal : nullptr, "no image", s);
  caption(l.thermal, in.thermal_caption);
  const PixelRect thermal_bar{l.thermal.x, l.thermal.y + l.thermal.h + 13 * s, l.thermal.w, 5 * s};
  const double c_lo = in.thermal_min - 273.15, c_hi = in.thermal_max - 273.15;
  colour_bar(fig, thermal_bar, iron_color, ticks_over(c_lo, c_hi, nice_step(c_hi - c_lo, 6), " C"), s);

  // depth camera with a colour bar in metres
  const Canvas depth = fit_canvas(depth_canvas(in.depth, in.depth_min, in.depth_max), l.depth.w, l.depth.h);
  place(fig, l.depth, in.depth.width > 0 ? &depth : nullptr, "no image", s);
  caption(l.depth, in.depth_caption);
  const PixelRect depth_bar{l.depth.x, l.depth.y + l.depth.h + 13 * s, l.depth.w, 5 * s};
  colour_bar(fig, depth_bar, depth_color, ticks_over(in.depth_min, in.depth_max, nice_step(in.depth_max - in.depth_min, 8), " m"), s);

  // laser plot
  const Canvas laser = laser_canvas(in.scan, l.laser.w, l.laser.h, in.laser_radius, s);
  place(fig, l.laser, &laser, "", s);
  caption(l.laser, in.laser_caption);
  return fig;
}

CameraView look_at_view(const Vec3& p_WE, const Vec3& p_WT, const Intrinsics& k) {
  CameraView v;
  v.X_WC = look_at(p_WE, p_WT);
  v.k = k;
  v.near_clip = 0.05;
  v.far_clip = 60.0;
  return v;
}

Vec3 clear_eye(const RayScene& scene, const Vec3& p_WE, const Vec3& p_WT, const Vec3& p_WR, RobotIndex ignore_robot) {
  return clear_eye([&](const Vec3& from, const Vec3& to) { return scene.occluded(from, to, ignore_robot); }, p_WE, p_WT, p_WR);
}

}  // namespace rescuesim
