#pragma once
/// The world as a `foxglove.SceneUpdate` (json encoding), so Foxglove's 3D panel shows the arena
/// without a URDF: walls, obstacles, raised areas and ramps as cubes and triangle lists, victims
/// as their body parts (boxes, spheres, cylinders) with a name label that turns green once
/// found, rubble at its current poses, and each robot link's shapes in that link's frame
/// (frame-locked, so /tf moves them).
///
/// World geometry is drawn in `SceneFrames::world_frame` (e.g. "map", or a robot's "odom");
/// `X_FW` places the world in that frame.

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/sim_time.h"
#include "world/world.h"

namespace rescuesim::foxglove {

/// Where the scene is drawn.
struct SceneFrames {
  std::string world_frame = "map";                   ///< frame of the world entities
  Pose3 X_FW;                                        ///< pose of the world frame W in world_frame F
  std::vector<std::vector<std::string>> link_frames; ///< per robot, per link: its TF frame name
};

/// What moves in the scene: rubble poses and which victims were found (sampled from a State).
struct SceneState {
  std::vector<Pose3> rubble;              ///< one per World::dynamics, pose in the world
  std::vector<double> victim_found_at;    ///< one per World::victims: sim time (s) first seen, < 0 not yet
  std::vector<std::string> victim_found_by;
};

/// True when two samples would draw the same scene: rubble within 1 mm and 0.001 rad, and the
/// same victims found.
bool same_scene(const SceneState& a, const SceneState& b);

/// Builds SceneUpdate JSON texts for one world.
class SceneBuilder {
 public:
  SceneBuilder(const World& world, SceneFrames frames);

  /// Every entity: what a new subscriber needs.
  std::string full(SimTime t, const SceneState& state) const;
  /// Only the entities that move or change (rubble, victim labels).
  std::string moving(SimTime t, const SceneState& state) const;
  /// Number of static entities (walls, floor, robot links, ...).
  std::size_t static_entity_count() const { return static_count_; }

 private:
  struct Rubble {
    std::string name;
    Geometry geometry;
    Vec3 color;
  };
  struct Label {
    std::string name;
    Vec3 p_W;  ///< where the label floats (m, world)
  };
  std::string static_json_;  ///< the static entities, as a comma-separated list of JSON objects
  std::size_t static_count_ = 0;
  SceneFrames frames_;
  std::vector<Rubble> rubble_;
  std::vector<Label> victims_;

  std::string moving_entities(SimTime t, const SceneState& state) const;
};

/// The JSON Schema (draft 07) of foxglove.SceneUpdate as this builder writes it (the shape
/// Foxglove's 3D panel reads: entities with cubes, spheres, cylinders, triangles, texts, ...).
std::string scene_update_schema();

}  // namespace rescuesim::foxglove
