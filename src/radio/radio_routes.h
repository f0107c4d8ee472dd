#pragma once
/// Multi-hop routes over radio links: the widest path (the path whose weakest link has the
/// largest margin over the link threshold), ties broken by fewer hops, then by the lowest
/// node indices. Links are symmetric; node indices are 0..n-1.

#include <span>
#include <vector>

namespace rescuesim {

/// The link margins between n nodes, row-major n×n; an entry that is not finite-or-+inf and
/// >= 0 (NaN, −inf, negative) is "no link". The diagonal is ignored.
struct MarginTable {
  int n = 0;
  std::vector<double> margin_db;  ///< n*n, margin_db[a*n + b] == margin_db[b*n + a]

  bool linked(int a, int b) const { return a != b && margin_db[static_cast<std::size_t>(a * n + b)] >= 0.0; }
  double at(int a, int b) const { return margin_db[static_cast<std::size_t>(a * n + b)]; }
};

/// The bottleneck (weakest link margin, dB) of the widest path from `from` to every node:
/// +inf for `from` itself, −inf for nodes not reachable. O(n²).
std::vector<double> widest_bottlenecks(const MarginTable& links, int from);

/// The route from `from` to `to` (both ends included) given `from`'s bottlenecks: among the
/// paths whose every link has margin >= bottleneck[to], one with the fewest hops; at each
/// step the lowest-index node discovered first. Empty when `to` is not reachable; {from}
/// when to == from. O(n²).
std::vector<int> widest_route(const MarginTable& links, std::span<const double> bottleneck, int from, int to);

}  // namespace rescuesim
