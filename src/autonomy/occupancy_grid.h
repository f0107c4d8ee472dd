#pragma once
/// Occupancy mapping from planar laser scans: a fixed-size log-odds grid in the odom frame,
/// updated by tracing every beam through the cells it crosses (free) up to its return
/// (occupied). Cells are indexed row-major from the grid's lower-left corner, as in
/// nav_msgs/OccupancyGrid. The cells are stored in tiles of 32 x 32 allocated when a scan
/// first touches them, so a map costs memory in proportion to the ground it has seen, not to
/// its box (a 40 m box is 5 MB whole; a robot that has seen one room of it holds a few tiles).

#include <compare>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/sim_time.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// Integer cell coordinates: column `x` and row `y` counted from the grid's origin corner.
struct Cell {
  int x = 0, y = 0;
  auto operator<=>(const Cell&) const = default;
};

/// What a cell is believed to hold.
enum class CellState : std::int8_t { unknown, free, occupied };

/// Settings of an OccupancyMapper. Log-odds are natural-log odds of occupancy.
struct OccupancyMapperConfig {
  double resolution = 0.05;       ///< m per cell side
  /// Size of the mapped box (m). Zero means "auto": a square of side `auto_size` centred on
  /// the first sensor pose integrated.
  Vec2 size = Vec2::Zero();
  Vec2 origin_O = Vec2::Zero();   ///< lower-left corner of the box in the odom frame (m), when `size` is set
  double auto_size = 40.0;        ///< m, side of the auto-allocated square
  double inf_free_range = 4.0;    ///< m, +inf beams clear cells up to min(range_max, this)
  /// A return's beam leaves uncleared the stretch before it that runs within this many cells
  /// of the surface hit (estimated from neighbouring returns), so shallow views do not erode walls.
  double surface_guard_cells = 1.5;
  double max_surface_guard = 2.0;   ///< m, the longest such stretch
  float hit_log_odds = 0.9f;        ///< added to the cell holding a return
  float miss_log_odds = -0.4f;      ///< added to every cell a beam crosses before its return
  float min_log_odds = -2.0f;       ///< clamp, so an old belief can still be revised
  float max_log_odds = 3.5f;        ///< clamp
  float occupied_threshold = 0.5f;  ///< log-odds above this: occupied
  float free_threshold = -0.2f;     ///< log-odds below this: free (in between: unknown)
};

/// A log-odds occupancy grid in the odom frame built from laser scans.
class OccupancyMapper {
 public:
  /// A mapper with a fixed box (`config.size` non-zero) or one that allocates a square of
  /// `config.auto_size` around the first scan's sensor position. Throws rescuesim::Error on
  /// a non-positive resolution or a box too large to index.
  explicit OccupancyMapper(OccupancyMapperConfig config = {});

  /// Allocates the auto-sized square centred on `p_O` (m, odom frame); no-op when allocated.
  void allocate_around(const Vec2& p_O);
  /// True once the grid has cells (always for a fixed box).
  bool allocated() const { return width_ > 0; }

  /// Adds one scan taken from sensor pose `X_OS` (laser frame in the odom frame at the scan's
  /// stamp). REP-117: finite ranges in [range_min, range_max) clear the cells before the
  /// return (but for the guarded stretch next to the surface, see surface_guard_cells) and
  /// mark the return's cell occupied (a return exactly on a cell border counts in the cell
  /// beyond it, inside the obstacle); ranges >= range_max clear up to range_max;
  /// +inf clears up to min(range_max, inf_free_range); -inf, NaN and finite ranges below
  /// range_min are ignored. Each cell is updated at most once per scan, and a cell holding a
  /// return in this scan is not cleared by another beam of it. Returns how many cells this
  /// scan observed for the first time, a measure of how much new ground it covered.
  int integrate(const msg::LaserScan& scan, const Pose2& X_OS);

  /// The grid as nav_msgs/OccupancyGrid: row-major from `origin`, -1 unknown, else the
  /// occupancy probability in percent (0..100).
  msg::OccupancyGrid to_message(const std::string& frame_id, SimTime stamp) const;

  /// The believed state of a cell inside the grid.
  CellState state(Cell c) const { return state_of(log_odds(c)); }
  bool is_free(Cell c) const { return state(c) == CellState::free; }
  bool is_occupied(Cell c) const { return state(c) == CellState::occupied; }
  bool is_unknown(Cell c) const { return state(c) == CellState::unknown; }
  /// Log-odds of a cell inside the grid (0 = never observed).
  float log_odds(Cell c) const {
    const Tile* t = tiles_[tile_index(c)].get();
    return t ? t->log_odds[in_tile(c)] : 0.0f;
  }
  /// Sets a cell to a firm belief (for known maps and tests): the clamp value of its state.
  void set_state(Cell c, CellState s);

  /// True when `c` lies inside the grid.
  bool contains(Cell c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  /// The cell holding point `p_O` (m, odom frame), or nothing outside the grid.
  std::optional<Cell> world_to_cell(const Vec2& p_O) const;
  /// The centre of cell `c` in the odom frame (m); any integer cell, inside the grid or not.
  Vec2 cell_to_world(Cell c) const {
    return origin_O_ + Vec2((c.x + 0.5) * resolution_, (c.y + 0.5) * resolution_);
  }
  /// Row-major index of a cell inside the grid.
  int index(Cell c) const { return c.y * width_ + c.x; }
  /// The cell at a row-major index.
  Cell cell_at(int i) const { return {i % width_, i / width_}; }

  int width() const { return width_; }    ///< cells along x
  int height() const { return height_; }  ///< cells along y
  double resolution() const { return resolution_; }  ///< m per cell side
  const Vec2& origin() const { return origin_O_; }   ///< lower-left corner of cell (0, 0), odom frame (m)

  /// The smallest cell box (inclusive corners) holding every cell ever observed or set;
  /// nothing before the first observation. Planners limit their work to it.
  std::optional<std::pair<Cell, Cell>> observed_box() const;

  /// Bytes the cells take: the tiles allocated so far (8 KiB each) and their index.
  std::size_t cell_bytes() const;

 private:
  static constexpr int kTileBits = 5, kTileSide = 1 << kTileBits, kTileCells = kTileSide * kTileSide;
  /// 32 x 32 cells, row-major: their log-odds and the last scan that touched each (2n: hit,
  /// 2n + 1: cleared, 1: set by set_state, 0: never).
  struct Tile {
    float log_odds[kTileCells] = {};
    std::uint32_t mark[kTileCells] = {};
  };
  /// The tiles, row-major over the grid; null until a cell of it is first written. Copies copy
  /// the tiles (an Explorer is copied by snapshots).
  class Tiles {
   public:
    Tiles() = default;
    explicit Tiles(std::size_t n) : t_(n) {}
    Tiles(const Tiles& o) : t_(o.t_.size()) {
      for (std::size_t i = 0; i < t_.size(); ++i) {
        if (o.t_[i]) t_[i] = std::make_unique<Tile>(*o.t_[i]);
      }
    }
    Tiles& operator=(const Tiles& o) {
      if (this != &o) *this = Tiles(o);
      return *this;
    }
    Tiles(Tiles&&) noexcept = default;
    Tiles& operator=(Tiles&&) noexcept = default;
    const std::unique_ptr<Tile>& operator[](std::size_t i) const { return t_[i]; }
    Tile& at(std::size_t i) {
      if (!t_[i]) t_[i] = std::make_unique<Tile>();
      return *t_[i];
    }
    std::size_t size() const { return t_.size(); }

   private:
    std::vector<std::unique_ptr<Tile>> t_;
  };
  std::size_t tile_index(Cell c) const {
    return static_cast<std::size_t>(c.y >> kTileBits) * static_cast<std::size_t>(tiles_x_) + static_cast<std::size_t>(c.x >> kTileBits);
  }
  static int in_tile(Cell c) { return ((c.y & (kTileSide - 1)) << kTileBits) | (c.x & (kTileSide - 1)); }
  CellState state_of(float l) const {
    return l > config_.occupied_threshold ? CellState::occupied
                                          : (l < config_.free_threshold ? CellState::free : CellState::unknown);
  }
  void allocate(const Vec2& origin_O, int width, int height);
  void grow_observed(Cell c);
  // one update of a cell (slot k of tile t) for the current scan; returns 1 on the cell's
  // first observation
  int update(Tile& t, int k, float delta, std::uint32_t mark);

  OccupancyMapperConfig config_;
  double resolution_;
  Vec2 origin_O_ = Vec2::Zero();
  int width_ = 0, height_ = 0;
  int tiles_x_ = 0;  // tiles per row of the grid
  Tiles tiles_;
  std::uint32_t scan_count_ = 0;
  Cell observed_min_{0, 0}, observed_max_{-1, -1};
};

}  // namespace rescuesim::autonomy
