#include "autonomy/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace rescuesim::autonomy {

namespace {

// the largest grid we agree to allocate (cells), far above any sane map
constexpr double kMaxCells = 1 << 28;

// m a return is moved along its beam before finding its cell
constexpr double kBorderNudge = 1e-4;

// one beam of a scan; `end` in continuous cell coordinates (cell (i, j) spans [i, i+1) x [j, j+1))
struct Beam {
  Vec2 direction_O = Vec2::Zero();  // unit, odom frame
  Vec2 end = Vec2::Zero();
  double length = 0;                // m to the return or the clearing limit
  double clear_length = 0;          // m cleared from the sensor
  bool hit = false;                 // ends in a return
  bool valid = false;               // usable at all
};

// walks the cells crossed by the segment a -> b (cell units), first to last, calling
// visit(x, y) until it returns false; Amanatides-Woo traversal, steered so that it always
// ends in the cell holding b
template <class Visit>
void trace(const Vec2& a, const Vec2& b, Visit&& visit) {
  int x = static_cast<int>(std::floor(a.x())), y = static_cast<int>(std::floor(a.y()));
  const int ex = static_cast<int>(std::floor(b.x())), ey = static_cast<int>(std::floor(b.y()));
  const Vec2 d = b - a;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  const double delta_x = d.x() != 0 ? 1.0 / std::abs(d.x()) : kInf;
  const double delta_y = d.y() != 0 ? 1.0 / std::abs(d.y()) : kInf;
  double next_x = d.x() > 0 ? (x + 1 - a.x()) * delta_x : (d.x() < 0 ? (a.x() - x) * delta_x : kInf);
  double next_y = d.y() > 0 ? (y + 1 - a.y()) * delta_y : (d.y() < 0 ? (a.y() - y) * delta_y : kInf);
  while (true) {
    if (!visit(x, y) || (x == ex && y == ey)) return;
    // step across whichever cell border comes first, but never past the end cell's row or column
    const bool step_in_x = x != ex && (next_x < next_y || y == ey);
    if (step_in_x) {
      x += step_x;
      next_x += delta_x;
    } else {
      y += step_y;
      next_y += delta_y;
    }
  }
}

}  // namespace

OccupancyMapper::OccupancyMapper(OccupancyMapperConfig config) : config_(std::move(config)) {
  resolution_ = config_.resolution;
  if (!(resolution_ > 0) || !std::isfinite(resolution_)) {
    throw Error(std::string("OccupancyMapper: resolution must be a positive number of metres, got ") +
                std::to_string(resolution_));
  }
  if (config_.size.x() != 0 || config_.size.y() != 0) {
    const double w = std::ceil(config_.size.x() / resolution_ - 1e-9);
    const double h = std::ceil(config_.size.y() / resolution_ - 1e-9);
    if (!(w >= 1 && h >= 1) || w * h > kMaxCells) {
      throw Error(std::string("OccupancyMapper: the box size must be positive and at most ") +
                  std::to_string(static_cast<long>(kMaxCells)) + " cells, got " + std::to_string(config_.size.x()) +
                  " x " + std::to_string(config_.size.y()) + " m");
    }
    allocate(config_.origin_O, static_cast<int>(w), static_cast<int>(h));
  } else if (!(config_.auto_size > 0) || std::pow(config_.auto_size / resolution_, 2) > kMaxCells) {
    throw Error(std::string("OccupancyMapper: auto_size must be positive and at most ") +
                std::to_string(static_cast<long>(kMaxCells)) + " cells, got " + std::to_string(config_.auto_size) +
                " m");
  }
}

void OccupancyMapper::allocate(const Vec2& origin_O, int width, int height) {
  origin_O_ = origin_O;
  width_ = width;
  height_ = height;
  tiles_x_ = (width + kTileSide - 1) / kTileSide;
  tiles_ = Tiles(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>((height + kTileSide - 1) / kTileSide));
}

void OccupancyMapper::allocate_around(const Vec2& p_O) {
  if (allocated()) return;
  const int n = static_cast<int>(std::ceil(config_.auto_size / resolution_ - 1e-9));
  allocate(p_O - Vec2::Constant(0.5 * n * resolution_), n, n);
}

std::optional<Cell> OccupancyMapper::world_to_cell(const Vec2& p_O) const {
  const Vec2 q = (p_O - origin_O_) / resolution_;
  if (!(q.x() >= 0 && q.y() >= 0 && q.x() < width_ && q.y() < height_)) return std::nullopt;
  const Cell c{static_cast<int>(q.x()), static_cast<int>(q.y())};
  if (!contains(c)) return std::nullopt;
  return c;
}

void OccupancyMapper::grow_observed(Cell c) {
  if (observed_max_.x < observed_min_.x) {
    observed_min_ = observed_max_ = c;
    return;
  }
  observed_min_ = {std::min(observed_min_.x, c.x), std::min(observed_min_.y, c.y)};
  observed_max_ = {std::max(observed_max_.x, c.x), std::max(observed_max_.y, c.y)};
}

std::optional<std::pair<Cell, Cell>> OccupancyMapper::observed_box() const {
  if (observed_max_.x < observed_min_.x) return std::nullopt;
  return std::pair{observed_min_, observed_max_};
}

void OccupancyMapper::set_state(Cell c, CellState s) {
  Tile& t = tiles_.at(tile_index(c));
  const int k = in_tile(c);
  t.log_odds[k] = s == CellState::unknown ? 0.0f : (s == CellState::free ? config_.min_log_odds : config_.max_log_odds);
  t.mark[k] = s == CellState::unknown ? 0 : 1;  // 1: observed, by no scan
  grow_observed(c);
}

int OccupancyMapper::update(Tile& t, int k, float delta, std::uint32_t mark) {
  float& l = t.log_odds[k];
  const bool first_look = t.mark[k] == 0;
  l = std::clamp(l + delta, config_.min_log_odds, config_.max_log_odds);
  t.mark[k] = mark;
  return first_look ? 1 : 0;
}

std::size_t OccupancyMapper::cell_bytes() const {
  std::size_t n = tiles_.size() * sizeof(std::unique_ptr<Tile>);
  for (std::size_t i = 0; i < tiles_.size(); ++i) n += tiles_[i] ? sizeof(Tile) : 0;
  return n;
}

int OccupancyMapper::integrate(const msg::LaserScan& scan, const Pose2& X_OS) {
  if (!allocated()) allocate_around(X_OS.position());
  const Vec2 start = (X_OS.position() - origin_O_) / resolution_;
  if (!world_to_cell(X_OS.position())) return 0;
  ++scan_count_;
  const std::uint32_t hit_mark = 2 * scan_count_, clear_mark = hit_mark + 1;

  // place each usable beam's end in cell units, per REP-117 (index-aligned with the scan)
  std::vector<Beam> beams(scan.ranges.size());
  const double inf_range = std::min<double>(scan.range_max, config_.inf_free_range);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double r = scan.ranges[i];
    Beam& b = beams[i];
    if (std::isnan(r) || r == -std::numeric_limits<double>::infinity()) continue;
    if (std::isinf(r)) {
      b.length = inf_range;
    } else if (r < scan.range_min) {
      continue;
    } else if (r >= scan.range_max) {
      b.length = scan.range_max;
    } else {
      b.length = r;
      b.hit = true;
    }
    if (!(b.length > 0)) continue;
    const double angle = static_cast<double>(scan.angle_min) + static_cast<double>(i) * scan.angle_increment;
    b.direction_O = Vec2(std::cos(X_OS.yaw + angle), std::sin(X_OS.yaw + angle));
    // a return exactly on a cell border counts in the cell beyond it, inside the obstacle,
    // which no beam crosses; the cell on the sensor's side may be open space
    const double end_length = b.hit ? b.length + kBorderNudge : b.length;
    b.end = (X_OS.position() + end_length * b.direction_O - origin_O_) / resolution_;
    b.clear_length = b.length;
    b.valid = true;
  }

  // a beam grazing a surface runs within a cell of it for a long way before its return;
  // leave that stretch uncleared, or walls seen at a shallow angle would erode. the surface
  // direction is the chord through the two neighbouring returns when the three lie on a
  // line, else (at an edge) the line to the nearer neighbouring return
  auto is_hit = [&](std::size_t j) { return beams[j].valid && beams[j].hit; };
  auto sine_to = [&](const Beam& b, const Vec2& tangent) {
    const double n = tangent.norm();
    return n > 0 ? std::abs(b.direction_O.x() * tangent.y() - b.direction_O.y() * tangent.x()) / n : 1.0;
  };
  for (std::size_t i = 0; i < beams.size(); ++i) {
    Beam& b = beams[i];
    if (!is_hit(i)) continue;
    const bool has_before = i > 0 && is_hit(i - 1), has_after = i + 1 < beams.size() && is_hit(i + 1);
    double sine = 1.0;
    if (has_before && has_after) {
      const Vec2 chord = beams[i + 1].end - beams[i - 1].end;
      const Vec2 off = b.end - beams[i - 1].end;
      const double span = chord.norm();
      const double deviation = span > 0 ? std::abs(off.x() * chord.y() - off.y() * chord.x()) / span : 0.0;
      if (deviation < 0.5 + 0.05 * span) {
        sine = sine_to(b, chord);
      } else {
        const Vec2 to_before = beams[i - 1].end - b.end, to_after = beams[i + 1].end - b.end;
        sine = sine_to(b, to_before.squaredNorm() <= to_after.squaredNorm() ? to_before : to_after);
      }
    } else if (has_before || has_after) {
      sine = sine_to(b, beams[has_before ? i - 1 : i + 1].end - b.end);
    }
    const double guard = std::min(config_.surface_guard_cells * resolution_ / std::max(sine, 1e-3), config_.max_surface_guard);
    b.clear_length = std::max(0.0, b.length - guard);
  }

  // the box of the sensor and all beam ends (clamped to the grid) holds every touched cell
  auto clamp_cell = [&](const Vec2& q) {
    return Cell{std::clamp(static_cast<int>(std::floor(q.x())), 0, width_ - 1),
                std::clamp(static_cast<int>(std::floor(q.y())), 0, height_ - 1)};
  };
  for (const Beam& b : beams) {
    if (!b.valid) continue;
    grow_observed(clamp_cell(start));
    grow_observed(clamp_cell(b.end));
  }

  // returns first, so that no beam of this scan clears a cell another beam saw occupied
  int learned = 0;
  for (const Beam& b : beams) {
    if (!b.valid || !b.hit) continue;
    const Cell c{static_cast<int>(std::floor(b.end.x())), static_cast<int>(std::floor(b.end.y()))};
    if (!contains(c)) continue;
    Tile& t = tiles_.at(tile_index(c));
    const int k = in_tile(c);
    if (t.mark[k] == hit_mark) continue;
    learned += update(t, k, config_.hit_log_odds, hit_mark);
  }

  // then clear the cells each beam crossed up to its guarded stretch (all the way for beams
  // without a return)
  for (const Beam& b : beams) {
    if (!b.valid || !(b.clear_length > 0)) continue;
    const Vec2 clear_end = start + b.direction_O * (b.clear_length / resolution_);
    trace(start, clear_end, [&](int x, int y) {
      const Cell c{x, y};
      if (!contains(c)) return false;
      Tile& t = tiles_.at(tile_index(c));
      const int k = in_tile(c);
      if (t.mark[k] != hit_mark && t.mark[k] != clear_mark) learned += update(t, k, config_.miss_log_odds, clear_mark);
      return true;
    });
  }
  return learned;
}

msg::OccupancyGrid OccupancyMapper::to_message(const std::string& frame_id, SimTime stamp) const {
  msg::OccupancyGrid m;
  m.header = {stamp, frame_id};
  m.map_load_time = stamp;
  m.resolution = static_cast<float>(resolution_);
  m.width = static_cast<std::uint32_t>(width_);
  m.height = static_cast<std::uint32_t>(height_);
  m.origin.p = Vec3(origin_O_.x(), origin_O_.y(), 0.0);
  m.data.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), -1);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const float l = log_odds({x, y});
      if (state_of(l) == CellState::unknown) continue;
      const double p = 1.0 / (1.0 + std::exp(-static_cast<double>(l)));
      m.data[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] =
          static_cast<std::int8_t>(std::lround(100.0 * p));
    }
  }
  return m;
}

}  // namespace rescuesim::autonomy
