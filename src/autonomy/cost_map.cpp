#include "autonomy/cost_map.h"

#include <algorithm>
#include <cmath>

namespace rescuesim::autonomy {

namespace {

constexpr double kFar = 1e20;  // squared distance standing for "no obstacle"

// exact squared distance transform of a sampled function along one line (Felzenszwalb and
// Huttenlocher): d[q] = min_p (q - p)^2 + f[p]; v, z are scratch of size n and n + 1
void distance_1d(const double* f, double* d, int n, std::vector<int>& v, std::vector<double>& z) {
  int k = 0;
  v[0] = 0;
  z[0] = -kFar;
  z[1] = kFar;
  // lower envelope of the parabolas rooted at each sample
  for (int q = 1; q < n; ++q) {
    double s = 0;
    while (true) {
      const int p = v[k];
      s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * q - 2.0 * p);
      if (s > z[k] || k == 0) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kFar;
  }
  // read the envelope back at every sample
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

}  // namespace

CostMap::CostMap(const OccupancyMapper& grid, const CostMapConfig& config, Cell lo, Cell hi) {
  lo_ = {std::max(lo.x, 0), std::max(lo.y, 0)};
  hi_ = {std::min(hi.x, grid.width() - 1), std::min(hi.y, grid.height() - 1)};
  if (hi_.x < lo_.x || hi_.y < lo_.y) {
    hi_ = {lo_.x - 1, lo_.y - 1};
    return;
  }
  width_ = hi_.x - lo_.x + 1;
  const int height = hi_.y - lo_.y + 1;
  const int n = width_ * height;

  // squared distance (cells) to the nearest occupied cell: columns, then rows
  std::vector<double> f(n), g(n);
  for (int i = 0; i < n; ++i) f[i] = grid.is_occupied(cell_at(i)) ? 0.0 : kFar;
  const int longest = std::max(width_, height);
  std::vector<double> line_in(longest), line_out(longest), z(longest + 1);
  std::vector<int> v(longest);
  for (int x = 0; x < width_; ++x) {
    for (int y = 0; y < height; ++y) line_in[y] = f[y * width_ + x];
    distance_1d(line_in.data(), line_out.data(), height, v, z);
    for (int y = 0; y < height; ++y) g[y * width_ + x] = line_out[y];
  }
  for (int y = 0; y < height; ++y) {
    distance_1d(&g[y * width_], &f[y * width_], width_, v, z);
  }

  // turn distance into cost: lethal inside the robot's radius (plus half a cell, since an
  // occupied cell's obstacle may lie anywhere in it), dearer up to the comfort distance
  const double res = grid.resolution();
  const double lethal = config.robot_radius + 0.5 * res;
  const double comfort = std::max(config.comfort_distance, lethal + res);
  factor_.resize(n);
  clearance_.resize(n);
  for (int i = 0; i < n; ++i) {
    double d = f[i] >= 0.5 * kFar ? std::numeric_limits<double>::infinity() : std::sqrt(f[i]) * res;
    if (!config.keep_out.empty()) {
      const Vec2 p = grid.cell_to_world(cell_at(i));
      for (const Vec2& c : config.keep_out) d = std::min(d, std::max(0.0, (p - c).norm() - config.keep_out_radius));
    }
    clearance_[i] = static_cast<float>(d);
    const CellState s = grid.state(cell_at(i));
    if (s == CellState::occupied || d < lethal || (s == CellState::unknown && !config.unknown_traversable)) {
      factor_[i] = kLethal;
      continue;
    }
    double k = 1.0 + config.clearance_weight * std::max(0.0, (comfort - d) / (comfort - lethal));
    if (s == CellState::unknown) k *= std::max(1.0, config.unknown_cost);
    factor_[i] = static_cast<float>(k);
  }
}

}  // namespace rescuesim::autonomy
