#pragma once
/// WorldSpec: the world as a user authors it (from SVG, the maze generator or YAML). Plain
/// data with no behaviour and no physics or graphics types; `validate()` checks it and the
/// simulation compiles it into a World. Frames: world x east, y north, z up (REP-103), metres;
/// the floor is the plane z = 0. Drawn worlds are 2.5-D (outlines extruded from the floor);
/// worlds from model files (SDF) add solids and bodies of any shape at any 3-D pose.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/polygon.h"
#include "core/pose.h"
#include "world/geometry.h"

namespace rescuesim {

/// Surface properties shared by geometry of one kind: looks, heat and contact.
struct MaterialSpec {
  std::string name;                          ///< unique key, referenced by geometry
  Vec3 color{0.5, 0.5, 0.5};                 ///< base colour, sRGB components in [0, 1]
  double roughness = 0.8;                    ///< 0 mirror-like .. 1 matte
  std::string texture = "none";              ///< procedural pattern: none, tiles, concrete, wood, fabric, skin
  double temperature = -1;                   ///< surface temperature (K); < 0 means "at ambient"
  double emissivity = 0.95;                  ///< thermal emissivity in (0, 1]
  double friction = 0.8;                     ///< Coulomb friction coefficient
  double restitution = 0.05;                 ///< bounce, 0..1
};

/// A straight wall: a box of `thickness` centred on segment a→b, standing on the floor.
struct WallSpec {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  ///< centre line end points (m)
  double thickness = 0.05;                   ///< m
  double height = 1.0;                       ///< m
  std::string material = "wall";
  SourceRef source;
};

/// A static obstacle: a simple polygon extruded from the floor to `height`.
struct BlockSpec {
  Polygon2 outline;  ///< counter-clockwise, m
  double height = 1.0;
  std::string material = "obstacle";
  SourceRef source;
};

/// A raised area: a flat platform `height` above the floor with ramps down to the floor on
/// chosen edges. Edge i runs from outline[i] to outline[i+1]; its ramp extends outward by
/// `ramp_length`.
struct RaisedAreaSpec {
  Polygon2 outline;             ///< platform top, counter-clockwise, m
  double height = 0.12;         ///< m
  std::vector<int> ramp_edges;  ///< indices of edges that have a ramp
  double ramp_length = 0.5;     ///< horizontal run of each ramp (m)
  std::string material = "raised";
  SourceRef source;
};

/// A loose obstacle (rubble): a dynamic box or upright cylinder resting on the ground.
struct RubbleSpec {
  enum class Shape { box, cylinder };
  Shape shape = Shape::box;
  Pose2 pose;                   ///< centre on the ground plane and heading
  Vec3 size{0.2, 0.2, 0.1};     ///< box: length x, width y, height z; cylinder: diameter, diameter, height
  double mass = 2.0;            ///< kg
  std::string material = "rubble";
  SourceRef source;
};

/// A generated terrain element of the response-robot test methods (NIST/ASTM E54.08, as in the
/// RoboCup Rescue lanes; docs/terrain.md), built as static solids over a rectangular footprint.
/// In the element's frame x runs along the direction of travel, from -length/2 to +length/2.
struct TerrainSpec {
  enum class Kind { stepfield, stairs, crossing_ramps, curb, hurdle, gap };
  Kind kind = Kind::stepfield;
  std::string name;
  Pose2 pose;                 ///< footprint centre; yaw = direction of travel
  double length = 2.4;        ///< footprint along travel (m)
  double width = 1.2;         ///< footprint across travel (m); a lane is 1.1-1.2 m
  double height = 0.15;       ///< curb, hurdle: its height; gap: the decks'; stairs: the total rise (m)
  double post = 0.1;          ///< stepfield: post size and pitch (m)
  bool half_cubic = true;     ///< stepfield: heights of 1-4 half posts (else 1-4 whole posts)
  double riser = 0.2;         ///< stairs: step height (m)
  double angle = 40;          ///< stairs: slope; crossing ramps: each ramp's slope (degrees)
  double gap = 0.3;           ///< gap: the opening between the decks (m)
  double thickness = 0.1;     ///< hurdle: along travel (m)
  std::uint64_t seed = 1;     ///< stepfield: the post heights
  std::string material = "raised";
  SourceRef source;

  /// The defaults of a kind: stepfield 2.4 x 1.2 m, half-cubic 10 cm posts; stairs 40 deg,
  /// 20 cm risers, 0.8 m rise; crossing ramps 15 deg; curb 15 cm; hurdle 20 cm; gap 30 cm
  /// between 20 cm decks.
  static TerrainSpec defaults(Kind kind);
  /// The kind's name in files ("stepfield", "stairs", "crossing-ramps", "curb", "hurdle", "gap").
  static const char* kind_name(Kind kind);
  /// Footprint corners in the world, counter-clockwise.
  Polygon2 outline() const;
};

/// A volume of smoke or dust (docs/environment.md): a footprint polygon extruded from `bottom`
/// to `bottom + height`, filled with particles that scatter and absorb. `density` is the
/// extinction coefficient for visible light (1/m): light crossing L metres of it keeps
/// exp(-density * L) of its power, and the eye sees about 3 / density metres (Koschmieder's
/// visibility). The other sensing bands' coefficients follow from it (world/media.h). The
/// footprint may grow outward and drift with sim time t: at t its edges have moved out by
/// growth * t and the whole has moved by drift * t (a pure function of t).
struct MediumSpec {
  enum class Kind { smoke, dust };
  Kind kind = Kind::smoke;
  std::string name;
  Polygon2 outline;             ///< footprint at t = 0, counter-clockwise, m
  double density = 0.5;         ///< visible-light extinction coefficient (1/m)
  double bottom = 0;            ///< m above the floor
  double height = 2.0;          ///< m, from bottom up
  double growth = 0;            ///< m/s each edge moves outward
  Vec2 drift = Vec2::Zero();    ///< m/s the footprint moves
  SourceRef source;

  /// The kind's name in files ("smoke", "dust").
  static const char* kind_name(Kind kind);
};

/// A patch of floor of another material (docs/terrain.md, "Ground materials"): sand, wet tiles
/// and the like, flush with the floor. It changes the friction of whatever touches the floor
/// inside its footprint, and how the floor looks there; it adds no solid (nothing to catch on).
/// Ground areas must not overlap, so every point of the floor has one material.
struct GroundAreaSpec {
  std::string name;
  Polygon2 outline;             ///< footprint, counter-clockwise, m
  std::string material;         ///< a material name (required; e.g. concrete, wood, sand, wet_tiles)
  SourceRef source;
};

/// A victim lying or sitting on the floor; the thermal camera sees skin warmer than clothes.
struct VictimSpec {
  enum class Posture { lying, sitting };
  std::string name;
  Pose2 pose;                         ///< body centre; yaw points from feet to head
  Posture posture = Posture::lying;
  double length = 1.6;                ///< head-to-feet extent when lying (m)
  double width = 0.45;                ///< shoulder width (m)
  double skin_temperature = 307.15;   ///< exposed skin surface (K)
  double clothes_temperature = 301.15;  ///< clothed body surface (K)
  /// true: the body is rescuesim's human figure built at `pose`; false: the body is the
  /// WorldSpec::solids whose `victim` names this victim (an SDF model named victim*).
  bool figure = true;
  SourceRef source;
};

/// A fixed solid at any 3-D pose: one collision shape of a model read from a model file (an
/// SDF <collision>; its link's <visual> gives the colour). It collides, is seen by the ray
/// sensors and is drawn. Meshes stay triangle meshes, so physics (a BVH) and the ray sensors
/// (the same triangles) see the exact surface.
struct SolidSpec {
  std::string name;                  ///< "model::link::collision"
  Geometry geometry;                 ///< in the solid's frame
  Pose3 X_WS;                        ///< solid frame in the world
  std::string material = "obstacle";
  double temperature = -1;           ///< K; < 0: the material's
  std::string victim;                ///< name of the victim this solid is the body of, or ""
  SourceRef source;
};

/// A loose rigid body of one shape from a model file (a non-static SDF link without joints).
struct BodySpec {
  std::string name;                  ///< "model::link"
  Geometry geometry;                 ///< collision shape in the body frame
  Pose3 X_WB;                        ///< body frame in the world: origin at the centre of mass, axes the principal axes
  double mass = 1.0;                 ///< kg
  Vec3 inertia{0.01, 0.01, 0.01};    ///< principal moments (kg m^2)
  std::string material = "rubble";
  SourceRef source;
};

/// A light source for rendering.
struct LightSpec {
  enum class Type { directional, point, spot };
  Type type = Type::directional;
  std::string name;           ///< as the source named it ("" for generated lights)
  Vec3 position{0, 0, 3};     ///< point and spot lights (m)
  Vec3 direction{-0.3, -0.2, -1.0};  ///< directional and spot lights: direction the light travels
  double range = 0;           ///< point and spot: distance where the light ends (m); 0 = unlimited
  double spot_angle = 0;      ///< spot: half-angle of the outer cone (rad)
  Vec3 color{1, 1, 1};
  double intensity = 1.0;
  bool casts_shadows = true;
};

/// Where a robot starts and what it is.
struct RobotPlacement {
  std::string name = "robot";
  std::string model = "rescue_robot";
  Pose2 start;
  SourceRef source;
  /// Height of the start above the floor (m), for starts on raised ground (a model file's
  /// pose); the robot is lowered until its wheels touch z = height.
  double height = 0;
};

/// The authored world.
struct WorldSpec {
  std::string name;                 ///< short name for outputs
  std::string source_file;          ///< where it came from, "" when generated in memory
  std::uint64_t seed = 0;           ///< seed of a generated world (recorded in outputs)
  Vec2 floor_min = Vec2::Zero();    ///< floor rectangle, south-west corner (m)
  Vec2 floor_max{10, 10};           ///< north-east corner (m)
  std::string floor_material = "floor";
  double ambient_temperature = 293.15;  ///< K: air and surfaces without their own temperature
  double gravity = 9.81;            ///< m/s^2, pointing down -z
  double physics_dt = 0;            ///< s: the file's physics step (an SDF <max_step_size>); 0 = the scenario's

  std::vector<MaterialSpec> materials;  ///< in declaration order; names unique
  std::vector<WallSpec> walls;
  std::vector<BlockSpec> blocks;
  std::vector<RaisedAreaSpec> raised_areas;
  std::vector<TerrainSpec> terrain;
  std::vector<RubbleSpec> rubble;
  std::vector<VictimSpec> victims;
  std::vector<LightSpec> lights;
  /// Daylight: the ambient light (sky and bounce) as a fraction of a bright overcast day's, 0 for
  /// none; and the sun: false drops the lights the SVG and maze loaders make up (unnamed ones: a
  /// sun, a maze's two overhead lamps) and the renderer's default sun (docs/environment.md).
  double ambient_light = 1.0;
  bool sun = true;
  std::vector<RobotPlacement> robots;
  std::vector<SolidSpec> solids;    ///< fixed 3-D solids (from SDF)
  std::vector<BodySpec> bodies;     ///< loose rigid bodies (from SDF)
  std::vector<MediumSpec> media;    ///< smoke and dust volumes (no solids; only what sensors see through)
  std::vector<GroundAreaSpec> ground;  ///< floor patches of other materials (no solids; friction and looks)
  std::map<std::string, std::string> metadata;  ///< generator parameters and the like

  /// The material with this name, or nullptr.
  const MaterialSpec* find_material(const std::string& name) const;
  /// Adds or replaces a material by name.
  void set_material(const MaterialSpec& m);
  /// Footprint of a wall as a polygon (m).
  static Polygon2 wall_outline(const WallSpec& w);
  /// Footprint of a raised area's ramp on edge i (a quadrilateral, m).
  static Polygon2 ramp_outline(const RaisedAreaSpec& r, int edge);
  /// Footprint of a victim (m).
  static Polygon2 victim_outline(const VictimSpec& v);
  /// Bounding box of everything in the world.
  Box2 content_bounds() const;
};

/// Materials every world starts with: floor, wall, obstacle, raised, rubble, victim_skin,
/// victim_clothes, robot_body, robot_wheel, robot_sensor, then the ground materials concrete,
/// wood, sand and wet_tiles (in this order; new ones are added at the end).
std::vector<MaterialSpec> default_materials();

/// Options for validation.
struct ValidateOptions {
  double robot_radius = 0.40;     ///< clearance a start pose needs from walls and obstacles (m)
  double max_extent = 10000.0;    ///< largest sane world size (m)
};

/// Checks a WorldSpec and returns every problem found (errors and warnings), each naming the
/// element it concerns. Catches non-positive sizes, non-finite numbers, empty worlds, start
/// poses overlapping walls or obstacles, victims inside walls and unknown materials.
Diagnostics validate(const WorldSpec& world, const ValidateOptions& options = {});

}  // namespace rescuesim
