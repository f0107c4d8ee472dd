#pragma once
/// URDF robots: a URDF file (read with urdfdom) becomes a RobotSpec — links with their
/// inertials, collision and visual shapes (meshes through import/mesh: a collision mesh becomes
/// its convex hull, or a convex decomposition), joints with limits and dynamics, a drive read
/// from a Gazebo diff-drive or skid-steer plugin, and sensors from <gazebo><sensor> blocks.
/// Errors name the file, the line and the element, and what was expected; problems that do not
/// stop the import (a link without an inertial, an unknown plugin) are warnings.

#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "world/resource_uri.h"
#include "world/robot_spec.h"

namespace rescuesim {

/// How a collision mesh on a link becomes convex shapes.
enum class CollisionMode {
  automatic,   ///< the convex hull, or a decomposition when the hull is much bigger than the mesh
  hull,        ///< always the convex hull
  decompose,   ///< always a convex decomposition
};

/// Settings of a URDF import.
struct UrdfOptions {
  ResourceResolver resolver;           ///< where package:// and relative mesh paths are found
  std::string namespace_prefix;        ///< fills TurtleBot3-style ${namespace} placeholders ("" by default)
  int hull_vertices = 64;              ///< vertex budget of each convex hull
  CollisionMode collision = CollisionMode::automatic;
  double decompose_ratio = 1.5;        ///< automatic: decompose when hull volume > this x mesh volume
  std::size_t max_triangles = 2'000'000;  ///< per mesh file; more is refused
  double default_density = 1000.0;     ///< kg/m^3 for links without an inertial (with a warning)
};

/// What the importer made of one mesh, for `rescuesim check` and the bench.
struct UrdfMeshReport {
  std::string link;
  std::string uri;
  std::string file;                    ///< resolved path
  bool collision = false;              ///< collision (true) or visual (false)
  int triangles = 0;
  int hull_vertices = 0;               ///< collision: vertices of all convex pieces
  int pieces = 0;                      ///< collision: convex pieces (1 = the hull)
  double mesh_volume = 0, hull_volume = 0;  ///< m^3 (collision meshes)
};

/// A URDF robot with everything learnt while reading it.
struct UrdfRobot {
  RobotSpec spec;
  Diagnostics diagnostics;             ///< warnings (errors are thrown)
  std::vector<UrdfMeshReport> meshes;
  std::string root_link;
  int moving_joints = 0, fixed_joints = 0;
  double load_seconds = 0;             ///< parse + mesh loading
  double hull_seconds = 0;             ///< convex hulls and decompositions
  std::string drive_source;            ///< where the drive came from ("plugin libgazebo_ros_diff_drive.so", "derived", "")
};

/// Reads a URDF file. Throws Error for malformed XML, xacro input, unknown or refused joint
/// types, joint loops, missing meshes, unresolvable URIs, non-physical inertials and the like.
UrdfRobot load_urdf(const std::filesystem::path& file, const UrdfOptions& options = {});

/// Reads URDF text; `file` names it in messages and anchors relative mesh paths.
UrdfRobot parse_urdf(const std::string& text, const std::string& file, const UrdfOptions& options = {});

/// True when a file looks like URDF by name (.urdf) — for the CLI's choice of reader.
bool is_urdf_path(const std::filesystem::path& file);

}  // namespace rescuesim

namespace rescuesim {

/// Makes the named joints a differential (or skid-steer, several a side) drive: they become
/// velocity-controlled, each wheel's forward sign comes from its axis, and the wheel radius
/// (from the wheel links' collision shapes) and the track (between the left and right wheel
/// centres) are derived unless given (> 0). Throws Error at `where` for unknown or fixed joints,
/// wheels whose axis does not point sideways, or 'left' wheels to the right of the 'right' ones
/// — unless `sides_by_position`, when the sides are swapped to where the wheels are (returns
/// true then).
bool configure_diff_drive(RobotSpec& robot, const std::vector<std::string>& left, const std::vector<std::string>& right,
                          double wheel_radius, double track_width, const SourceRef& where, bool sides_by_position = false);

}  // namespace rescuesim

namespace rescuesim {

/// Adds the sensors every robot has unless it already has one of the kind: wheel odometry
/// (when it has a drive), ground truth, joint states and a contact sensor on the root link.
void add_standard_sensors(RobotSpec& robot);

}  // namespace rescuesim
