/// From a maze grid to a WorldSpec: merged walls, raised platforms with ramps, victims against
/// walls, rubble near walls, the robot start, lights and the options as metadata. Everything a
/// cell holds stays inside the cell's interior square (the area between its wall faces), so
/// features of different cells can never touch each other or a wall.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "import/maze/maze.h"
#include "import/maze/maze_limits.h"

namespace rescuesim {

namespace {

using maze_limits::kTerrainClearance;

using maze_limits::kMinPlatform;

/// Gap between a platform and a closed wall face (m).
constexpr double kPlatformClearance = 0.02;
/// Victim body: width, longest length and gap to the wall it lies against (m).
constexpr double kVictimWidth = 0.40;
constexpr double kVictimMaxLength = 1.20;
constexpr double kVictimGap = 0.05;
/// Rubble: size ranges (m), density (kg/m^3), distance of its centre from a wall face (m),
/// clearance from faces and other pieces (m), and attempts per piece before giving up.
constexpr double kRubbleSideMin = 0.10, kRubbleSideMax = 0.30;
constexpr double kRubbleHeightMin = 0.08, kRubbleHeightMax = 0.25;
constexpr double kRubbleDensity = 400.0;
constexpr double kRubbleNearMin = 0.05, kRubbleNearMax = 0.25;
constexpr double kRubbleClearance = 0.005;
constexpr int kRubbleAttempts = 8;
/// Height of the point lights above the floor (m).
constexpr double kLightHeight = 2.5;

constexpr Side kSides[4] = {Side::east, Side::north, Side::west, Side::south};

/// Shortest text that reads back as the same double; locale-independent, so identical everywhere.
std::string text(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string short_num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

[[noreturn]] void bad(const std::string& element, const std::string& message) {
  throw Error(SourceRef{"", 0, element}, message);
}

/// The area between a cell's wall faces.
struct Interior {
  double x0, y0, x1, y1;
  double cx() const { return 0.5 * (x0 + x1); }
  double cy() const { return 0.5 * (y0 + y1); }
};

Interior interior(const MazeOptions& o, int c, int r) {
  const double h = 0.5 * o.wall_thickness;
  return {c * o.cell_size + h, r * o.cell_size + h, (c + 1) * o.cell_size - h, (r + 1) * o.cell_size - h};
}

/// Refuses a Maze whose grid does not match its options (one built by hand, say).
void check_maze(const Maze& m) {
  const MazeOptions& o = m.options;
  if (o.cols < 1 || o.rows < 1 || m.open_east.size() != static_cast<std::size_t>(m.cell_count()) ||
      m.open_north.size() != static_cast<std::size_t>(m.cell_count())) {
    bad("maze", "passage flags do not match the " + std::to_string(o.cols) + " x " + std::to_string(o.rows) + " grid");
  }
  if (!std::isfinite(o.cell_size) || !(o.wall_thickness > 0) || !(o.cell_size > 2 * o.wall_thickness)) {
    bad("maze option cell_size", "cell_size = " + short_num(o.cell_size) + " m, expected more than twice wall_thickness (" +
                                     short_num(o.wall_thickness) + " m)");
  }
  if (m.victim_cells.size() != m.victim_sides.size()) bad("maze", "victim cells and victim sides differ in number");
  const auto check_cell = [&](const std::array<int, 2>& c, const char* what) {
    if (c[0] < 0 || c[0] >= o.cols || c[1] < 0 || c[1] >= o.rows) {
      bad("maze", std::string(what) + " (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ") lies outside the grid");
    }
  };
  check_cell(o.start_cell, "start cell");
  for (const auto& c : o.more_start_cells) check_cell(c, "start cell");
  for (const auto& c : m.victim_cells) check_cell(c, "victim cell");
  for (const auto& c : m.raised_cells) check_cell(c, "raised cell");
  for (const auto& c : m.terrain_cells) check_cell(c, "terrain cell");
  if (!m.terrain_cells.empty() && o.terrain.empty()) bad("maze", "terrain cells without terrain kinds");
}

/// Walls: the closed cell sides along each grid line, merged into runs; each run reaches
/// half a thickness past its end points so walls overlap at corners and T-junctions.
void add_walls(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  const double s = o.cell_size, h = 0.5 * o.wall_thickness;
  const auto add = [&](Vec2 a, Vec2 b) {
    WallSpec wall;
    wall.a = a;
    wall.b = b;
    wall.thickness = o.wall_thickness;
    wall.height = o.wall_height;
    wall.material = "wall";
    wall.source = SourceRef{"", 0, "maze wall " + std::to_string(w.walls.size())};
    w.walls.push_back(wall);
  };
  // horizontal lines y = r * s: the side between cells (c, r - 1) and (c, r)
  for (int r = 0; r <= o.rows; ++r) {
    const auto closed = [&](int c) { return r == 0 || r == o.rows || !m.is_open(c, r - 1, Side::north); };
    for (int c = 0; c < o.cols;) {
      if (!closed(c)) {
        ++c;
        continue;
      }
      const int first = c;
      while (c < o.cols && closed(c)) ++c;
      add({first * s - h, r * s}, {c * s + h, r * s});
    }
  }
  // vertical lines x = c * s: the side between cells (c - 1, r) and (c, r)
  for (int c = 0; c <= o.cols; ++c) {
    const auto closed = [&](int r) { return c == 0 || c == o.cols || !m.is_open(c - 1, r, Side::east); };
    for (int r = 0; r < o.rows;) {
      if (!closed(r)) {
        ++r;
        continue;
      }
      const int first = r;
      while (r < o.rows && closed(r)) ++r;
      add({c * s, first * s - h}, {c * s, r * s + h});
    }
  }
}

/// Terrain cells: an element of the kinds in MazeOptions::terrain, taken in turn, across the
/// cell's interior less a clearance from the walls, its direction of travel along a passage of
/// the cell (east-west when it opens that way, else north-south); a stepfield's seed follows
/// the maze's and the cell's.
void add_terrain(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  for (std::size_t k = 0; k < m.terrain_cells.size(); ++k) {
    const int c = m.terrain_cells[k][0], r = m.terrain_cells[k][1];
    const Interior in = interior(o, c, r);
    const TerrainSpec::Kind kind = o.terrain[k % o.terrain.size()];
    TerrainSpec t = TerrainSpec::defaults(kind);
    t.name = "terrain_" + std::to_string(c) + "_" + std::to_string(r);
    const bool east_west = m.is_open(c, r, Side::east) || m.is_open(c, r, Side::west);
    t.pose = {0.5 * (in.x0 + in.x1), 0.5 * (in.y0 + in.y1), east_west ? 0.0 : M_PI / 2};
    t.length = std::min(in.x1 - in.x0, in.y1 - in.y0) - 2 * kTerrainClearance;
    t.width = t.length;
    t.seed = o.seed * 1000003ULL + static_cast<std::uint64_t>(m.index(c, r));
    t.source = SourceRef{"", 0, "maze terrain " + std::to_string(k)};
    w.terrain.push_back(t);
  }
}

/// Raised cells: a platform inset by ramp_length from each open side (where its ramp goes)
/// and by a small clearance from each closed side; outline counter-clockwise from south-west,
/// so edge 0 faces south, 1 east, 2 north, 3 west.
void add_raised(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  for (const auto& cell : m.raised_cells) {
    const int c = cell[0], r = cell[1];
    const Interior in = interior(o, c, r);
    const auto inset = [&](Side s) { return m.is_open(c, r, s) ? o.ramp_length : kPlatformClearance; };
    const double x0 = in.x0 + inset(Side::west), x1 = in.x1 - inset(Side::east);
    const double y0 = in.y0 + inset(Side::south), y1 = in.y1 - inset(Side::north);
    if (x1 - x0 < kMinPlatform || y1 - y0 < kMinPlatform) {
      bad("maze option raised_fraction", "cell (" + std::to_string(c) + ", " + std::to_string(r) +
                                             ") is too small for a raised platform: cell_size " + short_num(o.cell_size) +
                                             " m leaves less than " + short_num(kMinPlatform) + " m between ramps of ramp_length " +
                                             short_num(o.ramp_length) + " m");
    }
    RaisedAreaSpec area;
    area.outline = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    area.height = o.raised_height;
    area.ramp_length = o.ramp_length;
    const Side by_edge[4] = {Side::south, Side::east, Side::north, Side::west};
    for (int e = 0; e < 4; ++e) {
      if (m.is_open(c, r, by_edge[e])) area.ramp_edges.push_back(e);
    }
    area.material = "raised";
    area.source = SourceRef{"", 0, "maze raised area " + std::to_string(w.raised_areas.size())};
    w.raised_areas.push_back(area);
  }
}

/// Victims: lying along the closed side the maze chose, a little off its inner face, centred
/// along it; which way the head points is a coin toss.
void add_victims(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  Rng rng(o.seed, "maze/victims/heading");
  const double inner = o.cell_size - o.wall_thickness;
  const double length = std::min(kVictimMaxLength, 0.8 * inner);
  const double off = kVictimGap + 0.5 * kVictimWidth;
  for (std::size_t k = 0; k < m.victim_cells.size(); ++k) {
    const int c = m.victim_cells[k][0], r = m.victim_cells[k][1];
    const Side side = m.victim_sides[k];
    if (inner < kVictimGap + kVictimWidth) {
      bad("maze option victims", "a victim needs a cell interior of " + short_num(kVictimGap + kVictimWidth) + " m, but cell_size " +
                                     short_num(o.cell_size) + " m gives " + short_num(inner) + " m");
    }
    if (m.is_open(c, r, side)) {
      bad("maze", "victim " + std::to_string(k + 1) + " lies against an open side of cell (" + std::to_string(c) + ", " +
                      std::to_string(r) + ")");
    }
    const Interior in = interior(o, c, r);
    VictimSpec v;
    v.name = "victim_" + std::to_string(k + 1);
    v.posture = VictimSpec::Posture::lying;
    v.length = length;
    v.width = kVictimWidth;
    const bool vertical = side == Side::east || side == Side::west;
    v.pose.x = side == Side::east ? in.x1 - off : side == Side::west ? in.x0 + off : in.cx();
    v.pose.y = side == Side::north ? in.y1 - off : side == Side::south ? in.y0 + off : in.cy();
    v.pose.yaw = wrap_angle((vertical ? M_PI / 2 : 0.0) + (rng.below(2) ? M_PI : 0.0));
    v.source = SourceRef{"", 0, v.name};
    w.victims.push_back(v);
  }
}

/// Half extents along x and y of a rectangle of the given size turned by yaw.
Vec2 half_extents(double sx, double sy, double yaw) {
  const double c = std::abs(std::cos(yaw)), s = std::abs(std::sin(yaw));
  return {0.5 * (c * sx + s * sy), 0.5 * (s * sx + c * sy)};
}

/// Uniform in [lo, hi], or NaN when the range is empty.
double draw(Rng& rng, double lo, double hi) { return lo <= hi ? rng.uniform(lo, hi) : std::nan(""); }

/// Rubble: loose boxes and cylinders near a wall of a random free cell (not the start, a
/// victim's or a raised cell), or near a corner of a cell without walls. A piece that does not
/// fit after a few fresh draws is skipped. Returns how many pieces were placed.
int add_rubble(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  if (o.rubble <= 0) return 0;
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(m.cell_count()), 0);
  taken[static_cast<std::size_t>(m.index(o.start_cell[0], o.start_cell[1]))] = 1;
  for (const auto& c : o.more_start_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  for (const auto& c : m.victim_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  for (const auto& c : m.raised_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  for (const auto& c : m.terrain_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  std::vector<int> free_cells;
  for (int i = 0; i < m.cell_count(); ++i) {
    if (!taken[static_cast<std::size_t>(i)]) free_cells.push_back(i);
  }
  if (free_cells.empty()) return 0;

  Rng rng(o.seed, "maze/rubble");
  // footprints already placed, per cell: pieces never leave their cell
  std::vector<std::vector<Polygon2>> placed(static_cast<std::size_t>(m.cell_count()));
  int count = 0;
  for (int k = 0; k < o.rubble; ++k) {
    for (int attempt = 0; attempt < kRubbleAttempts; ++attempt) {
      const int i = free_cells[rng.below(static_cast<std::uint32_t>(free_cells.size()))];
      const int c = i % o.cols, r = i / o.cols;
      const Interior in = interior(o, c, r);
      // shape, size and heading
      RubbleSpec piece;
      piece.shape = rng.uniform() < 0.6 ? RubbleSpec::Shape::box : RubbleSpec::Shape::cylinder;
      const double sx = rng.uniform(kRubbleSideMin, kRubbleSideMax);
      const double sy = piece.shape == RubbleSpec::Shape::box ? rng.uniform(kRubbleSideMin, kRubbleSideMax) : sx;
      const double sz = rng.uniform(kRubbleHeightMin, kRubbleHeightMax);
      const double yaw = rng.uniform(-M_PI, M_PI);
      // the footprint used for fitting is the turned rectangle (a cylinder's square, to be safe)
      const Vec2 he = half_extents(sx, sy, yaw);
      const double g = kRubbleClearance;
      Side closed[4];
      std::uint32_t n_closed = 0;
      for (Side s : kSides) {
        if (!m.is_open(c, r, s)) closed[n_closed++] = s;
      }
      double x = 0, y = 0;
      if (n_closed > 0) {
        // centre 0.05..0.25 m off the wall face, anywhere along it that keeps the piece inside
        const Side s = closed[rng.below(n_closed)];
        const bool vertical = s == Side::east || s == Side::west;
        const double hn = vertical ? he.x() : he.y(), ha = vertical ? he.y() : he.x();
        const double d = draw(rng, std::max(kRubbleNearMin, hn + g), kRubbleNearMax);
        const double a = vertical ? draw(rng, in.y0 + ha + g, in.y1 - ha - g) : draw(rng, in.x0 + ha + g, in.x1 - ha - g);
        switch (s) {
          case Side::east: x = in.x1 - d, y = a; break;
          case Side::west: x = in.x0 + d, y = a; break;
          case Side::north: x = a, y = in.y1 - d; break;
          case Side::south: x = a, y = in.y0 + d; break;
        }
      } else {
        // no walls at all: near a random corner instead
        const std::uint32_t corner = rng.below(4);
        const double dx = draw(rng, std::max(kRubbleNearMin, he.x() + g), kRubbleNearMax);
        const double dy = draw(rng, std::max(kRubbleNearMin, he.y() + g), kRubbleNearMax);
        x = (corner & 1u) ? in.x1 - dx : in.x0 + dx;
        y = (corner & 2u) ? in.y1 - dy : in.y0 + dy;
      }
      // it must lie inside the interior (so off every wall) and clear of the cell's other pieces
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      if (x - he.x() < in.x0 + g || x + he.x() > in.x1 - g || y - he.y() < in.y0 + g || y + he.y() > in.y1 - g) continue;
      piece.pose = {x, y, yaw};
      const Polygon2 footprint = rectangle(piece.pose, sx + 2 * g, sy + 2 * g);
      auto& here = placed[static_cast<std::size_t>(i)];
      if (std::any_of(here.begin(), here.end(), [&](const Polygon2& p) { return polygons_overlap(p, footprint); })) continue;
      here.push_back(footprint);
      piece.size = {sx, sy, sz};
      const double volume = piece.shape == RubbleSpec::Shape::box ? sx * sy * sz : M_PI * 0.25 * sx * sx * sz;
      piece.mass = volume * kRubbleDensity;
      piece.material = "rubble";
      piece.source = SourceRef{"", 0, "maze rubble " + std::to_string(w.rubble.size())};
      w.rubble.push_back(piece);
      ++count;
      break;
    }
  }
  return count;
}

/// A robot at each start cell's centre ("robot" at start_cell, then "robot2", ...), facing its
/// cell's first open side (east, north, west, south).
void add_robots(WorldSpec& w, const Maze& m) {
  const MazeOptions& o = m.options;
  std::vector<std::array<int, 2>> cells{o.start_cell};
  cells.insert(cells.end(), o.more_start_cells.begin(), o.more_start_cells.end());
  const double yaw_of[4] = {0, M_PI / 2, M_PI, -M_PI / 2};
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const int c = cells[i][0], r = cells[i][1];
    double yaw = 0;
    for (int k = 0; k < 4; ++k) {
      if (m.is_open(c, r, kSides[k])) {
        yaw = yaw_of[k];
        break;
      }
    }
    RobotPlacement robot;
    robot.name = "robot";
    if (i > 0) robot.name += std::to_string(i + 1);
    robot.model = "rescue_robot";
    robot.start = {(c + 0.5) * o.cell_size, (r + 0.5) * o.cell_size, yaw};
    robot.source = SourceRef{"", 0, "maze start"};
    if (i > 0) robot.source.element += " " + std::to_string(i + 1);
    w.robots.push_back(robot);
  }
}

/// One sun-like directional light and two point lights over the maze's diagonal.
void add_lights(WorldSpec& w) {
  w.lights.push_back(LightSpec{});
  for (double f : {1.0 / 3.0, 2.0 / 3.0}) {
    LightSpec p;
    p.type = LightSpec::Type::point;
    p.position = {f * w.floor_max.x(), f * w.floor_max.y(), kLightHeight};
    w.lights.push_back(p);
  }
}

}  // namespace

WorldSpec maze_to_world(const Maze& maze) {
  check_maze(maze);
  const MazeOptions& o = maze.options;
  WorldSpec w;
  w.name = "maze-" + std::to_string(o.seed);
  w.seed = o.seed;
  w.floor_min = Vec2::Zero();
  w.floor_max = {o.cols * o.cell_size, o.rows * o.cell_size};
  w.materials = default_materials();
  add_walls(w, maze);
  add_raised(w, maze);
  add_terrain(w, maze);
  add_victims(w, maze);
  const int rubble_placed = add_rubble(w, maze);
  add_robots(w, maze);
  add_lights(w);

  // every option, as text that reads back exactly
  auto& md = w.metadata;
  md["generator"] = "rescuesim maze (modified Prim)";
  md["cols"] = std::to_string(o.cols);
  md["rows"] = std::to_string(o.rows);
  md["cell_size"] = text(o.cell_size);
  md["wall_thickness"] = text(o.wall_thickness);
  md["wall_height"] = text(o.wall_height);
  md["loop_fraction"] = text(o.loop_fraction);
  md["rubble"] = std::to_string(o.rubble);
  md["rubble_placed"] = std::to_string(rubble_placed);
  md["raised_fraction"] = text(o.raised_fraction);
  md["raised_height"] = text(o.raised_height);
  md["ramp_length"] = text(o.ramp_length);
  md["victims"] = std::to_string(o.victims);
  if (o.terrain_fraction > 0) {
    md["terrain_fraction"] = text(o.terrain_fraction);
    std::string kinds;
    for (TerrainSpec::Kind kind : o.terrain) kinds += (kinds.empty() ? "" : ",") + std::string(TerrainSpec::kind_name(kind));
    md["terrain"] = kinds;
  }
  md["start_cell"] = std::to_string(o.start_cell[0]) + "," + std::to_string(o.start_cell[1]);
  if (!o.more_start_cells.empty()) {
    std::string more;
    for (const auto& c : o.more_start_cells) more += (more.empty() ? "" : " ") + std::to_string(c[0]) + "," + std::to_string(c[1]);
    md["more_start_cells"] = more;
  }
  md["seed"] = std::to_string(o.seed);
  return w;
}

}  // namespace rescuesim
