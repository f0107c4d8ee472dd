#pragma once
/// Odometry checked against the laser: a wedged robot whose wheels spin (or a robot rocking
/// on debris) keeps counting odometry that the scans do not bear out. Each time odometry
/// claims a motion, the new scan is compared with the previous reference scan moved as
/// odometry says; a poor fit is a misfit, and repeated misfits mean the wheels slip.
/// Featureless places (a long corridor, open space) fit any motion along them, so they are
/// never called slipping; the fit "as if the robot had stood still" is kept for diagnosis.
/// A second input, `add_motion`, compares odometry with scan matching against the map (the
/// pose the matcher put the robot at): the same windowed verdict on their disagreement.

#include <deque>

#include "core/pose.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// Settings of a SlipDetector.
struct SlipDetectorConfig {
  double min_motion = 0.3;     ///< m of odometry travel (or min_turn) before a comparison
  double min_turn = 0.4;       ///< rad of odometry turn before a comparison
  double moved_misfit = 0.2;   ///< m; a mean error per return above this is a misfit
  int window = 3;              ///< the last this many comparisons ...
  int min_misfits = 2;         ///< ... holding this many misfits mean slipping
};

/// Detects wheel slip from scans placed by odometry.
class SlipDetector {
 public:
  explicit SlipDetector(SlipDetectorConfig config = {});

  /// Adds a scan taken at sensor pose `X_OS` (laser frame in odom, from odometry). Returns
  /// true when odometry had claimed enough motion since the reference scan for a comparison
  /// (the scan then becomes the reference); false otherwise.
  bool add(const msg::LaserScan& scan, const Pose2& X_OS);

  /// Adds an odometry pose `X_OB` (base_link in odom) and the pose scan matching found for the
  /// same instant, `X_MB` (base_link in the map frame). Once odometry claims enough motion
  /// since the reference pair, the two motions are compared: a misfit when they differ by
  /// more than moved_misfit (m) or min_turn / 2 (rad). Returns true when compared (the pair
  /// then becomes the reference). Use one detector for either kind of input, not both.
  bool add_motion(const Pose2& X_OB, const Pose2& X_MB);

  /// True while at least min_misfits of the last `window` comparisons were misfits.
  bool slipping() const;
  /// True when the last comparison was a misfit.
  bool last_misfit() const { return !history_.empty() && history_.back(); }
  /// Mean error per reference return (m, each capped at 1) of the last comparison: moved as
  /// odometry says, and as if the robot had stood still (add_motion: the distance between the
  /// two motions' ends, and the distance the matched motion went).
  double moved_error() const { return moved_error_; }
  double still_error() const { return still_error_; }
  /// Forgets the reference and the history (the next scan becomes the reference).
  void reset();

 private:
  SlipDetectorConfig config_;
  msg::LaserScan reference_;
  Pose2 X_OS_reference_;
  bool have_reference_ = false;
  Pose2 X_OB_reference_, X_MB_reference_;  // add_motion's reference pair
  void record(bool misfit);
  std::deque<bool> history_;  // misfit per comparison, oldest first
  double moved_error_ = 0, still_error_ = 0;
};

}  // namespace rescuesim::autonomy
