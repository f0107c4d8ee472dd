#pragma once
/// Walls between two radios, counted through the world's ray scene. World frame, metres.
///
/// A wall is a static object of the World other than the floor and victims' body parts
/// (walls, obstacles, platforms, ramps). The count for the segment p → q is the number of
/// distinct such objects it passes through: a ray is cast from p towards q, each hit is
/// stepped past by 1 mm and the ray cast again from there, until the segment's length is
/// used up. Consecutive hits on the same object (its entry and exit faces) count once.
/// Rubble (dynamic objects) and robot links are stepped through without counting. So:
/// - a segment ending inside a wall counts that wall once (its entry face), and one starting
///   inside a wall counts it once too (its exit face);
/// - a segment lying in the plane of a wall's face grazes it: the ray tracer reports no hit
///   for a ray in the plane of a triangle, so the wall is not counted (tested);
/// - hits closer than 1 mm to each other on different objects (walls touching) are each seen
///   only if the tracer reports both; walls thinner than 1 mm may be missed.
/// Each cast costs one Embree ray; a segment through k objects costs about 2k + 1 rays.

#include <span>
#include <vector>

#include "core/pose.h"
#include "raycast/ray_scene.h"
#include "world/world.h"

namespace rescuesim {

/// One segment between two radio positions (world frame, m).
struct RadioSegment {
  Vec3 p_W = Vec3::Zero();
  Vec3 q_W = Vec3::Zero();
};

/// Counts walls between radio positions in one World and its RayScene (which must have been
/// built from that World). Holds references: both must outlive it.
class WallCounter {
 public:
  WallCounter(const RayScene& scene, const World& world);

  /// Walls on the segment p → q (see the file comment), counting stops at `cap` (a count of
  /// `cap` means "cap or more"). Non-finite ends give 0.
  int count(const Vec3& p_W, const Vec3& q_W, int cap = 1 << 20) const;

  /// count() for many segments at once (batched casts; the answers are the same as one by
  /// one and do not depend on the thread count). counts.size() must equal segments.size().
  void count(std::span<const RadioSegment> segments, std::span<int> counts, int cap = 1 << 20) const;

  /// True when static object `index` (World::statics) counts as a wall.
  bool is_wall(int index) const;

 private:
  const RayScene& scene_;
  std::vector<bool> is_wall_;  ///< per World::statics index
};

}  // namespace rescuesim
