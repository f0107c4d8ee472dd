#pragma once
/// SDF worlds and models (Gazebo's format), read with sdformat 12 (SDF up to 1.9). A <world>
/// becomes a WorldSpec: static models become fixed solids (meshes kept as exact triangle meshes),
/// non-static models without joints become loose rigid bodies, models with joints and a
/// diff-drive plugin become robots (RobotSpec), models named victim* become victims and models
/// named robot_start* become robot starts; lights, gravity and the physics step are kept.
/// `model://` URIs resolve through the resolver's folders, then GZ_SIM_RESOURCE_PATH,
/// IGN_GAZEBO_RESOURCE_PATH and GAZEBO_MODEL_PATH (model.config honoured); `model://sun` and
/// `model://ground_plane` are built in. Errors name the file, the line and the element, and what
/// was expected; what is read but not honoured is a warning. docs/worlds.md lists what is and
/// is not supported.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "import/urdf/urdf_import.h"
#include "world/resource_uri.h"
#include "world/robot_spec.h"
#include "world/world_spec.h"

namespace rescuesim {

/// Settings of an SDF import.
struct SdfOptions {
  ResourceResolver resolver;                 ///< where model:// and relative mesh paths are found
  int hull_vertices = 64;                    ///< robot links and loose bodies: vertex budget of each convex hull
  CollisionMode collision = CollisionMode::automatic;  ///< robot links' collision meshes
  std::size_t max_triangles = 2'000'000;     ///< per mesh file; more is refused
  double max_extent = 10000.0;               ///< m: larger shapes, scales or poses are refused as absurd
  double default_density = 1000.0;           ///< kg/m^3 for links without an <inertial> (with a warning)
};

/// What one SDF model became, for `rescuesim check`.
struct SdfModelReport {
  std::string name;                          ///< scoped, "outer::inner" for nested models
  std::string becomes;  ///< "static geometry", "rigid body", "robot", "victim", "robot start", "floor", "light", "ignored"
  bool is_static = false;
  int links = 0, joints = 0, collisions = 0, visuals = 0;
  std::string source;                        ///< file:line of the <model> (or its <include>)
};

/// One mesh the importer loaded.
struct SdfMeshReport {
  std::string model, link;
  std::string uri, file;                     ///< as written, and resolved
  bool collision = false;                    ///< from a <collision> (true) or a <visual> (false)
  bool exact = false;                        ///< kept as a triangle mesh (static), else a convex hull
  int triangles = 0;
  std::string texture;                       ///< the diffuse texture the mesh file names, "" for none
  bool texture_drawn = false;                ///< found beside it and drawn by the cameras (exact meshes only)
};

/// An SDF world with everything learnt while reading it.
struct SdfWorld {
  WorldSpec spec;                            ///< solids, bodies, victims, robot starts, lights, gravity, step
  std::map<std::string, RobotSpec> robots;   ///< robot models by model name (spec.robots places them)
  Diagnostics diagnostics;                   ///< warnings (errors are thrown)
  std::vector<SdfModelReport> models;
  std::vector<SdfMeshReport> meshes;
  std::vector<std::string> plugins_honoured; ///< "model::filename" for each plugin acted on
  std::vector<std::string> plugins_ignored;  ///< "model::filename" (or "world::filename") read and not acted on
  std::string sdf_version;                   ///< the version the file declares
  double load_seconds = 0;                   ///< parse, URIs and meshes
  double parse_seconds = 0;  ///< of which inside sdformat's parser (about 60-100 ms a file: it reads its own spec each time)
};

/// Reads an SDF file holding a <world> (or a single <model>, placed at its pose in an otherwise
/// empty world). Throws Error for malformed SDF, unknown model:// URIs, meshes that are not
/// meshes, absurd scales and sizes, and versions sdformat cannot read; the message names the file
/// and line and the element.
SdfWorld load_sdf_world(const std::filesystem::path& file, const SdfOptions& options = {});

/// Reads SDF text; `file` names it in messages and anchors relative URIs.
SdfWorld parse_sdf_world(const std::string& text, const std::string& file, const SdfOptions& options = {});

/// A model placed into a world by a scenario (world.include) or an SDF <include>.
struct SdfInclude {
  std::string uri;                           ///< model://name, a folder with model.config, or an .sdf file
  std::string name;                          ///< overrides the model's name ("" keeps it)
  Pose3 pose;                                ///< the model's pose in the world
  bool has_pose = false;                     ///< false: the model's own <pose>
  SourceRef source;                          ///< who asked (scenario key), for messages
};

/// Adds included models to `world` (an SVG or maze world, or an SDF one): their solids, bodies,
/// victims, robot starts and robot models, as load_sdf_world would. Reports go to `report`.
void add_sdf_includes(const std::vector<SdfInclude>& includes, const SdfOptions& options, SdfWorld& report);

/// A robot from an SDF <model> with joints (a file, a model folder or a model:// URI).
struct SdfRobot {
  RobotSpec spec;
  Diagnostics diagnostics;
  std::vector<SdfMeshReport> meshes;
  std::string drive_source;                  ///< the plugin the drive came from, or ""
  std::vector<std::string> plugins_ignored;
  double load_seconds = 0;
};

/// Reads the robot a model describes: links with inertials and shapes (collision meshes become
/// convex hulls or decompositions, as for URDF), joints, a drive from the diff-drive plugin
/// (gz-sim-diff-drive-system, ignition-gazebo-diff-drive-system, libgazebo_ros_diff_drive.so;
/// several joints a side for skid steer) and <sensor>s. `where` names who asked.
SdfRobot load_sdf_robot(const std::string& uri, const SdfOptions& options, const SourceRef& where = {});

/// True when a file looks like SDF by name (.sdf, .world).
bool is_sdf_path(const std::filesystem::path& file);

}  // namespace rescuesim
