#pragma once
/// Meshes from files and what physics needs of them: loading STL (binary and ASCII), COLLADA,
/// OBJ and glTF/GLB through assimp; convex hulls reduced to a vertex budget (Bullet's
/// btConvexHullComputer); convex decomposition of concave meshes (Bullet extras' HACD); and the
/// volume, centroid and inertia of a closed mesh. Importers (import/urdf, import/sdf) use it;
/// no assimp or Bullet type appears here.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "world/geometry.h"

namespace rescuesim {

/// How to load a mesh file.
struct MeshLoadOptions {
  Vec3 scale = Vec3::Ones();                ///< per-axis scale applied after the file's own unit (URDF <mesh scale>)
  std::size_t max_triangles = 2'000'000;    ///< more than this is refused, naming the count
};

/// A mesh read from a file: every triangle of every node, in metres, in the file's frame with
/// z up (COLLADA's <unit> and <up_axis> honoured; STL and OBJ taken as they are; glTF's y-up
/// turned to z-up as ROS tools do for COLLADA).
struct LoadedMesh {
  TriangleMesh mesh;
  std::optional<Vec3> color;                ///< diffuse colour of the first material that has one (sRGB, 0..1)
  std::string format;                       ///< "stl", "collada", "obj", "gltf"
  std::string texture;                      ///< the diffuse texture the file names ("" for none), as written
  /// that texture, found beside the mesh file, with every triangle's texture coordinates; null
  /// when the file names none, it is missing, embedded, or the mesh has no texture coordinates
  std::shared_ptr<const SurfaceImage> image;
};

/// Loads a mesh file. `named_by` is the file and element that referred to it (a URDF's
/// <mesh filename=...>), quoted in errors. Throws Error, naming the file, when it is missing,
/// unreadable, not a mesh of a supported format (including binary garbage named .stl or
/// .dae), empty, or has more than options.max_triangles triangles.
LoadedMesh load_mesh(const std::filesystem::path& file, const MeshLoadOptions& options = {}, const SourceRef& named_by = {});

/// The convex hull of `points` as a closed, outward-facing triangle mesh with at most
/// `max_vertices` vertices (>= 4). When the exact hull has more, it is reduced (see
/// mesh_hull.cpp for how) so that it stays close to, and inside, the exact hull. Throws Error
/// when the points are degenerate (fewer than 4, or all in a plane or on a line).
TriangleMesh convex_hull(const std::vector<Vec3>& points, int max_vertices = 64);

/// Mass properties of a closed triangle mesh of uniform density 1, from the divergence theorem.
struct MassProperties {
  double volume = 0;                        ///< m^3 (absolute value; orientation-independent)
  Vec3 centroid = Vec3::Zero();             ///< m, in the mesh frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centroid, per unit density (m^5)
};
MassProperties mass_properties(const TriangleMesh& mesh);

/// Settings of a convex decomposition.
struct DecompositionOptions {
  int max_hulls = 16;                       ///< at most this many convex pieces
  int max_vertices_per_hull = 32;
  double concavity = 0.01;                  ///< m: largest allowed concavity of a piece
};

/// Splits a (possibly concave) closed mesh into convex pieces whose union approximates it, each
/// an outward-facing hull mesh. Falls back to the single convex hull when the mesh is already
/// convex enough (its hull adds at most 5% volume) or the pieces together are no tighter than it.
/// Deterministic. Throws Error for bad options or a mesh with no volume (see convex_hull).
std::vector<TriangleMesh> convex_decomposition(const TriangleMesh& mesh, const DecompositionOptions& options = {});

}  // namespace rescuesim
