#pragma once
/// Victim detection as one concept: a VictimDetector decides, at the victim-check rate, which
/// victims each robot has found. The owner of a run picks one implementation at set-up
/// (Session: thermal images when cameras render and a robot carries a thermal camera, else
/// line of sight) and hands it to the Simulation, which calls only that one.
///
/// Both implementations look through a robot's thermal camera (the last one in its spec); a
/// robot without one finds nothing. A victim counts as found once, at the first time any
/// robot finds it (VictimState::first_seen, seen_by); each robot's own first sighting is kept
/// too (VictimState::seen_at), since a robot knows only what it saw itself.

#include <string_view>
#include <vector>

#include "raycast/ray_scene.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

class VictimDetector {
 public:
  virtual ~VictimDetector() = default;
  /// How victims are found, as the run summary says it ("line of sight", "thermal images").
  virtual std::string_view name() const = 0;
  /// Called by the simulation at SimOptions::victim_check_rate with `rays` showing `state`:
  /// records in state.victims each victim first found at state.time.
  virtual void check(const World& world, State& state, const RayScene& rays) const = 0;
};

/// Geometric detection: a victim is found when one of its body parts lies inside the thermal
/// camera's frustum (hfov, aspect, min_range < depth <= max_range) and a ray from the camera to
/// that part first hits the victim itself. Needs no rendering.
class LineOfSightDetector : public VictimDetector {
 public:
  /// `robots`: per robot index, whether this detector looks for it; empty: every robot.
  explicit LineOfSightDetector(std::vector<bool> robots = {}) : robots_(std::move(robots)) {}
  std::string_view name() const override { return "line of sight"; }
  void check(const World& world, State& state, const RayScene& rays) const override;

 private:
  std::vector<bool> robots_;
};

/// Detection in the rendered thermal images: a victim is found when it shows as a warm blob
/// (victims_in_thermal_image in sensors/camera/camera.h). The blobs are searched on the render
/// thread and recorded by the camera service when it delivers each thermal frame, stamped with
/// the frame's time, so check() has nothing to do for those robots; a robot whose thermal
/// camera is not rendered (disabled) is still checked by line of sight.
class ThermalImageDetector : public VictimDetector {
 public:
  /// `rendered`: per robot index, true when its thermal camera is rendered by the camera service
  /// (RenderCameraService::detects_victims).
  explicit ThermalImageDetector(const std::vector<bool>& rendered);
  std::string_view name() const override { return "thermal images"; }
  void check(const World& world, State& state, const RayScene& rays) const override;

 private:
  LineOfSightDetector fallback_;  ///< for the robots whose thermal camera is not rendered
};

}  // namespace rescuesim
