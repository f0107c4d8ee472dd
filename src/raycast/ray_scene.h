#pragma once
/// RayScene: the world's geometry as a ray-tracing scene (Embree 3 inside, no Embree types
/// here) with rubble and robot links at the poses of a State. Lidar and sonar cast batches of
/// rays through it. World frame, metres throughout.

#include <cmath>
#include <cstddef>
#include <memory>
#include <span>

#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// A ray: origin and unit direction in the world frame, and how far it reaches (m).
struct Ray {
  Vec3 origin = Vec3::Zero();       ///< world frame (m)
  Vec3 direction = Vec3::UnitX();   ///< world frame, unit length
  float max_distance = INFINITY;    ///< m; hits beyond this are not reported
};

/// What a ray hit first.
struct RayHit {
  float distance = INFINITY;        ///< along the ray (m); +inf = no hit within max_distance
  Vec3 normal = Vec3::Zero();       ///< unit surface normal at the hit, world frame, facing the ray (dot(normal, dir) <= 0)
  /// Which kind of thing was hit.
  enum class Source { none, static_object, dynamic_object, robot_link };
  Source source = Source::none;
  int index = -1;                   ///< World::statics / World::dynamics index, or link index for robot_link
  RobotIndex robot;                 ///< World::robots index for robot_link, else -1

  bool hit() const { return source != Source::none; }
};

/// The ray-tracing scene of one World. Static objects, and the rubble bodies asleep in the
/// last update()'s State, are one flat world-frame geometry (one BVH: a ray through them visits
/// no instance); awake rubble and robot links are instances moved by update(). A body that falls
/// asleep or wakes rebuilds the flat geometry (not in worlds of more than 20 000 static
/// triangles, where rubble stays instanced). Which bodies are flat is a function of the State
/// alone, so a run and the same run restored from a snapshot trace the same triangles. Move-only. cast() and occluded() are const and may
/// run from several threads at once, but not concurrently with update().
class RayScene {
 public:
  /// Builds the scene with rubble at World::dynamics[i].X_WO and robots at their start poses
  /// (joints at their initial positions).
  explicit RayScene(const World& world);
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Moves rubble to State::dynamics[i].X_WB and every robot link to State::robots[r].X_WL[l].
  void update(const State& state);

  /// First hit of each ray; hits.size() must equal rays.size(). Links of robot `ignore_robot`
  /// (an index into World::robots; -1 = none) are invisible. Large batches run on the worker
  /// pool (core/parallel.h), isolated from the caller's other tasks. Results do not depend on
  /// the thread count, nor on a ray's place in the batch: rays are independent and traced in
  /// packets of 16. A ray whose origin or direction is not finite gets distance NaN and no hit.
  void cast(std::span<const Ray> rays, std::span<RayHit> hits, RobotIndex ignore_robot = {}) const;

  /// True when anything (walls, rubble, victims, robot links except `ignore_robot`'s) lies on
  /// the segment from `from` to `to` (world frame, m). Surfaces within 0.1 mm of `to` do not
  /// count, so a point on a surface is not occluded by that surface.
  bool occluded(const Vec3& from, const Vec3& to, RobotIndex ignore_robot = {}) const;

  /// Triangles in the scene (each rubble and link mesh counted once).
  std::size_t triangle_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rescuesim
