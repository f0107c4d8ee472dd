#include "viz/world_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "viz/font.h"
#include "world/terrain.h"

namespace rescuesim {

namespace {

/// The footprint of a 3-D shape on the floor: the convex hull of its vertices seen from above.
Polygon2 footprint(const Geometry& g, const Pose3& X_WS) {
  const bool has_mesh = g.type == Geometry::Type::mesh || g.type == Geometry::Type::convex;
  const TriangleMesh m = has_mesh ? TriangleMesh{} : mesh_of(g, 16);
  std::vector<Vec2> points;
  for (const Vec3& v : has_mesh ? g.mesh.vertices : m.vertices) points.push_back((X_WS * v).head<2>());
  return convex_hull(std::move(points));
}

// colours of the SVG convention (docs/worlds.md), in the matplotlib "tab10" shades
constexpr Rgb8 kPage{255, 255, 255};
constexpr Rgb8 kFloor{250, 250, 250};
constexpr Rgb8 kFloorEdge{200, 200, 200};
constexpr Rgb8 kGrid{228, 228, 228};
constexpr Rgb8 kWall{0, 0, 0};
constexpr Rgb8 kBlock{51, 51, 51};
constexpr Rgb8 kRaised{214, 39, 40};
constexpr Rgb8 kRamp{235, 147, 147};
constexpr Rgb8 kRubble{255, 127, 14};
constexpr Rgb8 kVictim{31, 119, 180};
constexpr Rgb8 kStart{44, 160, 44};
constexpr Rgb8 kMedium{110, 110, 110};
constexpr Rgb8 kText{0, 0, 0};
constexpr Rgb8 kLegendText{51, 51, 51};

constexpr double kStartRadius = 0.3;  // m
constexpr int kBandGap = 8;           // px between the map and the title or legend

Box2 floor_box(const WorldSpec& world) {
  Box2 b;
  b.extend(world.floor_min);
  b.extend(world.floor_max);
  return b;
}

std::string metres_label(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g m", m);
  return buf;
}

// the scale bar: 1 m, or 5 m for worlds larger than 30 m, then stepped through 1-2-5
// lengths until the bar is between 20 and 200 px long
double scale_bar_m(const Box2& floor, double px_per_m) {
  const double steps[] = {0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000};
  const int n = static_cast<int>(std::size(steps));
  int i = floor.size().maxCoeff() > 30 ? 5 : 3;
  while (i + 1 < n && steps[i] * px_per_m < 20) ++i;
  while (i > 0 && steps[i] * px_per_m > 200) --i;
  return steps[i];
}

// the legend: five coloured squares with labels, then the scale bar, laid out in lines
// that wrap when the image is too narrow for one
struct LegendItem {
  Rgb8 colour;
  const char* label;
};
constexpr LegendItem kLegendItems[] = {
    {kWall, "wall"}, {kRaised, "raised"}, {kVictim, "victim"}, {kRubble, "rubble"}, {kStart, "start"}};
constexpr int kBarEntry = 5;  // entries 0..4 are the items, 5 the scale bar
constexpr int kEntries = 6;

struct Legend {
  int scale = 1;
  double bar_m = 1, bar_px = 50;
  std::vector<std::vector<int>> lines;  // entries on each line
  int width = 0;                        // widest line (px)

  int line_step() const { return 11 * scale; }
  int entry_width(int e) const {
    if (e == kBarEntry) return static_cast<int>(std::ceil(bar_px)) + 5 * scale + font::text_width(metres_label(bar_m), scale);
    return 10 * scale + font::text_width(kLegendItems[e].label, scale);
  }
  // greedy line filling within max_width
  void flow(int max_width) {
    lines.clear();
    width = 0;
    int w = 0;
    for (int e = 0; e < kEntries; ++e) {
      const int ew = entry_width(e), gap = 12 * scale;
      if (!lines.empty() && w + gap + ew <= max_width) {
        lines.back().push_back(e);
        w += gap + ew;
      } else {
        lines.push_back({e});
        w = ew;
      }
      width = std::max(width, w);
    }
  }
};

// where everything goes on a plot_world canvas
struct Layout {
  PlotFrame frame;
  Box2 floor;
  int text_scale = 1;
  bool title = false, legend = false;
  Legend key;
};

Layout make_layout(const WorldSpec& world, const WorldPlotOptions& options) {
  if (!(options.px_per_m > 0) || !std::isfinite(options.px_per_m)) {
    throw Error("world plot: px_per_m must be a positive number, got " + std::to_string(options.px_per_m));
  }
  if (options.max_size_px < 32 || options.max_size_px > 32768) {
    throw Error("world plot: max_size_px must be within 32..32768, got " + std::to_string(options.max_size_px));
  }
  Layout L;
  L.floor = floor_box(world);
  const Vec2 size = L.floor.size();
  if (!(size.x() > 0) || !(size.y() > 0) || !std::isfinite(size.x()) || !std::isfinite(size.y())) {
    throw Error("world plot: the floor rectangle of world '" + world.name + "' is empty or not finite");
  }
  const int cap = options.max_size_px;
  const int margin = std::clamp(cap / 20, 4, 20);

  // title and legend get bands above and below the map; on very small images they are
  // left out so the map keeps its room
  L.title = !options.title.empty() && cap >= 200;
  L.legend = options.legend && cap >= 200;

  // resolution: the requested one, lowered until both sides (bands included) fit the cap
  int top = 0, bottom = 0;
  auto fit = [&](int s, int legend_lines) {
    top = L.title ? 7 * s + kBandGap : 0;
    bottom = L.legend ? legend_lines * 11 * s - 4 * s + kBandGap : 0;
    const double room_w = cap - 2 * margin, room_h = cap - 2 * margin - top - bottom;
    return std::min({options.px_per_m, room_w / size.x(), room_h / size.y()});
  };
  // text is drawn at double size on maps at least 500 px wide; a legend that wraps needs a
  // taller band, which may lower the resolution and change the scale bar, so this repeats
  // until the legend fits its band (the scale drops once, the line count only grows)
  int s = 2, lines = 1;
  double ppm = 0;
  for (;;) {
    ppm = fit(s, lines);
    if (s == 2 && size.x() * ppm < 500) {
      s = 1;
      continue;
    }
    if (!L.legend) break;
    L.key.scale = s;
    L.key.bar_m = scale_bar_m(L.floor, ppm);
    L.key.bar_px = L.key.bar_m * ppm;
    L.key.flow(cap - 2 * margin);
    if (static_cast<int>(L.key.lines.size()) <= lines) break;
    lines = static_cast<int>(L.key.lines.size());
  }
  L.text_scale = s;

  // the frame shows the floor plus the bands, which become extra metres above and below
  PlotFrame& f = L.frame;
  f.px_per_m = ppm;
  f.margin = margin;
  f.world = L.floor;
  f.world.max.y() += top / ppm;
  f.world.min.y() -= bottom / ppm;

  // a legend wider than the map widens the frame evenly on both sides (up to the cap)
  if (L.legend) {
    const int need = std::min(cap, L.key.width + 2 * margin);
    const int have = f.width();
    if (need > have) {
      const double extra = (need - have) / ppm / 2;
      f.world.min.x() -= extra;
      f.world.max.x() += extra;
    }
  }
  return L;
}

Polygon2 to_px(const PlotFrame& f, const Polygon2& poly) {
  Polygon2 out;
  out.reserve(poly.size());
  for (const auto& p : poly) out.push_back(f.to_px(p));
  return out;
}

// the pixel centre at or left of v, for crisp one-pixel grid lines
double snap(double v) { return std::floor(v) + 0.5; }

void draw_grid(Canvas& canvas, const PlotFrame& f, const Box2& floor) {
  // a 1 m grid on the floor, skipped when lines would be closer than 4 px; lines are
  // counted in integers so far-off floors (where x + 1 == x) cannot loop forever
  if (f.px_per_m < 4) return;
  const Vec2 tl = f.to_px({floor.min.x(), floor.max.y()});
  const Vec2 br = f.to_px({floor.max.x(), floor.min.y()});
  const double x0 = std::ceil(floor.min.x()), y0 = std::ceil(floor.min.y());
  const double nx = std::floor(floor.max.x()) - x0 + 1, ny = std::floor(floor.max.y()) - y0 + 1;
  if (!(nx <= 100000 && ny <= 100000)) return;
  for (int i = 0; i < static_cast<int>(nx); ++i) {
    const double px = snap(f.to_px({x0 + i, 0}).x());
    canvas.line({px, tl.y()}, {px, br.y()}, kGrid);
  }
  for (int i = 0; i < static_cast<int>(ny); ++i) {
    const double py = snap(f.to_px({0, y0 + i}).y());
    canvas.line({tl.x(), py}, {br.x(), py}, kGrid);
  }
}

void draw_map(Canvas& canvas, const PlotFrame& f, const WorldSpec& world, bool grid) {
  const double ppm = f.px_per_m;
  const Box2 floor = floor_box(world);

  // floor: a near-white sheet with a light edge and the optional grid
  const Polygon2 floor_poly{
      floor.min, {floor.max.x(), floor.min.y()}, floor.max, {floor.min.x(), floor.max.y()}};
  canvas.fill_polygon(to_px(f, floor_poly), kFloor);
  if (grid) draw_grid(canvas, f, floor);
  canvas.polyline(to_px(f, floor_poly), kFloorEdge, 1.0, true);

  // ground areas (floor patches of other materials) in their material's colour, the grid showing through
  for (const auto& g : world.ground) {
    const MaterialSpec* m = world.find_material(g.material);
    const Vec3 c = m ? m->color : Vec3(0.8, 0.8, 0.8);
    const auto byte = [](double v) { return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0))); };
    canvas.fill_polygon(to_px(f, g.outline), Rgb8{byte(c.x()), byte(c.y()), byte(c.z())}, 0.7);
  }

  // raised areas: ramps first in a lighter red, then the platform tops
  for (const auto& r : world.raised_areas) {
    const int n = static_cast<int>(r.outline.size());
    for (int e : r.ramp_edges) {
      if (e >= 0 && e < n && n >= 2) canvas.fill_polygon(to_px(f, WorldSpec::ramp_outline(r, e)), kRamp);
    }
    canvas.fill_polygon(to_px(f, r.outline), kRaised);
  }

  // test-method terrain: each post, step, deck and ramp, browner the higher its top (white at the
  // floor, full brown from 0.5 m); a ramp in the colour of half its height
  for (const auto& t : world.terrain) {
    std::vector<TerrainSolid> solids;
    try {
      solids = terrain_solids(t);
    } catch (const Error&) {
      continue;  // validation reports it; the plot draws what can be built
    }
    for (const auto& so : solids) {
      double top = 0;
      for (const Vec3& v : mesh_of(so.geometry, 8).vertices) top = std::max(top, (so.X_WS * v).z());
      const double k = std::clamp((so.ramp ? 0.5 : 1.0) * top / 0.5, 0.15, 1.0);
      const auto mix = [k](int brown) { return static_cast<std::uint8_t>(std::lround(255 + k * (brown - 255))); };
      canvas.fill_polygon(to_px(f, footprint(so.geometry, so.X_WS)), Rgb8{mix(140), mix(86), mix(75)});
    }
  }

  // solid obstacles (drawn and from model files), then walls; walls thinner than a pixel still
  // show as hairlines. A model file's solid shows as the convex hull of its footprint.
  for (const auto& b : world.blocks) canvas.fill_polygon(to_px(f, b.outline), kBlock);
  for (const auto& so : world.solids) {
    if (so.victim.empty()) canvas.fill_polygon(to_px(f, footprint(so.geometry, so.X_WS)), kBlock);
  }
  for (const auto& w : world.walls) {
    if (w.thickness * ppm >= 1.0) {
      canvas.fill_polygon(to_px(f, WorldSpec::wall_outline(w)), kWall);
    } else {
      canvas.line(f.to_px(w.a), f.to_px(w.b), kWall, 1.0);
    }
  }

  // rubble: boxes as rotated rectangles, cylinders as discs
  for (const auto& r : world.rubble) {
    if (r.shape == RubbleSpec::Shape::cylinder) {
      canvas.fill_circle(f.to_px(r.pose.position()), 0.5 * r.size.x() * ppm, kRubble);
    } else {
      canvas.fill_polygon(to_px(f, rectangle(r.pose, r.size.x(), r.size.y())), kRubble);
    }
  }

  for (const auto& b : world.bodies) canvas.fill_polygon(to_px(f, footprint(b.geometry, b.X_WB)), kRubble);

  // victims: the footprint, with a white dot near the head end (yaw points feet to head)
  // when the footprint is wide enough to hold one
  for (const auto& v : world.victims) {
    canvas.fill_polygon(to_px(f, WorldSpec::victim_outline(v)), kVictim);
    if (v.width * ppm < 4) continue;
    const double along = v.posture == VictimSpec::Posture::sitting ? 0.55 * v.length : v.length;
    const double head_r = std::min(0.1, 0.25 * v.width);
    const Vec2 head = v.pose.transform({0.5 * along - 1.2 * head_r, 0});
    canvas.fill_circle(f.to_px(head), std::max(head_r * ppm, 1.0), kPage);
  }

  // smoke and dust: their footprint at the start, a translucent grey over what lies beneath
  // (denser media darker, up to 60 % cover from 1/m), with a grey edge
  for (const auto& m : world.media) {
    if (m.outline.size() < 3) continue;
    const auto px = to_px(f, m.outline);
    canvas.fill_polygon(px, kMedium, std::clamp(0.2 + 0.4 * m.density, 0.2, 0.6));
    canvas.polyline(px, kMedium, 1.0, true, 0.8);
  }

  // robot starts: a green disc (at least 3 px, so small plots still show it) with a white
  // heading tick to the rim and a green one beyond
  for (const auto& r : world.robots) {
    const Vec2 c = f.to_px(r.start.position());
    const Vec2 dir(std::cos(r.start.yaw), -std::sin(r.start.yaw));  // y is flipped on the canvas
    const double rad = std::max(kStartRadius * ppm, 3.0);
    const double tick = std::max(1.0, 0.06 * ppm);
    canvas.fill_circle(c, rad, kStart);
    canvas.line(c, c + dir * rad * 0.85, kPage, tick);
    canvas.line(c + dir * rad, c + dir * (rad * 1.6 + 2), kStart, tick);
  }
}

void draw_legend(Canvas& canvas, const Legend& key, int left, int top) {
  const int s = key.scale;
  for (std::size_t i = 0; i < key.lines.size(); ++i) {
    int x = left;
    const int y = top + static_cast<int>(i) * key.line_step();
    for (int e : key.lines[i]) {
      if (e == kBarEntry) {
        // scale bar: a line with end ticks, its length in metres after it
        const double yc = y + 3.5 * s, x0 = x + 0.5 * s, x1 = x0 + key.bar_px;
        canvas.line({x0, yc}, {x1, yc}, kLegendText, s);
        canvas.line({x0, yc - 3 * s}, {x0, yc + 3 * s}, kLegendText, s);
        canvas.line({x1, yc - 3 * s}, {x1, yc + 3 * s}, kLegendText, s);
        canvas.text(static_cast<int>(std::ceil(x1)) + 4 * s, y, metres_label(key.bar_m), kLegendText, s);
      } else {
        canvas.fill_rect(x, y, x + 7 * s, y + 7 * s, kLegendItems[e].colour);
        canvas.text(x + 10 * s, y, kLegendItems[e].label, kLegendText, s);
      }
      x += key.entry_width(e) + 12 * s;
    }
  }
}

}  // namespace

PlotFrame plot_frame_for(const WorldSpec& world, const WorldPlotOptions& options) {
  return make_layout(world, options).frame;
}

Canvas plot_world(const WorldSpec& world, const WorldPlotOptions& options) {
  const Layout L = make_layout(world, options);
  const PlotFrame& f = L.frame;
  Canvas canvas(f.width(), f.height(), kPage);
  draw_map(canvas, f, world, options.grid);

  // title above the map and legend below it, from the floor's left edge; a legend wider
  // than the floor moves left as far as the margin
  const Vec2 top_left = f.to_px({L.floor.min.x(), L.floor.max.y()});
  const Vec2 bottom_left = f.to_px(L.floor.min);
  const int floor_x = static_cast<int>(std::lround(top_left.x()));
  if (L.title) {
    // a title too long for double size falls back to single size
    const int room = canvas.width() - floor_x - f.margin;
    const int s = font::text_width(options.title, L.text_scale) <= room ? L.text_scale : 1;
    canvas.text(floor_x, static_cast<int>(std::lround(top_left.y())) - kBandGap - 7 * s, options.title, kText, s);
  }
  if (L.legend) {
    const int x = std::max(f.margin, std::min(floor_x, canvas.width() - f.margin - L.key.width));
    draw_legend(canvas, L.key, x, static_cast<int>(std::lround(bottom_left.y())) + kBandGap);
  }
  return canvas;
}

void draw_world(Canvas& canvas, const PlotFrame& frame, const WorldSpec& world) {
  draw_map(canvas, frame, world, true);
}

}  // namespace rescuesim
