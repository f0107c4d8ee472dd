#pragma once
/// World: the compiled, immutable description of a simulation — every object as a shape with a
/// pose and a material, victims as human figures, robots as placed RobotSpecs. Physics, ray
/// casting and rendering are built from it; nothing in it changes while a simulation runs (that
/// is State, in world/state.h).

#include <map>
#include <string>
#include <vector>

#include "core/index.h"  // RobotIndex, VictimIndex: the positions in robots and victims
#include "world/geometry.h"
#include "world/robot_spec.h"
#include "world/world_spec.h"

namespace rescuesim {

/// What an object is, for sensors and statistics.
enum class ObjectKind { floor, wall, obstacle, platform, ramp, victim, rubble, robot };

/// A piece of static geometry fixed in the world.
struct StaticObject {
  std::string name;
  ObjectKind kind = ObjectKind::wall;
  Geometry geometry;
  Pose3 X_WO;                 ///< shape frame in the world
  int material = 0;           ///< index into World::materials
  double temperature = -1;    ///< K; < 0: the material's (or ambient)
  VictimIndex victim;         ///< the victim a body part belongs to; invalid for everything else
};

/// A loose rigid body (rubble).
struct DynamicObject {
  std::string name;
  Geometry geometry;
  Pose3 X_WO;                 ///< initial pose of the body (centre of mass at the origin)
  double mass = 1.0;          ///< kg
  Vec3 inertia{0.01, 0.01, 0.01};  ///< principal moments (kg m^2)
  int material = 0;
  bool spawned = false;       ///< added while running (SpawnEntity); a reset of spawned entities removes it
};

/// A victim: where they are and which static parts make up their body.
struct Victim {
  std::string name;
  Pose2 pose;
  VictimSpec::Posture posture = VictimSpec::Posture::lying;
  std::vector<int> parts;     ///< indices into World::statics
  Vec3 centre = Vec3::Zero(); ///< centre of the body (m), for "seen" checks
  double skin_temperature = 307.15, clothes_temperature = 301.15;
};

/// A floor patch of another material (WorldSpec::ground): no solid, only the friction of floor
/// contacts inside its footprint and the floor's look there.
struct GroundArea {
  std::string name;
  Polygon2 outline;           ///< footprint, counter-clockwise, m
  int material = 0;           ///< index into World::materials
};

/// A robot in the world.
struct RobotInstance {
  std::string name;           ///< unique, used for topic namespaces
  RobotSpec spec;
  Pose3 X_W_start;            ///< base link pose at the start
  /// Added while running (SpawnEntity): its topics and frames are always under `ns` (so the
  /// names of the robots already there never change), it has no built-in controller and is
  /// not in the mission; a reset of spawned entities removes it.
  bool spawned = false;
  std::string ns;             ///< a spawned robot's namespace, without slashes ("p3at"); empty otherwise
};

/// The compiled world.
struct World {
  std::string name;
  Box2 floor;                          ///< floor rectangle (m); the floor slab extends beyond it
  double ambient_temperature = 293.15; ///< K
  double gravity = 9.81;               ///< m/s^2
  std::vector<MaterialSpec> materials;
  std::vector<StaticObject> statics;
  std::vector<DynamicObject> dynamics;
  std::vector<Victim> victims;
  std::vector<RobotInstance> robots;
  std::vector<LightSpec> lights;
  double ambient_light = 1.0;          ///< fraction of the default ambient light (WorldSpec::ambient_light)
  bool sun = true;                     ///< a world without lights gets the default sun
  std::vector<MediumSpec> media;       ///< smoke and dust (world/media.h); empty: clear air, and no sensor pays for media
  std::vector<GroundArea> ground;      ///< floor patches of other materials; empty: the floor's material everywhere
  std::uint64_t world_seed = 0;        ///< of a generated world

  /// The robot at `r`, checked (std::out_of_range when there is none); has_robot says first.
  const RobotInstance& robot(RobotIndex r) const { return robots.at(r.slot()); }
  bool has_robot(RobotIndex r) const { return r.valid() && r.slot() < robots.size(); }
  /// The victim at `v`, checked (std::out_of_range when there is none).
  const Victim& victim(VictimIndex v) const { return victims.at(v.slot()); }
  /// Every robot's index, in order: `for (RobotIndex r : world.robot_indices())`.
  IndexRange<RobotTag> robot_indices() const { return indices<RobotTag>(robots.size()); }

  /// Index of a material by name; throws Error when it is missing.
  int material_index(const std::string& name) const;
  /// Temperature (K) of a static object's surface.
  double temperature_of(const StaticObject& o) const;
};

/// How to compile a WorldSpec.
struct CompileOptions {
  double floor_margin = 2.0;   ///< the floor slab extends this far beyond the drawn floor (m)
  double floor_thickness = 0.2;
};

/// Compiles a validated WorldSpec with the robot models it names (by model name). Robots
/// are placed at their start poses with their wheels on the ground. Throws Error for a robot
/// model that is not in `models`.
World compile_world(const WorldSpec& spec, const std::map<std::string, RobotSpec>& models, const CompileOptions& options = {});

/// A robot placed as compile_world places the scenario's robots: its base frame at `X_W` (a 2-D
/// start gives `height` 0), raised when needed so that its lowest collision point is 2 mm
/// above the floor (z = 0) rather than in it.
RobotInstance place_robot(std::string name, RobotSpec spec, const Pose3& X_W);

/// Adds the materials the world's robots name and the world lacks (after the others, so the
/// indices of those already there stay).
void add_robot_materials(World& world);

/// The body parts of a victim as (geometry, pose in the world, material name) triples: torso,
/// head, arms and legs from boxes, spheres and cylinders, lying or sitting.
struct BodyPart {
  Geometry geometry;
  Pose3 X_WP;
  bool skin = false;  ///< exposed skin (head, hands) rather than clothes
};
std::vector<BodyPart> victim_body(const VictimSpec& v);

}  // namespace rescuesim
