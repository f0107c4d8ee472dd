#include "radio/radio_routes.h"

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace rescuesim {

std::vector<double> widest_bottlenecks(const MarginTable& links, int from) {
  const int n = links.n;
  RS_DEMAND(from >= 0 && from < n, "widest_bottlenecks: source out of range");
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  std::vector<double> best(static_cast<std::size_t>(n), kNone);
  std::vector<bool> done(static_cast<std::size_t>(n), false);
  best[static_cast<std::size_t>(from)] = std::numeric_limits<double>::infinity();
  // dense max-min Dijkstra: settle the widest unsettled node (lowest index on ties)
  for (int round = 0; round < n; ++round) {
    int u = -1;
    for (int v = 0; v < n; ++v) {
      if (done[static_cast<std::size_t>(v)] || best[static_cast<std::size_t>(v)] == kNone) continue;
      if (u < 0 || best[static_cast<std::size_t>(v)] > best[static_cast<std::size_t>(u)]) u = v;
    }
    if (u < 0) break;
    done[static_cast<std::size_t>(u)] = true;
    for (int v = 0; v < n; ++v) {
      if (done[static_cast<std::size_t>(v)] || !links.linked(u, v)) continue;
      const double width = std::min(best[static_cast<std::size_t>(u)], links.at(u, v));
      if (width > best[static_cast<std::size_t>(v)]) best[static_cast<std::size_t>(v)] = width;
    }
  }
  return best;
}

std::vector<int> widest_route(const MarginTable& links, std::span<const double> bottleneck, int from, int to) {
  const int n = links.n;
  RS_DEMAND(from >= 0 && from < n && to >= 0 && to < n, "widest_route: node out of range");
  if (from == to) return {from};
  const double need = bottleneck[static_cast<std::size_t>(to)];
  if (!(need >= 0.0)) return {};
  // breadth-first over the links at least as strong as the bottleneck: fewest hops, and
  // neighbours visited in index order, so the route is the same on every run
  std::vector<int> parent(static_cast<std::size_t>(n), -2);
  std::vector<int> queue{from};
  parent[static_cast<std::size_t>(from)] = -1;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int u = queue[head];
    if (u == to) break;
    for (int v = 0; v < n; ++v) {
      if (parent[static_cast<std::size_t>(v)] != -2 || !links.linked(u, v) || !(links.at(u, v) >= need)) continue;
      parent[static_cast<std::size_t>(v)] = u;
      queue.push_back(v);
    }
  }
  if (parent[static_cast<std::size_t>(to)] == -2) return {};
  std::vector<int> route;
  for (int v = to; v != -1; v = parent[static_cast<std::size_t>(v)]) route.push_back(v);
  std::reverse(route.begin(), route.end());
  return route;
}

}  // namespace rescuesim
