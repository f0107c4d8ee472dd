#include "world/terrain.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rescuesim {

namespace {

/// SplitMix64: a small generator with a fixed definition, so a seed gives the same stepfield on
/// every platform and standard library (std::uniform_int_distribution is not specified bit for bit).
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// The most solids one element may make: a bound on what a file can make us build.
constexpr double kMaxSolids = 100000;

struct Builder {
  explicit Builder(const TerrainSpec& spec) : t(spec), X_WT(Pose3::from_pose2(spec.pose)) {}
  const TerrainSpec& t;
  Pose3 X_WT;
  std::vector<TerrainSolid> out;

  [[noreturn]] void fail(const std::string& what) const {
    SourceRef where = t.source;
    if (where.element.empty()) where.element = std::string(TerrainSpec::kind_name(t.kind)) + " '" + t.name + "'";
    throw Error(where, what);
  }

  /// A box over [x0, x1] x [y0, y1] in the element's frame, from the floor to `top`.
  void box(const std::string& part, double x0, double x1, double y0, double y1, double top) {
    Pose3 X_TS;
    X_TS.p = Vec3(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * top);
    out.push_back({t.name + "_" + part, Geometry::box({x1 - x0, y1 - y0, top}), X_WT * X_TS, false});
  }

  /// A wedge over [x0, x1] x [y0, y1] (element frame), on the floor, rising to `rise` at the side
  /// `high` points to: +x, -x, +y or -y (0, 1, 2, 3).
  void wedge(const std::string& part, double x0, double x1, double y0, double y1, double rise, int high) {
    TriangleMesh m;
    const Vec3 c[4] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
    for (const Vec3& p : c) m.vertices.push_back(X_WT * p);
    // the two corners on the high side get a top vertex each
    const int top[4][2] = {{1, 2}, {3, 0}, {2, 3}, {0, 1}};
    for (int k : top[high]) m.vertices.push_back(X_WT * (c[k] + Vec3(0, 0, rise)));
    const int a = top[high][0], b = top[high][1];
    // bottom, the high face (a, b, b', a'), the slope from the low edge up to (a', b'), two sides
    const int lo_a = (b + 1) % 4, lo_b = (a + 3) % 4;  // the low edge runs lo_a -> lo_b, opposite (a, b)
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {a, b, 5}, {a, 5, 4}, {lo_a, lo_b, 4}, {lo_a, 4, 5}, {lo_b, a, 4}, {b, lo_a, 5}};
    orient_outward(m);
    out.push_back({t.name + "_" + part, Geometry::convex(std::move(m)), Pose3{}, true});
  }

  void stepfield() {
    const double fx = std::floor(t.length / t.post + 1e-9), fy = std::floor(t.width / t.post + 1e-9);
    if (fx * fy > kMaxSolids) {
      fail("a stepfield of " + message_number(t.length) + " x " + message_number(t.width) + " m in " + message_number(t.post) +
           " m posts would have " + message_number(fx * fy) + " posts (expected at most " + message_number(kMaxSolids) +
           ": larger posts or a smaller footprint)");
    }
    const int nx = static_cast<int>(fx), ny = static_cast<int>(fy);
    if (nx < 1 || ny < 1) {
      fail("a stepfield of " + message_number(t.length) + " x " + message_number(t.width) + " m holds no " + message_number(t.post) +
           " m post (expected a footprint of at least one post)");
    }
    const std::vector<double> h = stepfield_heights(t, nx, ny);
    const double x0 = -0.5 * nx * t.post, y0 = -0.5 * ny * t.post;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const double x = x0 + i * t.post, y = y0 + j * t.post;
        box("post_" + std::to_string(i * ny + j), x, x + t.post, y, y + t.post, h[static_cast<std::size_t>(i * ny + j)]);
      }
    }
  }

  void stairs() {
    if (!(t.angle > 10 && t.angle <= 60)) {
      fail("stairs at " + message_number(t.angle) +
           " deg cannot be built (expected a slope above 10 and at most 60 degrees; the test method's are 35-45)");
    }
    if (!(t.riser > 0) || !(t.height >= t.riser))
      fail("stairs rising " + message_number(t.height) + " m in " + message_number(t.riser) +
           " m risers have no step (expected a rise of at least one riser)");
    if (t.height / t.riser > 1000)
      fail("stairs rising " + message_number(t.height) + " m in " + message_number(t.riser) + " m risers would have more than 1000 steps");
    const int n = static_cast<int>(std::lround(t.height / t.riser));
    const double tread = t.riser / std::tan(t.angle * M_PI / 180);
    const double landing = t.length - (n - 1) * tread;
    if (landing < 0.3) {
      fail(std::to_string(n) + " steps of " + message_number(tread) + " m need " + message_number((n - 1) * tread + 0.3) +
           " m with a 0.3 m landing; the footprint is " + message_number(t.length) + " m long");
    }
    const double x0 = -0.5 * t.length, y0 = -0.5 * t.width, y1 = 0.5 * t.width;
    for (int k = 1; k < n; ++k) box("step_" + std::to_string(k), x0 + (k - 1) * tread, x0 + k * tread, y0, y1, k * t.riser);
    box("landing", x0 + (n - 1) * tread, 0.5 * t.length, y0, y1, n * t.riser);
  }

  void crossing_ramps() {
    if (!(t.angle > 0 && t.angle <= 45))
      fail("crossing ramps at " + message_number(t.angle) +
           " deg (expected a slope above 0 and at most 45 degrees; the test method's is 15)");
    if (t.length / t.width > kMaxSolids)
      fail("crossing ramps " + message_number(t.length) + " m long in " + message_number(t.width) + " m cells would be more than " +
           message_number(kMaxSolids) + " ramps");
    const int n = static_cast<int>(std::floor(t.length / t.width + 1e-9));
    if (n < 1)
      fail("crossing ramps need a footprint at least as long as it is wide (" + message_number(t.width) + " m); it is " +
           message_number(t.length) + " m");
    const double rise = t.width * std::tan(t.angle * M_PI / 180);
    const double x0 = -0.5 * n * t.width, y0 = -0.5 * t.width, y1 = 0.5 * t.width;
    // square cells in turn: pitch up, roll left, pitch down, roll right
    const int high[4] = {0, 2, 1, 3};
    for (int i = 0; i < n; ++i) wedge("ramp_" + std::to_string(i), x0 + i * t.width, x0 + (i + 1) * t.width, y0, y1, rise, high[i % 4]);
  }

  void curb() {
    if (!(t.height > 0)) fail("curb height " + message_number(t.height) + " m is not positive");
    box("curb", 0, 0.5 * t.length, -0.5 * t.width, 0.5 * t.width, t.height);
  }

  void hurdle() {
    if (!(t.height > 0) || !(t.thickness > 0))
      fail("hurdle of " + message_number(t.height) + " m height and " + message_number(t.thickness) +
           " m thickness (expected both positive)");
    if (t.thickness > t.length)
      fail("hurdle " + message_number(t.thickness) + " m thick in a footprint " + message_number(t.length) + " m long");
    box("hurdle", -0.5 * t.thickness, 0.5 * t.thickness, -0.5 * t.width, 0.5 * t.width, t.height);
  }

  void gap() {
    if (!(t.height > 0) || !(t.gap > 0))
      fail("gap of " + message_number(t.gap) + " m between decks " + message_number(t.height) + " m high (expected both positive)");
    // 15 degree ramps up to decks of at least 0.3 m each side of the opening
    const double ramp = t.height / std::tan(15 * M_PI / 180);
    const double need = t.gap + 2 * ramp + 2 * 0.3;
    if (t.length < need)
      fail("a " + message_number(t.gap) + " m gap between " + message_number(t.height) + " m decks needs " + message_number(need) +
           " m (15 deg ramps, 0.3 m decks); the footprint is " + message_number(t.length) + " m long");
    const double L = 0.5 * t.length, y0 = -0.5 * t.width, y1 = 0.5 * t.width;
    wedge("ramp_in", -L, -L + ramp, y0, y1, t.height, 0);
    box("deck_near", -L + ramp, -0.5 * t.gap, y0, y1, t.height);
    box("deck_far", 0.5 * t.gap, L - ramp, y0, y1, t.height);
    wedge("ramp_out", L - ramp, L, y0, y1, t.height, 1);
  }
};

}  // namespace

TerrainSpec TerrainSpec::defaults(Kind kind) {
  TerrainSpec t;
  t.kind = kind;
  switch (kind) {
    case Kind::stepfield: break;
    case Kind::stairs: t.height = 0.8, t.angle = 40, t.riser = 0.2; break;
    case Kind::crossing_ramps: t.length = 3.6, t.angle = 15; break;
    case Kind::curb: t.length = 1.2, t.height = 0.15; break;
    case Kind::hurdle: t.length = 1.2, t.height = 0.2; break;
    case Kind::gap: t.length = 3.6, t.height = 0.2, t.gap = 0.3; break;
  }
  return t;
}

const char* TerrainSpec::kind_name(Kind kind) {
  switch (kind) {
    case Kind::stepfield: return "stepfield";
    case Kind::stairs: return "stairs";
    case Kind::crossing_ramps: return "crossing-ramps";
    case Kind::curb: return "curb";
    case Kind::hurdle: return "hurdle";
    case Kind::gap: return "gap";
  }
  return "?";
}

Polygon2 TerrainSpec::outline() const { return rectangle(pose, length, width); }

std::vector<double> stepfield_heights(const TerrainSpec& t, int nx, int ny) {
  std::uint64_t state = t.seed;
  const double unit = t.half_cubic ? 0.5 * t.post : t.post;
  std::vector<double> h(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (double& v : h) v = unit * static_cast<double>(1 + splitmix64(state) % 4);
  return h;
}

std::vector<TerrainSolid> terrain_solids(const TerrainSpec& t) {
  Builder b(t);
  if (!(t.length > 0) || !(t.width > 0) || !std::isfinite(t.length) || !std::isfinite(t.width)) {
    b.fail("footprint " + message_number(t.length) + " x " + message_number(t.width) + " m is not a positive size");
  }
  if (!std::isfinite(t.height) || t.height < 0) b.fail("height " + message_number(t.height) + " m is negative or not a number");
  switch (t.kind) {
    case TerrainSpec::Kind::stepfield:
      if (!(t.post > 0) || !std::isfinite(t.post)) b.fail("post size " + message_number(t.post) + " m is not positive");
      b.stepfield();
      break;
    case TerrainSpec::Kind::stairs: b.stairs(); break;
    case TerrainSpec::Kind::crossing_ramps: b.crossing_ramps(); break;
    case TerrainSpec::Kind::curb: b.curb(); break;
    case TerrainSpec::Kind::hurdle: b.hurdle(); break;
    case TerrainSpec::Kind::gap: b.gap(); break;
  }
  return std::move(b.out);
}

TerrainSpec::Kind terrain_kind_from_name(const std::string& name) {
  using K = TerrainSpec::Kind;
  for (K kind : {K::stepfield, K::stairs, K::crossing_ramps, K::curb, K::hurdle, K::gap}) {
    if (name == TerrainSpec::kind_name(kind)) return kind;
  }
  throw Error("unknown terrain '" + name + "'; expected stepfield, stairs, crossing-ramps, curb, hurdle or gap");
}

WorldSpec test_method_arena(const ArenaOptions& o) {
  if (o.lanes.empty()) throw Error("an arena needs at least one lane (expected --lanes like stepfield,stairs)");
  if (o.start_lane < 0 || o.start_lane >= static_cast<int>(o.lanes.size())) {
    throw Error("start lane " + std::to_string(o.start_lane) + " does not exist; the arena has " + std::to_string(o.lanes.size()) +
                " lanes (0.." + std::to_string(o.lanes.size() - 1) + ")");
  }
  if (!(o.lane_width >= 0.6) || !std::isfinite(o.lane_width))
    throw Error("lane width " + message_number(o.lane_width) + " m is too narrow for a robot (expected at least 0.6 m)");
  if (!(o.approach >= 1.0) || !std::isfinite(o.approach))
    throw Error("approach " + message_number(o.approach) + " m is too short to start from (expected at least 1 m)");
  if (o.figure_eight) {
    for (TerrainSpec::Kind k : o.lanes) {
      if (!is_figure_eight_kind(k)) {
        throw Error(std::string("a figure-8 arena holds stepfields and crossing ramps (the test methods' figure-8 terrains), not ") +
                    TerrainSpec::kind_name(k) + "; drive " + TerrainSpec::kind_name(k) + " in lanes (leave out --figure-eight)");
      }
    }
    if (!(o.lane_width >= kFigureEightLaneWidth - 1e-9)) {
      throw Error("lane width " + message_number(o.lane_width) + " m is too narrow for a figure-8 element " +
                  message_number(kFigureEightWidth) + " m wide (expected at least " + message_number(kFigureEightLaneWidth) + " m)");
    }
  }
  WorldSpec w;
  w.name = "arena";
  w.seed = o.seed;
  w.materials = default_materials();
  double longest = 0;
  for (TerrainSpec::Kind k : o.lanes) longest = std::max(longest, o.figure_eight ? kFigureEightLength : TerrainSpec::defaults(k).length);
  const double length = longest + 2 * o.approach, width = o.lane_width * static_cast<double>(o.lanes.size());
  w.floor_min = {0, 0};
  w.floor_max = {width, length};
  const double t = 0.05;
  auto wall = [&](Vec2 a, Vec2 b) { w.walls.push_back({a, b, t, o.wall_height, "wall", {}}); };
  wall({0, 0}, {width, 0});
  wall({width, 0}, {width, length});
  wall({width, length}, {0, length});
  wall({0, length}, {0, 0});
  // lane walls stop short of the south end, so a robot can be moved from lane to lane there
  for (std::size_t i = 1; i < o.lanes.size(); ++i)
    wall({o.lane_width * static_cast<double>(i), length}, {o.lane_width * static_cast<double>(i), 0.6 * o.approach});
  for (std::size_t i = 0; i < o.lanes.size(); ++i) {
    TerrainSpec e = TerrainSpec::defaults(o.lanes[i]);
    e.name = std::string(i < 10 ? "lane_0" : "lane_") + std::to_string(i) + "_" + TerrainSpec::kind_name(o.lanes[i]);
    for (char& c : e.name) c = c == '-' ? '_' : c;
    e.width = o.lane_width - 0.1;
    if (o.figure_eight) {
      e.width = kFigureEightWidth;
      e.length = kFigureEightLength;
    }
    e.seed = o.seed + i;
    const double x = o.lane_width * (static_cast<double>(i) + 0.5);
    e.pose = {x, 0.5 * length, M_PI / 2};
    w.metadata["lane." + std::to_string(i)] = TerrainSpec::kind_name(o.lanes[i]);
    w.metadata["lane." + std::to_string(i) + ".start_line_y"] = message_number(0.5 * length - 0.5 * e.length);
    w.metadata["lane." + std::to_string(i) + ".end_line_y"] = message_number(0.5 * length + 0.5 * e.length);
    w.terrain.push_back(std::move(e));
  }
  w.metadata["lane_width"] = message_number(o.lane_width);
  if (o.figure_eight) w.metadata["pattern"] = "figure-eight";
  RobotPlacement start;
  start.name = "robot";
  start.start = {o.lane_width * (o.start_lane + 0.5), 0.5 * o.approach, M_PI / 2};
  w.robots.push_back(start);
  return w;
}

}  // namespace rescuesim
