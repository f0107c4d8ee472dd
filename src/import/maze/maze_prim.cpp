/// The maze grid: modified Prim's algorithm for a spanning tree, then loops, raised cells and
/// victim cells. Every random choice draws from its own `Rng` stream derived from the seed, so
/// changing one feature (say the victim count) never moves the walls.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "import/maze/maze.h"
#include "import/maze/maze_limits.h"

namespace rescuesim {

namespace {

using maze_limits::kMinPlatform;
using maze_limits::kMinVictimInterior;
using maze_limits::kMinTerrainInterior;

/// Largest grid side and rubble count accepted.
constexpr int kMaxCells = 500;
constexpr int kMaxRubble = 10000;

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

[[noreturn]] void bad_option(const std::string& name, const std::string& message) {
  throw Error(SourceRef{"", 0, "maze option " + name}, message);
}

void check_int_range(const char* name, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    bad_option(name, std::string(name) + " = " + std::to_string(value) + ", expected an integer in [" + std::to_string(lo) +
                         ", " + std::to_string(hi) + "]");
  }
}

void check_positive(const char* name, double value) {
  if (!std::isfinite(value) || !(value > 0)) {
    bad_option(name, std::string(name) + " = " + num(value) + " m, expected a finite length > 0");
  }
}

void check_fraction(const char* name, double value) {
  if (!(value >= 0 && value <= 1)) {
    bad_option(name, std::string(name) + " = " + num(value) + ", expected a fraction in [0, 1]");
  }
}

/// Cells that get a platform: round(raised_fraction × cells), never the start cell.
int raised_target(const MazeOptions& o) {
  const long n = std::lround(o.raised_fraction * o.cols * o.rows);
  return static_cast<int>(std::min<long>(n, static_cast<long>(o.cols) * o.rows - 1));
}

/// Rejects impossible options before any work, naming the option and what was expected.
void check_options(const MazeOptions& o) {
  check_int_range("cols", o.cols, 1, kMaxCells);
  check_int_range("rows", o.rows, 1, kMaxCells);
  check_positive("wall_thickness", o.wall_thickness);
  check_positive("wall_height", o.wall_height);
  check_positive("cell_size", o.cell_size);
  if (!(o.cell_size > 2 * o.wall_thickness)) {
    bad_option("cell_size", "cell_size = " + num(o.cell_size) + " m, expected more than twice wall_thickness (" +
                                num(o.wall_thickness) + " m)");
  }
  check_positive("raised_height", o.raised_height);
  check_positive("ramp_length", o.ramp_length);
  check_fraction("loop_fraction", o.loop_fraction);
  check_fraction("raised_fraction", o.raised_fraction);
  check_fraction("terrain_fraction", o.terrain_fraction);
  if (o.terrain_fraction > 0) {
    if (o.terrain.empty()) bad_option("terrain", "terrain_fraction = " + num(o.terrain_fraction) + " needs at least one terrain kind");
    for (TerrainSpec::Kind k : o.terrain) {
      if (k != TerrainSpec::Kind::stepfield && k != TerrainSpec::Kind::curb && k != TerrainSpec::Kind::hurdle) {
        bad_option("terrain", std::string(TerrainSpec::kind_name(k)) +
                                  " does not fit in a maze cell; cells take stepfield, curb or hurdle (stairs, gaps and crossing "
                                  "ramps need a lane: rescuesim arena)");
      }
    }
    if (o.cell_size - o.wall_thickness < kMinTerrainInterior) {
      bad_option("terrain_fraction", "terrain_fraction = " + num(o.terrain_fraction) + " needs a cell interior of at least " +
                                         num(kMinTerrainInterior) + " m, but cell_size " + num(o.cell_size) + " m gives " +
                                         num(o.cell_size - o.wall_thickness) + " m");
    }
  }
  check_int_range("rubble", o.rubble, 0, kMaxRubble);
  // too many victims for the grid is reported once the free cells are known
  check_int_range("victims", o.victims, 0, std::numeric_limits<int>::max());
  if (o.start_cell[0] < 0 || o.start_cell[0] >= o.cols || o.start_cell[1] < 0 || o.start_cell[1] >= o.rows) {
    bad_option("start_cell", "start_cell = (" + std::to_string(o.start_cell[0]) + ", " + std::to_string(o.start_cell[1]) +
                                 "), expected a cell inside the " + std::to_string(o.cols) + " x " + std::to_string(o.rows) +
                                 " grid (col in [0, " + std::to_string(o.cols - 1) + "], row in [0, " +
                                 std::to_string(o.rows - 1) + "])");
  }
  for (std::size_t k = 0; k < o.more_start_cells.size(); ++k) {
    const auto& c = o.more_start_cells[k];
    const std::string name = "start_cells[" + std::to_string(k + 1) + "]";
    if (c[0] < 0 || c[0] >= o.cols || c[1] < 0 || c[1] >= o.rows) {
      bad_option("start_cells", name + " = (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ") lies outside the " +
                                    std::to_string(o.cols) + " x " + std::to_string(o.rows) + " grid");
    }
    bool repeated = c == o.start_cell;
    for (std::size_t j = 0; j < k; ++j) repeated = repeated || c == o.more_start_cells[j];
    if (repeated) {
      bad_option("start_cells",
                 name + " = (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ") is already a start: one robot per cell");
    }
  }
  // geometry that must fit whichever cells are chosen, so the answer never depends on the seed
  const double interior = o.cell_size - o.wall_thickness;
  if (raised_target(o) > 0 && interior - 2 * o.ramp_length < kMinPlatform) {
    bad_option("raised_fraction", "raised_fraction = " + num(o.raised_fraction) + " needs cells whose interior (cell_size " +
                                      num(o.cell_size) + " m - wall_thickness) holds two ramps of ramp_length " +
                                      num(o.ramp_length) + " m and a " + num(kMinPlatform) +
                                      " m platform; use larger cells or shorter ramps");
  }
  if (o.victims > 0 && interior < kMinVictimInterior) {
    bad_option("victims", "victims = " + std::to_string(o.victims) + " needs a cell interior of at least " +
                              num(kMinVictimInterior) + " m, but cell_size " + num(o.cell_size) + " m gives " + num(interior) +
                              " m");
  }
}

/// The neighbour of cell (c, r) through `side`.
std::array<int, 2> step(int c, int r, Side side) {
  switch (side) {
    case Side::east: return {c + 1, r};
    case Side::north: return {c, r + 1};
    case Side::west: return {c - 1, r};
    case Side::south: return {c, r - 1};
  }
  return {c, r};
}

constexpr Side kSides[4] = {Side::east, Side::north, Side::west, Side::south};

Side opposite(Side s) { return static_cast<Side>((static_cast<int>(s) + 2) % 4); }

/// Sets the passage flag between (c, r) and its neighbour through `side`.
void set_open(Maze& m, int c, int r, Side side) {
  switch (side) {
    case Side::east: m.open_east[static_cast<std::size_t>(m.index(c, r))] = 1; break;
    case Side::north: m.open_north[static_cast<std::size_t>(m.index(c, r))] = 1; break;
    case Side::west: m.open_east[static_cast<std::size_t>(m.index(c - 1, r))] = 1; break;
    case Side::south: m.open_north[static_cast<std::size_t>(m.index(c, r - 1))] = 1; break;
  }
}

/// Moves k uniformly chosen items to the front of v (a partial Fisher-Yates shuffle).
template <typename T>
void choose_front(std::vector<T>& v, std::size_t k, Rng& rng) {
  k = std::min(k, v.size());
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = i + rng.below(static_cast<std::uint32_t>(v.size() - i));
    std::swap(v[i], v[j]);
  }
}

/// Modified Prim's algorithm: grow a spanning tree from the start cell by attaching random
/// frontier cells to random neighbours already in the tree.
void carve_tree(Maze& m) {
  const int cols = m.options.cols, rows = m.options.rows;
  Rng rng(m.options.seed, "maze/prim");
  std::vector<std::uint8_t> in_tree(static_cast<std::size_t>(m.cell_count()), 0);
  std::vector<std::uint8_t> in_frontier(in_tree.size(), 0);
  std::vector<std::array<int, 2>> frontier;
  const auto inside = [&](const std::array<int, 2>& p) { return p[0] >= 0 && p[0] < cols && p[1] >= 0 && p[1] < rows; };
  const auto add = [&](int c, int r) {
    in_tree[static_cast<std::size_t>(m.index(c, r))] = 1;
    for (Side s : kSides) {
      const auto n = step(c, r, s);
      if (!inside(n)) continue;
      const auto i = static_cast<std::size_t>(m.index(n[0], n[1]));
      if (in_tree[i] || in_frontier[i]) continue;
      in_frontier[i] = 1;
      frontier.push_back(n);
    }
  };
  add(m.options.start_cell[0], m.options.start_cell[1]);
  while (!frontier.empty()) {
    // take a random frontier cell out (swap with the last: order stays deterministic)
    const std::size_t k = rng.below(static_cast<std::uint32_t>(frontier.size()));
    const auto cell = frontier[k];
    frontier[k] = frontier.back();
    frontier.pop_back();
    // connect it to one of its neighbours already in the tree, chosen at random
    Side links[4];
    std::uint32_t n_links = 0;
    for (Side s : kSides) {
      const auto n = step(cell[0], cell[1], s);
      if (inside(n) && in_tree[static_cast<std::size_t>(m.index(n[0], n[1]))]) links[n_links++] = s;
    }
    set_open(m, cell[0], cell[1], links[rng.below(n_links)]);
    add(cell[0], cell[1]);
  }
}

/// Opens round(loop_fraction × closed interior walls) more walls, chosen at random.
void add_loops(Maze& m) {
  const int cols = m.options.cols, rows = m.options.rows;
  // closed interior walls in cell order, east before north: (cell index, side)
  std::vector<std::pair<int, Side>> closed;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int i = m.index(c, r);
      if (c + 1 < cols && !m.open_east[static_cast<std::size_t>(i)]) closed.emplace_back(i, Side::east);
      if (r + 1 < rows && !m.open_north[static_cast<std::size_t>(i)]) closed.emplace_back(i, Side::north);
    }
  }
  const auto k = static_cast<std::size_t>(std::lround(m.options.loop_fraction * static_cast<double>(closed.size())));
  Rng rng(m.options.seed, "maze/loops");
  choose_front(closed, k, rng);
  for (std::size_t j = 0; j < k; ++j) set_open(m, closed[j].first % cols, closed[j].first / cols, closed[j].second);
}

/// True for the start cells (start_cell and more_start_cells), per cell index.
std::vector<std::uint8_t> start_cells(const Maze& m) {
  std::vector<std::uint8_t> starts(static_cast<std::size_t>(m.cell_count()), 0);
  starts[static_cast<std::size_t>(m.index(m.options.start_cell[0], m.options.start_cell[1]))] = 1;
  for (const auto& c : m.options.more_start_cells) starts[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  return starts;
}

/// Picks the terrain cells at random among the cells that are no start, raised or victim cell;
/// listed in cell order. Throws when there are too few.
void choose_terrain(Maze& m) {
  const long want = std::lround(m.options.terrain_fraction * m.cell_count());
  if (want <= 0) return;
  std::vector<std::uint8_t> taken = start_cells(m);
  for (const auto& c : m.raised_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  for (const auto& c : m.victim_cells) taken[static_cast<std::size_t>(m.index(c[0], c[1]))] = 1;
  std::vector<int> cells;
  for (int i = 0; i < m.cell_count(); ++i) {
    if (!taken[static_cast<std::size_t>(i)]) cells.push_back(i);
  }
  if (want > std::ssize(cells)) {
    bad_option("terrain_fraction", "terrain_fraction = " + num(m.options.terrain_fraction) + " asks for " + std::to_string(want) +
                                       " cells, but only " + std::to_string(cells.size()) +
                                       " are free (not a start, raised or victim cell)");
  }
  Rng rng(m.options.seed, "maze/terrain");
  choose_front(cells, static_cast<std::size_t>(want), rng);
  cells.resize(static_cast<std::size_t>(want));
  std::sort(cells.begin(), cells.end());
  for (int i : cells) m.terrain_cells.push_back({i % m.options.cols, i / m.options.cols});
}

/// Picks the raised cells at random among all but the start cells; listed in cell order.
void choose_raised(Maze& m) {
  const int want = raised_target(m.options);
  if (want <= 0) return;
  const std::vector<std::uint8_t> starts = start_cells(m);
  std::vector<int> cells;
  for (int i = 0; i < m.cell_count(); ++i) {
    if (!starts[static_cast<std::size_t>(i)]) cells.push_back(i);
  }
  Rng rng(m.options.seed, "maze/raised");
  choose_front(cells, static_cast<std::size_t>(want), rng);
  cells.resize(static_cast<std::size_t>(want));
  std::sort(cells.begin(), cells.end());
  for (int i : cells) m.raised_cells.push_back({i % m.options.cols, i / m.options.cols});
}

/// Places victims: random dead ends first, then random other cells with a closed side;
/// never a start cell or a raised cell, one per cell, each against a closed side.
void choose_victims(Maze& m) {
  const int want = m.options.victims;
  if (want <= 0) return;
  const int cols = m.options.cols;
  const std::vector<std::uint8_t> starts = start_cells(m);
  std::vector<std::uint8_t> raised(static_cast<std::size_t>(m.cell_count()), 0);
  for (const auto& rc : m.raised_cells) raised[static_cast<std::size_t>(m.index(rc[0], rc[1]))] = 1;
  std::vector<int> dead_ends, others;
  for (int i = 0; i < m.cell_count(); ++i) {
    if (starts[static_cast<std::size_t>(i)] || raised[static_cast<std::size_t>(i)]) continue;
    const int d = m.degree(i % cols, i / cols);
    if (d == 1) {
      dead_ends.push_back(i);
    } else if (d < 4) {
      others.push_back(i);
    }
  }
  const auto room = static_cast<int>(dead_ends.size() + others.size());
  if (want > room) {
    bad_option("victims", std::to_string(want) + " requested, but only " + std::to_string(room) +
                              " cells can hold one (not a start cell, not a raised cell, not a cell open on all sides)");
  }
  Rng rng(m.options.seed, "maze/victims");
  choose_front(dead_ends, static_cast<std::size_t>(want), rng);
  std::vector<int> chosen(dead_ends.begin(), dead_ends.begin() + std::min<std::ptrdiff_t>(want, std::ssize(dead_ends)));
  if (std::ssize(chosen) < want) {
    const auto more = static_cast<std::size_t>(want - std::ssize(chosen));
    choose_front(others, more, rng);
    chosen.insert(chosen.end(), others.begin(), others.begin() + static_cast<std::ptrdiff_t>(more));
  }
  for (int i : chosen) {
    const int c = i % cols, r = i / cols;
    Side closed[4];
    std::uint32_t n_closed = 0;
    Side open_side = Side::east;
    for (Side s : kSides) {
      if (m.is_open(c, r, s)) {
        open_side = s;
      } else {
        closed[n_closed++] = s;
      }
    }
    // a dead end's victim lies at the far wall, facing the way in; elsewhere any closed side
    const Side side = n_closed == 3 ? opposite(open_side) : closed[rng.below(n_closed)];
    m.victim_cells.push_back({c, r});
    m.victim_sides.push_back(side);
  }
}

}  // namespace

bool Maze::is_open(int col, int row, Side side) const {
  const int cols = options.cols, rows = options.rows;
  RS_DEMAND(col >= 0 && col < cols && row >= 0 && row < rows, "maze cell outside the grid");
  switch (side) {
    case Side::east: return col + 1 < cols && open_east[static_cast<std::size_t>(index(col, row))] != 0;
    case Side::north: return row + 1 < rows && open_north[static_cast<std::size_t>(index(col, row))] != 0;
    case Side::west: return col > 0 && open_east[static_cast<std::size_t>(index(col - 1, row))] != 0;
    case Side::south: return row > 0 && open_north[static_cast<std::size_t>(index(col, row - 1))] != 0;
  }
  return false;
}

int Maze::opening_count() const {
  int n = 0;
  for (int r = 0; r < options.rows; ++r) {
    for (int c = 0; c < options.cols; ++c) n += int{is_open(c, r, Side::east)} + int{is_open(c, r, Side::north)};
  }
  return n;
}

int Maze::degree(int col, int row) const {
  int n = 0;
  for (Side s : kSides) n += int{is_open(col, row, s)};
  return n;
}

std::vector<std::uint8_t> Maze::reachable_from(std::array<int, 2> from) const {
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(cell_count()), 0);
  RS_DEMAND(from[0] >= 0 && from[0] < options.cols && from[1] >= 0 && from[1] < options.rows, "maze cell outside the grid");
  // depth-first flood fill with an explicit stack (no recursion on 250 000 cells)
  std::vector<std::array<int, 2>> stack{from};
  seen[static_cast<std::size_t>(index(from[0], from[1]))] = 1;
  while (!stack.empty()) {
    const auto cell = stack.back();
    stack.pop_back();
    for (Side s : kSides) {
      if (!is_open(cell[0], cell[1], s)) continue;
      const auto n = step(cell[0], cell[1], s);
      auto& flag = seen[static_cast<std::size_t>(index(n[0], n[1]))];
      if (flag) continue;
      flag = 1;
      stack.push_back(n);
    }
  }
  return seen;
}

Maze generate_maze(const MazeOptions& options) {
  check_options(options);
  Maze m;
  m.options = options;
  m.open_east.assign(static_cast<std::size_t>(m.cell_count()), 0);
  m.open_north.assign(static_cast<std::size_t>(m.cell_count()), 0);
  carve_tree(m);
  add_loops(m);
  choose_raised(m);
  choose_victims(m);
  choose_terrain(m);
  return m;
}

}  // namespace rescuesim
