#pragma once
/// Where a camera has looked: a flag per cell of an OccupancyMapper, set for the cells a
/// camera's horizontal fan reached, traced through the map from the camera and stopped by the
/// first occupied or unknown cell. The explorer uses it to find ground its victim camera has
/// not yet seen: the laser maps a corridor long before a narrow camera has looked into every
/// dead end off it, and victims are found only by the camera.
///
/// Traced by hand on the mapper's cells rather than through the ray scene: the explorer knows
/// only its own map (it runs unchanged inside a ROS node), and a fan of 2-D beams over a
/// grid is a few lines of stepping.

#include <cstdint>
#include <vector>

#include "autonomy/occupancy_grid.h"

namespace rescuesim::autonomy {

/// A camera's view as the explorer models it: a horizontal fan.
struct CameraFan {
  double hfov = 57.0 * 3.141592653589793 / 180;  ///< rad, horizontal field of view
  double range = 4.0;                          ///< m, how far it counts as looked
  double beam_spacing = 0.5 * 3.141592653589793 / 180;  ///< rad between traced beams
  /// m; unknown cells this near the camera do not stop a beam (the robot's own footprint, which
  /// its laser does not see)
  double near = 0.0;
};

/// The cells a camera has looked at, on the cells of one OccupancyMapper.
class LookCoverage {
 public:
  /// Traces the fan from `p_M` (m, map frame) centred on bearing `yaw` (rad, map frame): each
  /// beam marks the cells it crosses up to the fan's range, stopping after the first occupied
  /// cell (marked: the camera saw that surface) or before the first unknown one beyond `near`. Returns how
  /// many cells were marked for the first time. Nothing happens before the map has cells.
  int look(const OccupancyMapper& map, const Vec2& p_M, double yaw, const CameraFan& fan);
  /// Marks every cell whose centre lies within `radius` of `p_M` (ground the robot itself
  /// covers: nothing lies hidden under it). Returns the cells marked for the first time.
  int cover_disc(const OccupancyMapper& map, const Vec2& p_M, double radius);
  /// Marks the cells whose centre lies in the square of half-side `half` (m) around `p_M` as
  /// seen by a teammate's camera (what a teammate said over the radio). Returns how many cells
  /// were new to either kind of seeing.
  int mark_team_square(const OccupancyMapper& map, const Vec2& p_M, double half);
  /// True when this robot's camera, or a teammate's (mark_team_square), has looked at cell `c`
  /// (false outside the grid or before any look).
  bool looked(Cell c) const { return flags(c) != 0; }
  /// True when this robot's own camera has looked at cell `c`.
  bool looked_self(Cell c) const { return (flags(c) & kSelf) != 0; }
  /// True when a teammate said it has looked at cell `c`.
  bool looked_by_team(Cell c) const { return (flags(c) & kTeam) != 0; }
  /// Cells this robot's own camera has looked at so far.
  long count() const { return count_; }

 private:
  static constexpr std::uint8_t kSelf = 1, kTeam = 2;
  void fit(const OccupancyMapper& map);
  int mark(const OccupancyMapper& map, Cell c);
  std::uint8_t flags(Cell c) const;

  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> looked_;
  long count_ = 0;
};

}  // namespace rescuesim::autonomy
