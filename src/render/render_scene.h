#pragma once
/// RenderScene: what a renderer draws, built from a World and moved by a State, with no graphics
/// types — triangle meshes with normals and texture coordinates, materials in linear colour,
/// items placing a mesh with a material in the world, lights and the ambient temperature.
/// World frame (x east, y north, z up), metres, kelvin.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// A triangle mesh for rendering, in its item's frame: flat faces have their own vertices, round
/// surfaces shared smooth normals. Texture coordinates are in metres along the surface, so
/// procedural patterns (0.5 m floor tiles, wood grain) have their real size on every object.
struct RenderMesh {
  std::vector<Eigen::Vector3f> positions;  ///< m, item frame
  std::vector<Eigen::Vector3f> normals;    ///< unit outward normals, item frame
  std::vector<Eigen::Vector2f> uvs;        ///< surface coordinates (m)
  std::vector<std::uint32_t> indices;      ///< counter-clockwise (outward-facing) triangles, 3 per triangle
};

/// Procedural surface pattern drawn by the renderer.
enum class TextureKind { none, tiles, concrete, wood, fabric, skin };

/// Looks and heat of a surface.
struct RenderMaterial {
  std::string name;
  Vec3 albedo{0.2, 0.2, 0.2};       ///< linear reflectance per channel (from MaterialSpec::color, sRGB)
  double roughness = 0.8;           ///< 0 mirror-like .. 1 matte
  TextureKind texture = TextureKind::none;
  /// an image drawn instead of the albedo (a mesh file's texture), at the mesh's own texture
  /// coordinates (0..1, v up) rather than metric ones; "" for none
  std::string image;
  double temperature = 293.15;      ///< K: the material's own, or the ambient temperature
  double emissivity = 0.95;         ///< in (0, 1]
};

/// One mesh drawn with one material at one pose.
struct RenderItem {
  enum class Source { static_object, dynamic_object, robot_link };
  Source source = Source::static_object;
  int index = -1;           ///< World::statics or World::dynamics index, or the link index; -1 for a floor patch (World::ground)
  RobotIndex robot;         ///< World::robots index for robot links, else -1
  int mesh = 0;             ///< index into RenderScene::meshes
  int material = 0;         ///< index into RenderScene::materials
  double temperature = 0;   ///< K, surface temperature (object's own, else material's, else ambient)
  Pose3 X_PI;               ///< item frame in its parent (the dynamic body or robot link); identity for statics
  Pose3 X_WI;               ///< item frame in the world, current
  bool casts_shadows = true;  ///< false for the floor slab: nothing lies below it
  bool movable() const { return source != Source::static_object; }
};

/// A light: directional (the sun), point, or spot (a point light with a cone: a robot's lamp).
struct RenderLight {
  bool directional = true;
  Vec3 direction{-0.3, -0.2, -1.0};  ///< directional and spot: unit direction the light travels, world frame
  Vec3 position{0, 0, 3};            ///< point and spot: world frame (m)
  Vec3 color{1, 1, 1};               ///< linear colour times intensity
  bool casts_shadows = true;         ///< directional only: the first such light gets the shadow map
  bool spot = false;                 ///< point lights: lit only inside a cone around `direction`
  double cone = 0;                   ///< spot: half-angle of the cone's edge (rad)
  double inner_cone = 0;             ///< spot: half-angle of the fully lit core (rad), < cone
  double range = 0;                  ///< point and spot: distance where the light has faded out (m); 0 = unlimited
};

/// A robot's lamp (RobotSpec::lights): where it is, and the light it gives when on.
struct RenderLamp {
  RobotIndex robot;     ///< World::robots index
  int link = -1;        ///< link index
  Pose3 X_LF;           ///< lamp frame in the link (x: where it shines)
  RenderLight light;    ///< a spot light, posed by update_render_scene
};

/// Everything a renderer needs; items keep World order (statics, floor patches, then rubble, then robot links).
struct RenderScene {
  std::vector<RenderMesh> meshes;
  std::vector<RenderMaterial> materials;
  std::vector<RenderItem> items;
  /// World::lights (or one default sun when it has none and World::sun), then the lamps of the
  /// robots whose lights are on (update_render_scene); renderers use the first 8
  std::vector<RenderLight> lights;
  std::size_t world_lights = 0;              ///< how many of `lights` are the world's
  std::vector<RenderLamp> lamps;             ///< every robot lamp, on or off
  double ambient_light = 1.0;                ///< World::ambient_light: scales the ambient and fill light and the sky
  double ambient_temperature = 293.15;       ///< K, also what a thermal camera sees where nothing is
  Vec3 sky_color{0.62, 0.70, 0.80};          ///< background, sRGB in [0, 1]
  std::vector<MediumSpec> media;             ///< World::media: smoke and dust the cameras look through
  double time = 0;                           ///< s, sim time of the poses (media grow and drift with it)

  /// Triangles of every item (each mesh counted once per item that draws it).
  std::size_t triangle_count() const;
};

/// Builds the scene: statics at their World poses, floor patches (World::ground) as 2 mm sheets on
/// the floor after them, rubble at World::dynamics[i].X_WO, robots at
/// their start poses with joints at their initial positions. Link shapes whose material the
/// world does not have are drawn in "robot_body" (or grey).
RenderScene build_render_scene(const World& world);

/// Moves rubble to State::dynamics[i].X_WB and robot link shapes to
/// State::robots[r].X_WL[l] * X_LG, sets the scene's time to the State's, and puts the lamps
/// of robots whose lights are on (RobotState::lights_on) after the world's lights. Throws Error
/// when the State does not match the scene's World (counts of rubble, robots or links differ).
void update_render_scene(RenderScene& scene, const State& state);

/// Linear value of one sRGB component in [0, 1].
double srgb_to_linear(double c);
/// The sRGB encoding of a linear value (clamped to [0, 1]).
double linear_to_srgb(double c);

/// The render mesh of a geometry in its own frame (boxes, cylinders and spheres with smooth or
/// per-face normals and metric texture coordinates; convex and mesh shapes flat-shaded, a mesh
/// with an image at that image's texture coordinates).
RenderMesh render_mesh_of(const Geometry& g);

}  // namespace rescuesim
