#pragma once
/// Private to import/mesh: reading our triangles and colour out of an assimp scene. Only the
/// scene's name is declared here; the assimp headers stay in the .cpp files.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "world/geometry.h"

struct aiScene;

namespace rescuesim::mesh_detail {

/// Triangles the scene holds once its polygons are fanned (an n-gon gives n - 2), counting a
/// mesh once for every node that places it. Lines and points count nothing.
std::uint64_t count_triangles(const aiScene& scene);

/// Unwelded triangles: three vertices per triangle, in order.
struct TriangleSoup {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<Vec2, 3>> corner_uvs;  ///< per triangle: its corners' first texture coordinates ((0, 0) without)
  bool all_uvs = true;                          ///< every mesh had texture coordinates
};

/// Every triangle of every node, mapped through the node transforms (root first) and then
/// `X_root`, the loader's own fix of the file's frame and the user's scale. Triangles under a
/// mirroring transform are re-wound so they keep facing out. Faces that are not triangles and
/// indices out of range are skipped.
TriangleSoup scene_triangles(const aiScene& scene, const Eigen::Matrix4d& X_root);

/// The diffuse colour of the first mesh, in node order, whose material has one, clamped to 0..1.
/// Assimp's stand-in materials are skipped: the one named "DefaultMaterial" (STL, OBJ without
/// .mtl) and, when `last_material_is_default` (assimp's glTF 2 reader), the last one. With
/// `linear_color` (glTF's baseColorFactor) the colour is converted to sRGB.
std::optional<Vec3> first_diffuse_color(const aiScene& scene, bool last_material_is_default, bool linear_color);

/// The file name of the first diffuse (or glTF base colour) texture, in node order, as the file
/// writes it (relative to the mesh file, usually); "" when there is none or it is embedded.
std::string first_diffuse_texture(const aiScene& scene);

}  // namespace rescuesim::mesh_detail
