#include "autonomy/astar.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace rescuesim::autonomy {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSqrt2 = 1.4142135623730951;
constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// an open-list entry; the queue pops the smallest (f, h, index)
struct Node {
  double f, h;
  int i;
  bool operator>(const Node& o) const {
    if (f != o.f) return f > o.f;
    if (h != o.h) return h > o.h;
    return i > o.i;
  }
};
using OpenList = std::priority_queue<Node, std::vector<Node>, std::greater<Node>>;

// octile distance between two cells, in cells
double octile(Cell a, Cell b) {
  const double dx = std::abs(a.x - b.x), dy = std::abs(a.y - b.y);
  return std::max(dx, dy) + (kSqrt2 - 1.0) * std::min(dx, dy);
}

// the box around a set of cells and the map's observed part, padded
std::pair<Cell, Cell> search_window(const OccupancyMapper& grid, std::vector<Cell> cells, int pad) {
  if (auto box = grid.observed_box()) {
    cells.push_back(box->first);
    cells.push_back(box->second);
  }
  Cell lo = cells.front(), hi = cells.front();
  for (const Cell& c : cells) {
    lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
    hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
  }
  return {{lo.x - pad, lo.y - pad}, {hi.x + pad, hi.y + pad}};
}

// the search state shared by A* and the frontier Dijkstra
class Search {
 public:
  Search(const OccupancyMapper& grid, const CostMap& costs, const PlannerConfig& config, Cell start)
      : grid_(grid), costs_(costs), start_(start), g_(costs.size(), kInf), parent_(costs.size(), -1),
        closed_(costs.size(), 0) {
    // a start in lethal space may leave through nearby unoccupied cells at the dearest cost
    escaping_ = costs.factor(start) == CostMap::kLethal;
    escape_cells_ = config.escape_radius / grid.resolution();
    escape_factor_ = 2.0 * (1.0 + config.cost.clearance_weight);
  }

  // cost factor of entering a cell, or +inf
  double factor(Cell c) const {
    const double k = costs_.factor(c);
    if (k != CostMap::kLethal) return k;
    if (c == start_) return escape_factor_;
    if (escaping_ && !grid_.is_occupied(c) && std::hypot(c.x - start_.x, c.y - start_.y) <= escape_cells_) {
      return escape_factor_;
    }
    return kInf;
  }

  // relaxes the 8 neighbours of the cell at local index i; heuristic(cell) gives h
  template <class Heuristic>
  void expand(int i, OpenList& open, Heuristic&& heuristic) {
    const Cell c = costs_.cell_at(i);
    const double res = grid_.resolution();
    for (int k = 0; k < 8; ++k) {
      const Cell n{c.x + kDx[k], c.y + kDy[k]};
      if (!costs_.in_window(n)) continue;
      const double kn = factor(n);
      if (kn == kInf) continue;
      // no diagonal squeeze between two blocked cells' corners
      if (k >= 4 && (factor({c.x + kDx[k], c.y}) == kInf || factor({c.x, c.y + kDy[k]}) == kInf)) continue;
      const int j = costs_.local(n);
      if (closed_[j]) continue;
      const double g = g_[i] + (k < 4 ? res : kSqrt2 * res) * kn;
      if (g < g_[j]) {
        g_[j] = g;
        parent_[j] = i;
        const double h = heuristic(n);
        open.push({g + h, h, j});
      }
    }
  }

  // the path of cell centres ending at local index i, collinear interior points removed
  std::vector<Vec2> path_to(int i) const {
    std::vector<Cell> cells;
    for (int j = i; j >= 0; j = parent_[j]) cells.push_back(costs_.cell_at(j));
    std::reverse(cells.begin(), cells.end());
    std::vector<Vec2> path;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      if (k > 0 && k + 1 < cells.size()) {
        const Cell a = cells[k - 1], b = cells[k], c = cells[k + 1];
        if (b.x - a.x == c.x - b.x && b.y - a.y == c.y - b.y) continue;
      }
      path.push_back(grid_.cell_to_world(cells[k]));
    }
    return path;
  }

  std::vector<double>& g() { return g_; }
  std::vector<char>& closed() { return closed_; }

 private:
  const OccupancyMapper& grid_;
  const CostMap& costs_;
  Cell start_;
  std::vector<double> g_;
  std::vector<int> parent_;
  std::vector<char> closed_;
  bool escaping_ = false;
  double escape_cells_ = 0, escape_factor_ = 1;
};

}  // namespace

AStarPlanner::AStarPlanner(PlannerConfig config) : config_(std::move(config)) {}

bool is_frontier(const OccupancyMapper& grid, Cell c) {
  if (!grid.is_free(c)) return false;
  for (int k = 0; k < 8; ++k) {
    const Cell n{c.x + kDx[k], c.y + kDy[k]};
    if (grid.contains(n) && grid.is_unknown(n)) return true;
  }
  return false;
}

double path_length(const std::vector<Vec2>& path) {
  double length = 0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

std::vector<Vec2> AStarPlanner::plan(const OccupancyMapper& grid, const Vec2& start_O, const Vec2& goal_O) {
  expansions_ = 0;
  const auto start = grid.world_to_cell(start_O), goal = grid.world_to_cell(goal_O);
  if (!start || !goal) return {};
  const int pad = static_cast<int>(std::ceil(config_.cost.comfort_distance / grid.resolution())) + 2;
  const auto [lo, hi] = search_window(grid, {*start, *goal}, pad);
  const CostMap costs(grid, config_.cost, lo, hi);
  Search search(grid, costs, config_, *start);
  if (search.factor(*goal) == kInf) return {};

  // A* with the octile heuristic (cost factors are >= 1, so it never overestimates)
  const double res = grid.resolution();
  auto heuristic = [&](Cell c) { return octile(c, *goal) * res; };
  const int s = costs.local(*start), t = costs.local(*goal);
  OpenList open;
  search.g()[s] = 0;
  open.push({heuristic(*start), heuristic(*start), s});
  while (!open.empty()) {
    const Node node = open.top();
    open.pop();
    if (search.closed()[node.i]) continue;
    search.closed()[node.i] = 1;
    ++expansions_;
    if (node.i == t) return search.path_to(t);
    search.expand(node.i, open, heuristic);
  }
  return {};
}

std::vector<Vec2> AStarPlanner::plan_to_nearest_frontier(const OccupancyMapper& grid, const Vec2& start_O,
                                                         const std::vector<Vec2>& excluded_O, const std::vector<Vec2>& claimed_O) {
  return plan_to_nearest_target(
      grid, start_O, [&grid](Cell c) { return is_frontier(grid, c); }, [this](Cell) { return config_.min_frontier_cells; },
      excluded_O, claimed_O);
}

std::vector<Vec2> AStarPlanner::plan_to_nearest_target(const OccupancyMapper& grid, const Vec2& start_O,
                                                       const std::function<bool(Cell)>& is_target,
                                                       const std::function<int(Cell)>& min_cells,
                                                       const std::vector<Vec2>& excluded_O, const std::vector<Vec2>& claimed_O) {
  expansions_ = 0;
  const auto start = grid.world_to_cell(start_O);
  if (!start) return {};
  CostMapConfig cost = config_.cost;
  cost.unknown_traversable = false;
  const int pad = static_cast<int>(std::ceil(cost.comfort_distance / grid.resolution())) + 2;
  const auto [lo, hi] = search_window(grid, {*start}, pad);
  const CostMap costs(grid, cost, lo, hi);
  Search search(grid, costs, config_, *start);

  // frontier cluster sizes, found on demand and remembered per cell (0: not yet measured)
  std::vector<int> cluster_size(costs.size(), 0);
  auto cluster_of = [&](Cell seed) {
    const int si = costs.local(seed);
    if (cluster_size[si] != 0) return cluster_size[si];
    std::vector<int> members{si};
    cluster_size[si] = -1;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Cell c = costs.cell_at(members[k]);
      for (int d = 0; d < 8; ++d) {
        const Cell n{c.x + kDx[d], c.y + kDy[d]};
        if (!costs.in_window(n) || cluster_size[costs.local(n)] != 0 || !grid.contains(n) || !is_target(n)) continue;
        cluster_size[costs.local(n)] = -1;
        members.push_back(costs.local(n));
      }
    }
    for (int m : members) cluster_size[m] = static_cast<int>(members.size());
    return static_cast<int>(members.size());
  };
  auto wanted = [&](Cell c) {
    const Vec2 p = grid.cell_to_world(c);
    if ((p - grid.cell_to_world(*start)).norm() < config_.min_frontier_distance) return false;
    for (const Vec2& q : excluded_O) {
      if ((p - q).norm() < config_.excluded_radius) return false;
    }
    for (const Vec2& q : claimed_O) {
      if ((p - q).norm() < config_.claimed_radius) return false;
    }
    return is_target(c) && cluster_of(c) >= min_cells(c);
  };

  // Dijkstra through known free space until the first wanted frontier cell is settled
  auto no_heuristic = [](Cell) { return 0.0; };
  const int s = costs.local(*start);
  OpenList open;
  search.g()[s] = 0;
  open.push({0.0, 0.0, s});
  while (!open.empty()) {
    const Node node = open.top();
    open.pop();
    if (search.closed()[node.i]) continue;
    search.closed()[node.i] = 1;
    ++expansions_;
    if (wanted(costs.cell_at(node.i))) return search.path_to(node.i);
    search.expand(node.i, open, no_heuristic);
  }
  return {};
}

bool path_blocked(const OccupancyMapper& grid, const std::vector<Vec2>& path, std::size_t first, const Vec2& from_O,
                  double clearance) {
  if (first >= path.size()) return false;
  const double res = grid.resolution();
  const int reach = static_cast<int>(std::ceil(clearance / res)) + 1;
  // is there an occupied cell centre within the clearance of point p?
  auto near_obstacle = [&](const Vec2& p) {
    const Vec2 q = (p - grid.origin()) / res;
    const int cx = static_cast<int>(std::floor(q.x())), cy = static_cast<int>(std::floor(q.y()));
    for (int y = cy - reach; y <= cy + reach; ++y) {
      for (int x = cx - reach; x <= cx + reach; ++x) {
        const Cell c{x, y};
        if (grid.contains(c) && grid.is_occupied(c) && (grid.cell_to_world(c) - p).norm() < clearance) return true;
      }
    }
    return false;
  };
  // sample the remaining polyline every cell
  Vec2 a = from_O;
  for (std::size_t k = first; k < path.size(); ++k) {
    const Vec2 b = path[k];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / res)));
    for (int i = 0; i <= steps; ++i) {
      if (near_obstacle(a + (b - a) * (static_cast<double>(i) / steps))) return true;
    }
    a = b;
  }
  return false;
}

}  // namespace rescuesim::autonomy
