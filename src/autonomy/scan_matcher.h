#pragma once
/// Scan-to-map matching: where a scan fits best on the occupancy grid built so far, searched
/// round a predicted pose (odometry placed in the map frame). A brute-force correlative search
/// (Olson 2009, "Real-time correlative scan matching") over a small window of translations
/// and headings on a smoothed likelihood field of the grid's occupied cells finds the best
/// cell-and-degree candidate; a few Gauss-Newton steps on the bilinearly interpolated field
/// (as Hector SLAM does, Kohlbrecher et al. 2011) refine it below one cell. The spread of the
/// candidates that score nearly as well as the best tells whether the fit pins the pose down:
/// in a long featureless corridor every shift along it fits equally well, and that direction
/// is reported ambiguous and left uncorrected.
///
/// Written by hand: no Debian library does 2-D scan-to-grid matching on its own (the SLAM
/// packages bring their own maps, threads and ROS). Deterministic: no threads, no randomness,
/// no clock; candidates are visited in a fixed order and ties go to the one nearest the prediction.

#include <vector>

#include "autonomy/occupancy_grid.h"
#include "core/pose.h"

namespace rescuesim::autonomy {

/// Settings of a ScanMatcher.
struct ScanMatcherConfig {
  double search_xy = 0.2;           ///< m, half width of the square window of translations (searched in steps of one cell)
  double search_yaw = 5 * M_PI / 180;  ///< rad, half width of the window of headings
  double yaw_step = 1 * M_PI / 180;    ///< rad between two headings of the search
  double field_sigma = 0.06;        ///< m, width of the Gaussian round each occupied cell in the likelihood field
  double field_reach = 0.25;        ///< m, distance beyond which the field is zero
  int max_points = 180;             ///< the scan is thinned evenly to at most this many points
  int min_points = 30;              ///< fewer points than this: no match
  double max_range = 12.0;          ///< m, points farther than this from base_link are not used (far returns magnify heading error)
  double min_score = 0.45;          ///< mean field value (0..1) over the points below which the match is rejected
  double near_best = 0.97;          ///< candidates scoring at least this fraction of the best count as near-best
  /// m, standard deviation of the near-best candidates' positions along a direction above
  /// which that direction is ambiguous (not pinned down by the scan)
  double max_spread = 0.06;
  int refine_iterations = 6;        ///< Gauss-Newton steps after the search
  /// the likelihood field is rebuilt every this many matches (1: every match, on the grid as
  /// it is; more: cheaper, on a grid up to that many updates old) ...
  int field_refresh = 1;
  double field_margin = 2.0;        ///< m ... over the box the points need widened by this much (with field_refresh > 1)
};

/// What a match concluded.
enum class MatchVerdict {
  good,       ///< the pose is pinned down: use the match
  ambiguous,  ///< one direction is unconstrained (a corridor): only the heading and the other direction are corrected
  rejected,   ///< no map, too few points, a poor fit or nothing pinned down: keep the prediction
};

/// The result of matching one scan.
struct ScanMatch {
  MatchVerdict verdict = MatchVerdict::rejected;
  Pose2 X_MB_predicted;     ///< the prediction the search started from (map frame)
  Pose2 X_MB_best;          ///< the best fit found (map frame), whatever the verdict
  Pose2 X_MB;               ///< the pose to use: the best fit, the prediction corrected only where pinned down, or the prediction
  double score = 0;         ///< mean field value (0..1) of the points at X_MB_best
  double predicted_score = 0;  ///< the same at the prediction
  int points = 0;           ///< points used
  double spread_major = 0;  ///< m, standard deviation of the near-best candidates along their widest direction
  double spread_minor = 0;  ///< m, the same across it
  Vec2 major_axis_M = Vec2::UnitX();  ///< unit, map frame: the widest direction of the near-best candidates
};

/// A likelihood field of a grid's occupied cells: exp(-d^2 / (2 sigma^2)) with d the distance
/// (m) from a cell's centre to the nearest occupied cell's centre (chamfer distance, exact
/// along rows, columns and diagonals), zero beyond `reach`. Covers a box of the grid's cells.
class LikelihoodField {
 public:
  /// Builds the field over the grid's cells in [lo, hi] (inclusive, clipped to the grid);
  /// occupied cells up to `reach` outside the box count too.
  void build(const OccupancyMapper& grid, Cell lo, Cell hi, double sigma, double reach);
  /// True when the field was built on a grid of the same geometry as `grid` and its box holds
  /// the cells [lo, hi] (clipped to the grid).
  bool covers(const OccupancyMapper& grid, Cell lo, Cell hi) const;
  /// The field at cell `c` (grid coordinates), zero outside the box.
  double at(Cell c) const {
    const int x = c.x - lo_.x, y = c.y - lo_.y;
    return x >= 0 && y >= 0 && x < w_ && y < h_ ? values_[static_cast<std::size_t>(y * w_ + x)] : 0.0;
  }
  /// The field bilinearly interpolated between cell centres at `p_M` (m, map frame), and its
  /// gradient (per m) in `grad_M` when given.
  double interpolate(const Vec2& p_M, Vec2* grad_M = nullptr) const;

 private:
  Cell lo_{0, 0};
  int w_ = 0, h_ = 0;
  int grid_w_ = 0, grid_h_ = 0;  // the grid's size when built
  Vec2 origin_M_ = Vec2::Zero();  // lower-left corner of the grid's cell (0, 0)
  double resolution_ = 1;
  std::vector<float> values_;
};

/// Matches scans against an occupancy grid.
class ScanMatcher {
 public:
  explicit ScanMatcher(ScanMatcherConfig config = {});

  /// Where points `p_B` (m, base_link; a scan's returns) fit best on `grid` round the
  /// predicted pose `X_MB_predicted` (base_link in the grid's frame). The likelihood field is
  /// rebuilt over the part of the grid the points can reach.
  ScanMatch match(const OccupancyMapper& grid, const std::vector<Vec2>& p_B, const Pose2& X_MB_predicted);

  /// The field of the last match.
  const LikelihoodField& field() const { return field_; }
  const ScanMatcherConfig& config() const { return config_; }

 private:
  double mean_field(const std::vector<Vec2>& p_B, const Pose2& X_MB) const;

  ScanMatcherConfig config_;
  LikelihoodField field_;
  int field_uses_ = 0;  // matches on the field since it was built
};

}  // namespace rescuesim::autonomy
