#include "import/maze/maze.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/polygon.h"
#include "world/world_spec.h"

namespace rescuesim {
namespace {

constexpr Side kSides[4] = {Side::east, Side::north, Side::west, Side::south};

MazeOptions make(int cols, int rows, std::uint64_t seed, double loops = 0.0) {
  MazeOptions o;
  o.cols = cols;
  o.rows = rows;
  o.seed = seed;
  o.loop_fraction = loops;
  return o;
}

int interior_walls(const MazeOptions& o) { return (o.cols - 1) * o.rows + o.cols * (o.rows - 1); }

/// Openings counted straight from the flags, ignoring any set on the boundary.
int count_flags(const Maze& m) {
  int n = 0;
  for (int r = 0; r < m.options.rows; ++r) {
    for (int c = 0; c < m.options.cols; ++c) {
      const auto i = static_cast<std::size_t>(m.index(c, r));
      if (c + 1 < m.options.cols && m.open_east[i]) ++n;
      if (r + 1 < m.options.rows && m.open_north[i]) ++n;
    }
  }
  return n;
}

bool all_reachable(const Maze& m) {
  const auto seen = m.reachable_from(m.options.start_cell);
  for (auto f : seen) {
    if (!f) return false;
  }
  return true;
}

/// The square between a cell's wall faces, shrunk by `shrink`.
Polygon2 cell_interior(const MazeOptions& o, int c, int r, double shrink = 0) {
  const double h = 0.5 * o.wall_thickness + shrink;
  const double x0 = c * o.cell_size + h, y0 = r * o.cell_size + h;
  const double x1 = (c + 1) * o.cell_size - h, y1 = (r + 1) * o.cell_size - h;
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

bool inside_box(const Polygon2& poly, const Polygon2& box, double eps = 1e-9) {
  const Box2 b = bounds(box), p = bounds(poly);
  return p.min.x() >= b.min.x() - eps && p.min.y() >= b.min.y() - eps && p.max.x() <= b.max.x() + eps &&
         p.max.y() <= b.max.y() + eps;
}

/// The cell holding point p.
std::array<int, 2> cell_of(const MazeOptions& o, const Vec2& p) {
  return {static_cast<int>(std::floor(p.x() / o.cell_size)), static_cast<int>(std::floor(p.y() / o.cell_size))};
}

double total_wall_length(const WorldSpec& w) {
  double len = 0;
  for (const auto& wall : w.walls) len += (wall.b - wall.a).norm();
  return len;
}

/// Walls and victims of two worlds match exactly (bit for bit).
void expect_same_walls_and_victims(const WorldSpec& a, const WorldSpec& b) {
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_EQ(a.walls[i].a, b.walls[i].a);
    EXPECT_EQ(a.walls[i].b, b.walls[i].b);
    EXPECT_EQ(a.walls[i].source.element, b.walls[i].source.element);
  }
  ASSERT_EQ(a.victims.size(), b.victims.size());
  for (std::size_t i = 0; i < a.victims.size(); ++i) {
    EXPECT_EQ(a.victims[i].pose.x, b.victims[i].pose.x);
    EXPECT_EQ(a.victims[i].pose.y, b.victims[i].pose.y);
    EXPECT_EQ(a.victims[i].pose.yaw, b.victims[i].pose.yaw);
  }
}

// --- the grid --------------------------------------------------------------------------------

TEST(MazeGrid, PerfectMazeIsASpanningTree) {
  const std::array<int, 2> sizes[] = {{1, 1}, {1, 10}, {10, 1}, {7, 5}, {50, 50}};
  for (const auto& size : sizes) {
    for (std::uint64_t seed : {1ull, 2ull, 42ull, 987654321ull}) {
      MazeOptions o = make(size[0], size[1], seed);
      o.start_cell = {size[0] / 2, size[1] - 1};
      const Maze m = generate_maze(o);
      SCOPED_TRACE(std::to_string(size[0]) + "x" + std::to_string(size[1]) + " seed " + std::to_string(seed));
      EXPECT_EQ(m.opening_count(), m.cell_count() - 1);
      EXPECT_EQ(count_flags(m), m.cell_count() - 1);
      EXPECT_TRUE(all_reachable(m));
      // the outer boundary stays closed
      for (int c = 0; c < o.cols; ++c) {
        EXPECT_FALSE(m.is_open(c, 0, Side::south));
        EXPECT_FALSE(m.is_open(c, o.rows - 1, Side::north));
      }
      for (int r = 0; r < o.rows; ++r) {
        EXPECT_FALSE(m.is_open(0, r, Side::west));
        EXPECT_FALSE(m.is_open(o.cols - 1, r, Side::east));
      }
    }
  }
}

TEST(MazeGrid, DegreeAndOpenAgree) {
  const Maze m = generate_maze(make(6, 4, 3, 0.4));
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 6; ++c) {
      int d = 0;
      for (Side s : kSides) d += m.is_open(c, r, s) ? 1 : 0;
      EXPECT_EQ(m.degree(c, r), d);
      EXPECT_TRUE(c + 1 == 6 || m.is_open(c, r, Side::east) == m.is_open(c + 1, r, Side::west));
      EXPECT_TRUE(r + 1 == 4 || m.is_open(c, r, Side::north) == m.is_open(c, r + 1, Side::south));
    }
  }
}

TEST(MazeGrid, FullLoopFractionOpensEveryInteriorWall) {
  for (const auto& size : {std::array<int, 2>{1, 1}, {1, 6}, {5, 1}, {7, 5}, {20, 13}}) {
    const MazeOptions o = make(size[0], size[1], 5, 1.0);
    const Maze m = generate_maze(o);
    EXPECT_EQ(m.opening_count(), interior_walls(o));
  }
}

TEST(MazeGrid, QuarterLoopFractionOpensAQuarterOfTheRemainingWalls) {
  for (const auto& size : {std::array<int, 2>{7, 5}, {10, 10}, {3, 17}, {31, 29}}) {
    for (std::uint64_t seed : {1ull, 9ull}) {
      const MazeOptions o = make(size[0], size[1], seed, 0.25);
      const Maze m = generate_maze(o);
      const int cells = o.cols * o.rows;
      const auto extra = std::lround(0.25 * (interior_walls(o) - (cells - 1)));
      EXPECT_EQ(m.opening_count(), cells - 1 + extra);
      EXPECT_TRUE(all_reachable(m));
    }
  }
}

TEST(MazeGrid, SameSeedSameMazeDifferentSeedDifferentMaze) {
  MazeOptions o = make(12, 9, 77, 0.2);
  o.victims = 5;
  o.raised_fraction = 0.1;
  const Maze a = generate_maze(o), b = generate_maze(o);
  EXPECT_EQ(a.open_east, b.open_east);
  EXPECT_EQ(a.open_north, b.open_north);
  EXPECT_EQ(a.victim_cells, b.victim_cells);
  EXPECT_EQ(a.victim_sides, b.victim_sides);
  EXPECT_EQ(a.raised_cells, b.raised_cells);
  // ten seeds, ten different mazes
  std::vector<std::vector<std::uint8_t>> seen;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    o.seed = seed;
    const Maze m = generate_maze(o);
    std::vector<std::uint8_t> flags = m.open_east;
    flags.insert(flags.end(), m.open_north.begin(), m.open_north.end());
    for (const auto& other : seen) EXPECT_NE(flags, other) << "seed " << seed;
    seen.push_back(flags);
  }
}

TEST(MazeGrid, FeaturesDoNotMoveTheWalls) {
  MazeOptions o = make(10, 8, 31, 0.15);
  const Maze plain = generate_maze(o);
  o.victims = 6;
  o.raised_fraction = 0.2;
  o.rubble = 25;
  const Maze featured = generate_maze(o);
  EXPECT_EQ(plain.open_east, featured.open_east);
  EXPECT_EQ(plain.open_north, featured.open_north);
}

// --- victims and raised cells ----------------------------------------------------------------

TEST(MazeVictims, DeadEndsArePreferred) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    MazeOptions o = make(10, 10, seed);
    o.victims = 4;
    const Maze m = generate_maze(o);
    ASSERT_EQ(m.victim_cells.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      const auto c = m.victim_cells[k];
      EXPECT_EQ(m.degree(c[0], c[1]), 1) << "seed " << seed;
      // against the wall opposite the way in
      const int opposite = (static_cast<int>(m.victim_sides[k]) + 2) % 4;
      EXPECT_TRUE(m.is_open(c[0], c[1], static_cast<Side>(opposite)));
    }
  }
}

TEST(MazeVictims, ReachableNeverAtStartOrRaisedOnePerCell) {
  struct Case {
    int cols, rows;
    double loops, raised;
    int victims;
  };
  const Case cases[] = {{10, 10, 0.0, 0.0, 12}, {8, 8, 0.3, 0.2, 20}, {5, 4, 1.0, 0.0, 10}, {15, 3, 0.1, 0.3, 20}};
  for (const auto& k : cases) {
    MazeOptions o = make(k.cols, k.rows, 11, k.loops);
    o.raised_fraction = k.raised;
    o.victims = k.victims;
    o.start_cell = {1, 1};
    const Maze m = generate_maze(o);
    ASSERT_EQ(m.victim_cells.size(), static_cast<std::size_t>(k.victims));
    ASSERT_EQ(m.victim_sides.size(), m.victim_cells.size());
    const auto seen = m.reachable_from(o.start_cell);
    std::vector<int> per_cell(static_cast<std::size_t>(m.cell_count()), 0);
    for (std::size_t v = 0; v < m.victim_cells.size(); ++v) {
      const auto c = m.victim_cells[v];
      EXPECT_TRUE(seen[static_cast<std::size_t>(m.index(c[0], c[1]))]);
      EXPECT_NE(c, o.start_cell);
      EXPECT_FALSE(m.is_open(c[0], c[1], m.victim_sides[v]));
      EXPECT_EQ(++per_cell[static_cast<std::size_t>(m.index(c[0], c[1]))], 1);
      for (const auto& rc : m.raised_cells) EXPECT_NE(rc, c);
    }
  }
}

TEST(MazeVictims, TooManyVictimsNamesTheOptionAndTheRoom) {
  // with every interior wall open only the 12 boundary cells have a closed side; one is the start
  MazeOptions o = make(4, 4, 3, 1.0);
  o.victims = 11;
  EXPECT_EQ(generate_maze(o).victim_cells.size(), 11u);
  o.victims = 12;
  try {
    generate_maze(o);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("victims"), std::string::npos) << what;
    EXPECT_NE(what.find("12 requested, but only 11 cells can hold one"), std::string::npos) << what;
  }
}

TEST(MazeRaised, CountAndNeverTheStartCell) {
  for (double f : {0.0, 0.1, 0.5, 1.0}) {
    MazeOptions o = make(6, 5, 4, 0.2);
    o.raised_fraction = f;
    o.start_cell = {2, 3};
    const Maze m = generate_maze(o);
    const long want = std::min<long>(std::lround(f * 30), 29);
    EXPECT_EQ(static_cast<long>(m.raised_cells.size()), want);
    for (const auto& c : m.raised_cells) EXPECT_NE(c, o.start_cell);
  }
}

// --- the world -------------------------------------------------------------------------------

TEST(MazeWorld, WallsCoverExactlyTheClosedSides) {
  for (std::uint64_t seed : {1ull, 6ull}) {
    MazeOptions o = make(9, 7, seed, 0.2);
    o.cell_size = 1.2;
    o.wall_thickness = 0.08;
    const Maze m = generate_maze(o);
    const WorldSpec w = maze_to_world(m);
    // closed sides and the runs they form along each grid line
    int closed = 0, runs = 0;
    for (int r = 0; r <= o.rows; ++r) {
      const auto shut = [&](int c) { return r == 0 || r == o.rows || !m.is_open(c, r - 1, Side::north); };
      for (int c = 0; c < o.cols; ++c) {
        closed += shut(c) ? 1 : 0;
        runs += shut(c) && (c == 0 || !shut(c - 1)) ? 1 : 0;
      }
    }
    for (int c = 0; c <= o.cols; ++c) {
      const auto shut = [&](int r) { return c == 0 || c == o.cols || !m.is_open(c - 1, r, Side::east); };
      for (int r = 0; r < o.rows; ++r) {
        closed += shut(r) ? 1 : 0;
        runs += shut(r) && (r == 0 || !shut(r - 1)) ? 1 : 0;
      }
    }
    EXPECT_EQ(closed, 2 * o.cols + 2 * o.rows + interior_walls(o) - m.opening_count());
    EXPECT_EQ(static_cast<int>(w.walls.size()), runs);
    // each run is extended by half a thickness at both ends
    EXPECT_NEAR(total_wall_length(w), closed * o.cell_size + runs * o.wall_thickness, 1e-9);
    for (const auto& wall : w.walls) {
      EXPECT_EQ(wall.material, "wall");
      EXPECT_DOUBLE_EQ(wall.height, o.wall_height);
      EXPECT_DOUBLE_EQ(wall.thickness, o.wall_thickness);
      EXPECT_TRUE(wall.a.x() == wall.b.x() || wall.a.y() == wall.b.y()) << "walls are axis-aligned";
    }
    const auto inside_some_wall = [&](const Vec2& p) {
      for (const auto& wall : w.walls) {
        if (contains(WorldSpec::wall_outline(wall), p, 1e-9)) return true;
      }
      return false;
    };
    for (int r = 0; r < o.rows; ++r) {
      for (int c = 0; c < o.cols; ++c) {
        // no wall reaches into a cell's interior
        const Polygon2 in = cell_interior(o, c, r, 1e-6);
        for (const auto& wall : w.walls) EXPECT_FALSE(polygons_overlap(WorldSpec::wall_outline(wall), in));
        // closed sides are walled, open sides are passable at their middle
        const Vec2 mid_e((c + 1) * o.cell_size, (r + 0.5) * o.cell_size);
        const Vec2 mid_n((c + 0.5) * o.cell_size, (r + 1) * o.cell_size);
        EXPECT_EQ(inside_some_wall(mid_e), !m.is_open(c, r, Side::east));
        EXPECT_EQ(inside_some_wall(mid_n), !m.is_open(c, r, Side::north));
        EXPECT_TRUE(c > 0 || inside_some_wall({0, (r + 0.5) * o.cell_size}));
        EXPECT_TRUE(r > 0 || inside_some_wall({(c + 0.5) * o.cell_size, 0}));
      }
    }
    // every grid corner a wall touches is filled all round: no gaps at corners or T-junctions
    const auto h_closed = [&](int c, int r) {
      return c >= 0 && c < o.cols && (r == 0 || r == o.rows || !m.is_open(c, r - 1, Side::north));
    };
    const auto v_closed = [&](int c, int r) {
      return r >= 0 && r < o.rows && (c == 0 || c == o.cols || !m.is_open(c - 1, r, Side::east));
    };
    const double q = 0.49 * o.wall_thickness;
    for (int r = 0; r <= o.rows; ++r) {
      for (int c = 0; c <= o.cols; ++c) {
        if (!h_closed(c - 1, r) && !h_closed(c, r) && !v_closed(c, r - 1) && !v_closed(c, r)) continue;
        const Vec2 corner(c * o.cell_size, r * o.cell_size);
        for (const Vec2& d : {Vec2(q, q), Vec2(-q, q), Vec2(q, -q), Vec2(-q, -q)}) {
          EXPECT_TRUE(inside_some_wall(corner + d)) << "gap at grid corner " << c << "," << r;
        }
      }
    }
  }
}

TEST(MazeWorld, VictimsLieAgainstTheirWall) {
  MazeOptions o = make(10, 10, 8, 0.1);
  o.victims = 15;
  const Maze m = generate_maze(o);
  const WorldSpec w = maze_to_world(m);
  ASSERT_EQ(w.victims.size(), 15u);
  const double inner = o.cell_size - o.wall_thickness;
  for (std::size_t k = 0; k < w.victims.size(); ++k) {
    const auto& v = w.victims[k];
    EXPECT_EQ(v.name, "victim_" + std::to_string(k + 1));
    EXPECT_EQ(v.posture, VictimSpec::Posture::lying);
    EXPECT_DOUBLE_EQ(v.length, std::min(1.2, 0.8 * inner));
    EXPECT_DOUBLE_EQ(v.width, 0.4);
    EXPECT_DOUBLE_EQ(v.skin_temperature, VictimSpec{}.skin_temperature);
    EXPECT_DOUBLE_EQ(v.clothes_temperature, VictimSpec{}.clothes_temperature);
    const auto c = m.victim_cells[k];
    EXPECT_EQ(cell_of(o, v.pose.position()), c);
    const Polygon2 in = cell_interior(o, c[0], c[1]);
    const Box2 b = bounds(in);
    EXPECT_TRUE(inside_box(WorldSpec::victim_outline(v), in));
    const double off = 0.05 + 0.2;
    const Vec2 dir(std::cos(v.pose.yaw), std::sin(v.pose.yaw));
    switch (m.victim_sides[k]) {
      case Side::east: EXPECT_NEAR(b.max.x() - v.pose.x, off, 1e-9); EXPECT_NEAR(std::abs(dir.y()), 1, 1e-9); break;
      case Side::west: EXPECT_NEAR(v.pose.x - b.min.x(), off, 1e-9); EXPECT_NEAR(std::abs(dir.y()), 1, 1e-9); break;
      case Side::north: EXPECT_NEAR(b.max.y() - v.pose.y, off, 1e-9); EXPECT_NEAR(std::abs(dir.x()), 1, 1e-9); break;
      case Side::south: EXPECT_NEAR(v.pose.y - b.min.y(), off, 1e-9); EXPECT_NEAR(std::abs(dir.x()), 1, 1e-9); break;
    }
  }
}

TEST(MazeWorld, VictimsAndRubbleAvoidWallsAndEachOther) {
  for (std::uint64_t seed : {2ull, 3ull, 5ull}) {
    MazeOptions o = make(8, 6, seed, 0.2);
    o.victims = 6;
    o.rubble = 60;
    o.raised_fraction = 0.1;
    const Maze m = generate_maze(o);
    const WorldSpec w = maze_to_world(m);
    EXPECT_EQ(w.metadata.at("rubble_placed"), std::to_string(w.rubble.size()));
    EXPECT_GT(w.rubble.size(), 40u);
    std::vector<Polygon2> walls;
    for (const auto& wall : w.walls) walls.push_back(WorldSpec::wall_outline(wall));
    std::vector<Polygon2> things;
    for (const auto& v : w.victims) things.push_back(WorldSpec::victim_outline(v));
    for (const auto& r : w.rubble) things.push_back(rectangle(r.pose, r.size.x(), r.size.y()));
    for (std::size_t i = 0; i < things.size(); ++i) {
      for (const auto& wall : walls) EXPECT_FALSE(polygons_overlap(things[i], wall)) << "item " << i;
      for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(polygons_overlap(things[i], things[j])) << i << " and " << j;
    }
  }
}

TEST(MazeWorld, RubbleSizesPlacesAndSkips) {
  MazeOptions o = make(7, 7, 12, 0.3);
  o.rubble = 80;
  o.victims = 3;
  o.raised_fraction = 0.15;
  const Maze m = generate_maze(o);
  const WorldSpec w = maze_to_world(m);
  int boxes = 0;
  for (const auto& r : w.rubble) {
    const auto c = cell_of(o, r.pose.position());
    EXPECT_NE(c, o.start_cell);
    for (const auto& v : m.victim_cells) EXPECT_NE(c, v);
    for (const auto& rc : m.raised_cells) EXPECT_NE(c, rc);
    EXPECT_TRUE(r.size.x() >= 0.10 && r.size.x() <= 0.30 && r.size.y() >= 0.10 && r.size.y() <= 0.30) << r.size.transpose();
    EXPECT_TRUE(r.size.z() >= 0.08 && r.size.z() <= 0.25) << r.size.z();
    const bool box = r.shape == RubbleSpec::Shape::box;
    boxes += box ? 1 : 0;
    EXPECT_TRUE(box || r.size.x() == r.size.y());
    const double volume = box ? r.size.x() * r.size.y() * r.size.z() : M_PI * 0.25 * r.size.x() * r.size.x() * r.size.z();
    EXPECT_NEAR(r.mass, 400 * volume, 1e-9);
    EXPECT_EQ(r.material, "rubble");
    // centre 0.05..0.25 m from a closed side's face (or from two faces near a corner)
    const Box2 b = bounds(cell_interior(o, c[0], c[1]));
    const double dist[4] = {b.max.x() - r.pose.x, b.max.y() - r.pose.y, r.pose.x - b.min.x(), r.pose.y - b.min.y()};
    bool near = false, any_closed = false;
    for (int s = 0; s < 4; ++s) {
      if (m.is_open(c[0], c[1], kSides[s])) continue;
      any_closed = true;
      near = near || (dist[s] >= 0.05 - 1e-9 && dist[s] <= 0.25 + 1e-9);
    }
    if (!any_closed) near = std::min(dist[0], dist[2]) <= 0.25 + 1e-9 && std::min(dist[1], dist[3]) <= 0.25 + 1e-9;
    EXPECT_TRUE(near) << "rubble at " << r.pose.x << ", " << r.pose.y;
  }
  // roughly 60 % boxes
  EXPECT_GT(boxes, static_cast<int>(w.rubble.size()) / 3);
  EXPECT_LT(boxes, static_cast<int>(w.rubble.size()) * 5 / 6);

  // tiny cells hold little: pieces that do not fit are skipped and the count says so
  MazeOptions tight = make(2, 2, 3);
  tight.cell_size = 0.5;
  tight.rubble = 200;
  const WorldSpec t = maze_to_world(generate_maze(tight));
  EXPECT_LT(t.rubble.size(), 200u);
  EXPECT_EQ(t.metadata.at("rubble_placed"), std::to_string(t.rubble.size()));
}

TEST(MazeWorld, RubbleCountChangesNeitherWallsNorVictims) {
  MazeOptions o = make(9, 9, 21, 0.2);
  o.victims = 5;
  o.raised_fraction = 0.1;
  const WorldSpec a = maze_to_world(generate_maze(o));
  o.rubble = 40;
  const WorldSpec b = maze_to_world(generate_maze(o));
  expect_same_walls_and_victims(a, b);
  ASSERT_EQ(a.raised_areas.size(), b.raised_areas.size());
  EXPECT_TRUE(a.rubble.empty());
  EXPECT_FALSE(b.rubble.empty());
}

TEST(MazeWorld, SameSeedSameWorld) {
  MazeOptions o = make(11, 7, 99, 0.3);
  o.victims = 4;
  o.rubble = 30;
  o.raised_fraction = 0.2;
  const WorldSpec a = maze_to_world(generate_maze(o)), b = maze_to_world(generate_maze(o));
  expect_same_walls_and_victims(a, b);
  ASSERT_EQ(a.rubble.size(), b.rubble.size());
  for (std::size_t i = 0; i < a.rubble.size(); ++i) {
    EXPECT_EQ(a.rubble[i].pose.x, b.rubble[i].pose.x);
    EXPECT_EQ(a.rubble[i].pose.yaw, b.rubble[i].pose.yaw);
    EXPECT_EQ(a.rubble[i].size, b.rubble[i].size);
  }
  EXPECT_EQ(a.metadata, b.metadata);
}

TEST(MazeWorld, RaisedAreasHaveRampsExactlyOnOpenSides) {
  MazeOptions o = make(8, 8, 17, 0.3);
  o.raised_fraction = 0.3;
  const Maze m = generate_maze(o);
  const WorldSpec w = maze_to_world(m);
  ASSERT_EQ(w.raised_areas.size(), m.raised_cells.size());
  ASSERT_EQ(w.raised_areas.size(), 19u);
  const Side by_edge[4] = {Side::south, Side::east, Side::north, Side::west};
  for (std::size_t k = 0; k < w.raised_areas.size(); ++k) {
    const auto& a = w.raised_areas[k];
    const auto c = m.raised_cells[k];
    ASSERT_EQ(a.outline.size(), 4u);
    EXPECT_GT(signed_area(a.outline), 0);
    EXPECT_DOUBLE_EQ(a.height, o.raised_height);
    EXPECT_DOUBLE_EQ(a.ramp_length, o.ramp_length);
    std::vector<int> want;
    for (int e = 0; e < 4; ++e) {
      if (m.is_open(c[0], c[1], by_edge[e])) want.push_back(e);
    }
    EXPECT_EQ(a.ramp_edges, want);
    // platform and ramps stay inside the cell; ramps end at the wall faces, closed sides keep a gap
    const Polygon2 in = cell_interior(o, c[0], c[1]);
    const Box2 ib = bounds(in), pb = bounds(a.outline);
    EXPECT_TRUE(inside_box(a.outline, in));
    for (int e : a.ramp_edges) EXPECT_TRUE(inside_box(WorldSpec::ramp_outline(a, e), in));
    const double gap[4] = {pb.min.y() - ib.min.y(), ib.max.x() - pb.max.x(), ib.max.y() - pb.max.y(), pb.min.x() - ib.min.x()};
    for (int e = 0; e < 4; ++e) {
      EXPECT_NEAR(gap[e], m.is_open(c[0], c[1], by_edge[e]) ? o.ramp_length : 0.02, 1e-9);
    }
  }
}

TEST(MazeWorld, RobotStartsAtTheStartCellCentreFacingAnOpenSide) {
  for (const auto& start : {std::array<int, 2>{0, 0}, {3, 2}, {6, 4}, {0, 4}}) {
    for (std::uint64_t seed : {1ull, 2ull, 3ull}) {
      MazeOptions o = make(7, 5, seed);
      o.start_cell = start;
      const Maze m = generate_maze(o);
      const WorldSpec w = maze_to_world(m);
      ASSERT_EQ(w.robots.size(), 1u);
      const auto& robot = w.robots[0];
      EXPECT_EQ(robot.name, "robot");
      EXPECT_EQ(robot.model, "rescue_robot");
      EXPECT_NEAR(robot.start.x, (start[0] + 0.5) * o.cell_size, 1e-12);
      EXPECT_NEAR(robot.start.y, (start[1] + 0.5) * o.cell_size, 1e-12);
      const Vec2 dir(std::cos(robot.start.yaw), std::sin(robot.start.yaw));
      const Vec2 normals[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
      int facing = -1, first_open = -1;
      for (int s = 0; s < 4; ++s) {
        if ((dir - normals[s]).norm() < 1e-9) facing = s;
        if (first_open < 0 && m.is_open(start[0], start[1], kSides[s])) first_open = s;
      }
      EXPECT_EQ(facing, first_open);
    }
  }
}

TEST(MazeWorld, MoreStartCellsGetARobotEachAndStayClear) {
  MazeOptions o = make(6, 6, 9, 0.2);
  o.victims = 8;
  o.raised_fraction = 0.3;
  o.rubble = 20;
  const WorldSpec one = maze_to_world(generate_maze(o));
  o.more_start_cells = {{5, 5}, {0, 5}};
  const Maze m = generate_maze(o);
  const WorldSpec w = maze_to_world(m);
  ASSERT_EQ(w.robots.size(), 3u);
  EXPECT_EQ(w.robots[0].name, "robot");
  EXPECT_EQ(w.robots[1].name, "robot2");
  EXPECT_EQ(w.robots[2].name, "robot3");
  EXPECT_NEAR(w.robots[1].start.x, 5.5 * o.cell_size, 1e-12);
  EXPECT_NEAR(w.robots[1].start.y, 5.5 * o.cell_size, 1e-12);
  EXPECT_NEAR(w.robots[2].start.x, 0.5 * o.cell_size, 1e-12);
  for (const auto& start : o.more_start_cells) {
    for (const auto& c : m.victim_cells) EXPECT_NE(c, start);
    for (const auto& c : m.raised_cells) EXPECT_NE(c, start);
  }
  // rubble keeps out of every start cell
  for (const auto& r : w.rubble) {
    const std::array<int, 2> cell{static_cast<int>(std::floor(r.pose.x / o.cell_size)),
                                  static_cast<int>(std::floor(r.pose.y / o.cell_size))};
    EXPECT_NE(cell, o.start_cell);
    for (const auto& start : o.more_start_cells) EXPECT_NE(cell, start);
  }
  // the walls do not depend on where the robots start
  EXPECT_EQ(w.walls.size(), one.walls.size());
  EXPECT_EQ(w.metadata.at("more_start_cells"), "5,5 0,5");
  EXPECT_EQ(one.metadata.count("more_start_cells"), 0u);

  MazeOptions same = o;
  same.more_start_cells = {{2, 2}, {2, 2}};
  EXPECT_THROW(generate_maze(same), Error);
  same.more_start_cells = {o.start_cell};
  EXPECT_THROW(generate_maze(same), Error);
  same.more_start_cells = {{6, 0}};
  EXPECT_THROW(generate_maze(same), Error);
}

TEST(MazeWorld, WorldValidatesWithoutErrors) {
  struct Case {
    int cols, rows;
    double cell, loops, raised;
    int victims, rubble;
    std::array<int, 2> start;
    std::uint64_t seed;
  };
  const Case cases[] = {
      {1, 1, 1.5, 0, 0, 0, 0, {0, 0}, 1},          {1, 10, 1.0, 0, 0.2, 3, 5, {0, 9}, 2},
      {10, 1, 1.2, 0.5, 0, 2, 10, {4, 0}, 3},      {7, 5, 1.5, 0.25, 0.1, 4, 20, {3, 2}, 4},
      {20, 20, 1.5, 0.1, 0.05, 10, 100, {0, 0}, 5}, {12, 9, 2.5, 1.0, 0.3, 8, 50, {11, 8}, 6},
  };
  for (const auto& k : cases) {
    MazeOptions o = make(k.cols, k.rows, k.seed, k.loops);
    o.cell_size = k.cell;
    o.raised_fraction = k.raised;
    o.victims = k.victims;
    o.rubble = k.rubble;
    o.start_cell = k.start;
    const WorldSpec w = maze_to_world(generate_maze(o));
    const Diagnostics d = validate(w);
    for (const auto& item : d.items()) {
      if (item.severity == Severity::error) ADD_FAILURE() << "seed " << k.seed << ": " << item.str();
    }
    EXPECT_EQ(w.name, "maze-" + std::to_string(k.seed));
    EXPECT_EQ(w.seed, k.seed);
    EXPECT_EQ(w.floor_min, Vec2(0, 0));
    EXPECT_NEAR(w.floor_max.x(), k.cols * k.cell, 1e-12);
    EXPECT_NEAR(w.floor_max.y(), k.rows * k.cell, 1e-12);
    EXPECT_NE(w.find_material("wall"), nullptr);
    ASSERT_EQ(w.lights.size(), 3u);
    EXPECT_EQ(w.lights[0].type, LightSpec::Type::directional);
    EXPECT_EQ(w.lights[1].type, LightSpec::Type::point);
    EXPECT_DOUBLE_EQ(w.lights[2].position.z(), 2.5);
  }
}

TEST(MazeWorld, MetadataRecordsEveryOption) {
  MazeOptions o = make(6, 4, 1234567890123ull, 0.1);
  o.cell_size = 1.25;
  o.rubble = 7;
  o.victims = 2;
  o.start_cell = {5, 3};
  const WorldSpec w = maze_to_world(generate_maze(o));
  const auto& md = w.metadata;
  EXPECT_EQ(md.at("generator"), "rescuesim maze (modified Prim)");
  EXPECT_EQ(md.at("cols"), "6");
  EXPECT_EQ(md.at("rows"), "4");
  EXPECT_EQ(md.at("cell_size"), "1.25");
  EXPECT_EQ(md.at("loop_fraction"), "0.1");
  EXPECT_EQ(md.at("rubble"), "7");
  EXPECT_EQ(md.at("raised_fraction"), "0");
  EXPECT_EQ(md.at("victims"), "2");
  EXPECT_EQ(md.at("start_cell"), "5,3");
  EXPECT_EQ(md.at("seed"), "1234567890123");
  EXPECT_EQ(md.at("wall_thickness"), "0.05");
  EXPECT_EQ(md.at("wall_height"), "1");
  EXPECT_EQ(md.at("raised_height"), "0.1");
  EXPECT_EQ(md.at("ramp_length"), "0.4");
  EXPECT_EQ(md.count("rubble_placed"), 1u);
}

// --- bad options -----------------------------------------------------------------------------

TEST(MazeOptionsCheck, BadOptionsNameTheOption) {
  struct Case {
    const char* option;
    std::function<void(MazeOptions&)> spoil;
  };
  const Case cases[] = {
      {"cols", [](MazeOptions& o) { o.cols = 0; }},
      {"cols", [](MazeOptions& o) { o.cols = 501; }},
      {"rows", [](MazeOptions& o) { o.rows = -3; }},
      {"cell_size", [](MazeOptions& o) { o.cell_size = 0.1; }},
      {"cell_size", [](MazeOptions& o) { o.cell_size = NAN; }},
      {"cell_size", [](MazeOptions& o) { o.cell_size = INFINITY; }},
      {"wall_thickness", [](MazeOptions& o) { o.wall_thickness = 0; }},
      {"wall_height", [](MazeOptions& o) { o.wall_height = -1; }},
      {"raised_height", [](MazeOptions& o) { o.raised_height = 0; }},
      {"ramp_length", [](MazeOptions& o) { o.ramp_length = NAN; }},
      {"loop_fraction", [](MazeOptions& o) { o.loop_fraction = -0.1; }},
      {"loop_fraction", [](MazeOptions& o) { o.loop_fraction = NAN; }},
      {"raised_fraction", [](MazeOptions& o) { o.raised_fraction = 1.5; }},
      {"rubble", [](MazeOptions& o) { o.rubble = -1; }},
      {"rubble", [](MazeOptions& o) { o.rubble = 10001; }},
      {"victims", [](MazeOptions& o) { o.victims = -2; }},
      {"victims", [](MazeOptions& o) { o.victims = 40; }},
      {"start_cell", [](MazeOptions& o) { o.start_cell = {8, 0}; }},
      {"start_cell", [](MazeOptions& o) { o.start_cell = {0, -1}; }},
      // geometry that cannot fit: ramps in small cells, victims in tiny cells
      {"raised_fraction", [](MazeOptions& o) { o.raised_fraction = 0.5; o.cell_size = 0.9; }},
      {"victims", [](MazeOptions& o) { o.victims = 1; o.cell_size = 0.4; }},
  };
  for (const auto& k : cases) {
    MazeOptions o = make(8, 4, 1);
    k.spoil(o);
    try {
      generate_maze(o);
      ADD_FAILURE() << "no error for a bad " << k.option;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string("maze option ") + k.option), std::string::npos) << what;
      EXPECT_EQ(e.where().element, std::string("maze option ") + k.option);
    }
  }
}

TEST(MazeTerrain, AFractionOfTheFreeCellsGetTerrainAndRubbleKeepsOutOfThem) {
  MazeOptions o;
  o.cols = 6;
  o.rows = 5;
  o.seed = 11;
  o.victims = 3;
  o.raised_fraction = 0.1;  // 3 cells
  o.rubble = 30;
  o.terrain_fraction = 0.2;  // round(0.2 x 30) = 6 cells
  o.terrain = {TerrainSpec::Kind::stepfield, TerrainSpec::Kind::curb, TerrainSpec::Kind::hurdle};
  const Maze m = generate_maze(o);
  ASSERT_EQ(m.terrain_cells.size(), 6u);
  for (const auto& c : m.terrain_cells) {
    EXPECT_NE(c, o.start_cell);
    for (const auto& v : m.victim_cells) EXPECT_NE(c, v);
    for (const auto& r : m.raised_cells) EXPECT_NE(c, r);
  }
  const WorldSpec w = maze_to_world(m);
  ASSERT_EQ(w.terrain.size(), 6u);
  // the kinds in turn, each across its cell's interior less 5 cm from each wall: 1.5 - 0.05 - 0.1
  for (std::size_t k = 0; k < w.terrain.size(); ++k) {
    const TerrainSpec& t = w.terrain[k];
    EXPECT_EQ(t.kind, o.terrain[k % 3]);
    EXPECT_NEAR(t.length, 1.35, 1e-12);
    const auto& c = m.terrain_cells[k];
    EXPECT_NEAR(t.pose.x, (c[0] + 0.5) * o.cell_size, 1e-9);
    EXPECT_NEAR(t.pose.y, (c[1] + 0.5) * o.cell_size, 1e-9);
  }
  // no rubble piece in a terrain cell, and the world is valid (no overlaps)
  for (const auto& r : w.rubble) {
    const int col = static_cast<int>(std::floor(r.pose.x / o.cell_size)), row = static_cast<int>(std::floor(r.pose.y / o.cell_size));
    for (const auto& c : m.terrain_cells) EXPECT_FALSE(c[0] == col && c[1] == row) << "rubble in terrain cell " << col << "," << row;
  }
  const Diagnostics problems = validate(w);
  for (const auto& d : problems.items()) ADD_FAILURE() << d.str();
  EXPECT_EQ(w.metadata.at("terrain"), "stepfield,curb,hurdle");
  // the same seed, the same cells
  EXPECT_EQ(generate_maze(o).terrain_cells, m.terrain_cells);
}

TEST(MazeTerrain, KindsThatDoNotFitACellAndTooFewFreeCellsAreErrors) {
  MazeOptions o;
  o.terrain_fraction = 0.1;
  o.terrain = {TerrainSpec::Kind::stairs};
  try {
    generate_maze(o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("stairs does not fit in a maze cell; cells take stepfield, curb or hurdle"), std::string::npos)
        << e.message();
  }
  o.terrain = {TerrainSpec::Kind::curb};
  o.cols = o.rows = 2;
  o.terrain_fraction = 1.0;  // 4 cells asked, the start cell is never one
  try {
    generate_maze(o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("asks for 4 cells, but only 3 are free"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace rescuesim
