#include "autonomy/look_coverage.h"

#include <algorithm>
#include <cmath>

namespace rescuesim::autonomy {

void LookCoverage::fit(const OccupancyMapper& map) {
  if (map.width() == width_ && map.height() == height_) return;
  width_ = map.width();
  height_ = map.height();
  looked_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
  count_ = 0;
}

int LookCoverage::mark(const OccupancyMapper& map, Cell c) {
  std::uint8_t& f = looked_[static_cast<std::size_t>(map.index(c))];
  if (f & kSelf) return 0;
  const int added = f == 0 ? 1 : 0;
  f |= kSelf;
  ++count_;
  return added;
}

std::uint8_t LookCoverage::flags(Cell c) const {
  if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) return 0;
  return looked_[static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(c.x)];
}

int LookCoverage::mark_team_square(const OccupancyMapper& map, const Vec2& p_M, double half) {
  if (!map.allocated() || !(half > 0)) return 0;
  fit(map);
  int added = 0;
  // the square's cell range, clipped to the grid
  const Vec2 lo = (p_M - Vec2(half, half) - map.origin()) / map.resolution();
  const Vec2 hi = (p_M + Vec2(half, half) - map.origin()) / map.resolution();
  if (!lo.allFinite() || !hi.allFinite()) return 0;
  // off the grid altogether (a teammate's word can be anything): nothing, and no integer overflow
  if (hi.x() < 0 || hi.y() < 0 || lo.x() >= width_ || lo.y() >= height_) return 0;
  const int x0 = static_cast<int>(std::max(0.0, std::floor(lo.x()))), y0 = static_cast<int>(std::max(0.0, std::floor(lo.y())));
  const int x1 = static_cast<int>(std::min<double>(width_ - 1, std::floor(hi.x())));
  const int y1 = static_cast<int>(std::min<double>(height_ - 1, std::floor(hi.y())));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Vec2 q = map.cell_to_world({x, y}) - p_M;
      if (std::abs(q.x()) > half || std::abs(q.y()) > half) continue;
      std::uint8_t& f = looked_[static_cast<std::size_t>(map.index({x, y}))];
      added += f == 0 ? 1 : 0;
      f |= kTeam;
    }
  }
  return added;
}

int LookCoverage::look(const OccupancyMapper& map, const Vec2& p_M, double yaw, const CameraFan& fan) {
  if (!map.allocated() || !(fan.range > 0) || !(fan.hfov > 0) || !(fan.beam_spacing > 0)) return 0;
  fit(map);
  int added = 0;
  const int beams = std::max(1, static_cast<int>(std::ceil(fan.hfov / fan.beam_spacing))) + 1;
  // half-cell steps along each beam: no cell a beam crosses diagonally is skipped for long,
  // and neighbouring beams fill what one leaves out
  const double step = 0.5 * map.resolution();
  const int steps = static_cast<int>(std::ceil(fan.range / step));
  for (int b = 0; b < beams; ++b) {
    const double a = yaw - fan.hfov / 2 + fan.hfov * b / (beams - 1);
    const Vec2 d(std::cos(a), std::sin(a));
    for (int k = 0; k <= steps; ++k) {
      const auto c = map.world_to_cell(p_M + d * (k * step));
      if (!c) break;
      const CellState s = map.state(*c);
      if (s == CellState::unknown && k * step <= fan.near) continue;
      if (s == CellState::unknown) break;
      added += mark(map, *c);
      if (s == CellState::occupied) break;
    }
  }
  return added;
}

int LookCoverage::cover_disc(const OccupancyMapper& map, const Vec2& p_M, double radius) {
  if (!map.allocated() || !(radius > 0)) return 0;
  fit(map);
  int added = 0;
  const int reach = static_cast<int>(std::ceil(radius / map.resolution()));
  const auto centre = map.world_to_cell(p_M);
  if (!centre) return 0;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const Cell c{centre->x + dx, centre->y + dy};
      if (map.contains(c) && (map.cell_to_world(c) - p_M).norm() <= radius) added += mark(map, c);
    }
  }
  return added;
}

}  // namespace rescuesim::autonomy
