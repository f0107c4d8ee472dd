#pragma once
// Internal to import/sdf: what the files of the SDF importer share — parsing with sdformat
// (model:// look-up, built-in models, errors), locations for messages, shapes and inertials,
// and the robot builder. sdformat types appear only here and in import/sdf's .cpp files.

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <sdf/sdf.hh>

#include "import/mesh/mesh.h"
#include "import/sdf/sdf_import.h"

namespace rescuesim::sdf_detail {

// --- parsing (sdf_parse.cpp) -------------------------------------------------------------

/// A parsed SDF document and what the parse learnt.
struct Parsed {
  sdf::Root root;
  std::string declared_version;  ///< the <sdf version> the file declares
  double seconds = 0;            ///< spent in sdformat's parser (its includes too)
};

/// Parses SDF text (`file` names it and anchors relative URIs); model:// resolves through the
/// options' resolver and the built-in models. Throws Error for malformed XML, versions sdformat
/// cannot read and every sdformat error; warnings (a newer 1.x version) go to `diagnostics`.
void parse_sdf(const std::string& text, const std::string& file, const SdfOptions& options, Parsed& out, Diagnostics& diagnostics);

/// Reads a file's text; throws Error naming it when it cannot.
std::string read_text(const std::filesystem::path& file);

/// The folder of model `name` (holding model.config) from the resolver's folders, the Gazebo
/// environment and, last, the built-in models; nullopt when none has it. `tried` collects every
/// folder looked at.
std::optional<std::filesystem::path> find_model_folder(const std::string& name, const SdfOptions& options,
                                                       std::vector<std::filesystem::path>* tried = nullptr);

/// The SDF file a model folder's model.config names (the highest <sdf version> sdformat 12
/// reads, else the highest given); throws Error when there is none.
std::filesystem::path model_file_of(const std::filesystem::path& folder, const SourceRef& where);

/// A `model://`, folder or file URI as a file to load; throws Error listing the places searched.
std::filesystem::path resolve_model_uri(const std::string& uri, const SdfOptions& options, const SourceRef& where);

// --- locations and small conversions (sdf_parse.cpp) --------------------------------------

Pose3 pose_of(const ignition::math::Pose3d& p);
Vec3 vec_of(const ignition::math::Vector3d& v);
Vec3 color_of(const ignition::math::Color& c);

/// `<tag name="...">` of an element.
std::string describe(const sdf::ElementPtr& e);

/// Where an element is: its file (or `fallback_file` for the top-level text), its line, and
/// `<tag name="...">` preceded by `context` (e.g. the model) when given.
SourceRef where_of(const sdf::ElementPtr& e, const std::string& fallback_file, const std::string& context = "");

/// Resolves an sdformat pose (SemanticPose of a model, link, joint, shape, light or sensor) into
/// the frame `to` ("" = the frame it is written relative to); throws Error at `where`.
Pose3 resolve(const sdf::SemanticPose& pose, const std::string& to, const SourceRef& where);

/// Throws Error at `where` when a pose is not finite or further than max_extent from its frame.
void check_pose(const Pose3& X, double max_extent, const SourceRef& where, const std::string& what);

// --- shapes (sdf_geometry.cpp) --------------------------------------------------------------

/// Shared state of one import: options, messages, loaded meshes.
struct Reader {
  const SdfOptions& options;
  std::string file;                         ///< the top-level file, for elements without their own
  Diagnostics& diagnostics;
  std::vector<SdfMeshReport>& meshes;
  std::map<std::tuple<std::string, double, double, double>, LoadedMesh> cache;  ///< by file and scale

  SourceRef at(const sdf::ElementPtr& e, const std::string& context = "") const { return where_of(e, file, context); }
};

/// How a mesh becomes a shape.
enum class MeshUse {
  exact,   ///< the file's triangles (static solids, visuals)
  convex,  ///< a convex hull or decomposition per options.collision (robot links)
};

/// One shape an SDF <geometry> became, placed in the geometry's frame.
struct Piece {
  Geometry geometry;
  Pose3 X_GP;
};

/// What an SDF <geometry> became.
struct Shape {
  std::vector<Piece> pieces;      ///< empty: nothing to add (the floor, a heightmap)
  bool floor = false;             ///< the plane z = 0 with normal +z
  std::optional<Vec3> mesh_color; ///< a mesh file's own colour
};

/// Names of the element a shape belongs to, for messages and reports.
struct ShapeOwner {
  std::string model, link, element;  ///< element: "<collision name=\"c\">" or "<visual ...>"
  bool collision = true;
};

/// Converts a <geometry> whose frame is X_WG in the world (for the floor test). Throws Error for
/// absurd or non-positive sizes and meshes that cannot be loaded.
Shape shape_of(const sdf::Geometry& g, const Pose3& X_WG, MeshUse use, const ShapeOwner& owner, Reader& r);

/// A link's inertial in the link frame: mass, the centre-of-mass frame and the inertia tensor
/// about it in that frame.
struct Inertial {
  double mass = 0;
  Pose3 X_LI;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
};

/// The link's <inertial>, or (with a warning) options.default_density over `shapes_L` (shapes in
/// the link frame); a link with neither gets no mass.
Inertial inertial_of(const sdf::Link& link, const std::vector<Piece>& shapes_L, const std::string& model, Reader& r);

/// The material of a link's shape: "<model>::<link>::<visual>" with the colour of the link's first
/// visual (diffuse, else ambient), else `mesh_color`, else `fallback`'s; with the collision's
/// <surface><friction><ode><mu> when given (then named after the collision). Added to (or
/// replaced in) `materials`; returns its name, or fallback.name when nothing is specified.
std::string material_of(const sdf::Link& link, const sdf::Collision* collision, const std::string& model,
                        const std::optional<Vec3>& mesh_color, const MaterialSpec& fallback, std::vector<MaterialSpec>& materials);

/// <surface><friction><ode><mu> of a collision, when given.
std::optional<double> friction_of(const sdf::Collision& c);

/// The colour a <visual>'s <material> gives (diffuse, else ambient), if any.
std::optional<Vec3> visual_color(const sdf::Visual& visual);

// --- robots (sdf_robot.cpp) -----------------------------------------------------------------

/// What the robot builder learnt besides the spec.
struct RobotExtras {
  std::string drive_source;
  std::vector<std::string> plugins_honoured, plugins_ignored;
};

/// Builds the RobotSpec of a model with joints; `name` is its (scoped) name. `skip_links` are
/// links that are not part of the robot (fixed to the world). Throws Error for joint types
/// rescuesim does not simulate, loops and a bad drive plugin.
RobotSpec build_robot(const sdf::Model& model, const std::string& name, const std::vector<std::string>& skip_links, Reader& r,
                      RobotExtras& extras);

/// The plugins under an element: (filename, element).
std::vector<std::pair<std::string, sdf::ElementPtr>> plugins_of(const sdf::ElementPtr& parent);

}  // namespace rescuesim::sdf_detail
