#include "import/mesh/mesh_assimp.h"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace rescuesim::mesh_detail {

namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  }
  return out;
}

/// Calls visit(node, X_WN) for every node, parents before children, children in file order.
template <typename Visit>
void walk_nodes(const aiScene& scene, const Eigen::Matrix4d& X_root, Visit&& visit) {
  if (scene.mRootNode == nullptr) return;
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack{{scene.mRootNode, X_root * to_eigen(scene.mRootNode->mTransformation)}};
  while (!stack.empty()) {
    auto [node, X_WN] = std::move(stack.back());
    stack.pop_back();
    visit(*node, X_WN);
    // push in reverse so the first child is visited next
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) stack.emplace_back(child, X_WN * to_eigen(child->mTransformation));
    }
  }
}

/// The meshes a node places that really exist in the scene.
template <typename Use>
void for_node_meshes(const aiScene& scene, const aiNode& node, Use&& use) {
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned m = node.mMeshes[i];
    if (m < scene.mNumMeshes && scene.mMeshes[m] != nullptr) use(*scene.mMeshes[m]);
  }
}

double linear_to_srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

}  // namespace

std::uint64_t count_triangles(const aiScene& scene) {
  // faces of each mesh once, then once per node that places the mesh
  std::vector<std::uint64_t> per_mesh(scene.mNumMeshes, 0);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr || mesh->mFaces == nullptr) continue;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n >= 3) per_mesh[m] += n - 2;
    }
  }
  std::uint64_t total = 0;
  walk_nodes(scene, Eigen::Matrix4d::Identity(), [&](const aiNode& node, const Eigen::Matrix4d&) {
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      if (node.mMeshes[i] < scene.mNumMeshes) total += per_mesh[node.mMeshes[i]];
    }
  });
  return total;
}

TriangleSoup scene_triangles(const aiScene& scene, const Eigen::Matrix4d& X_root) {
  TriangleSoup soup;
  walk_nodes(scene, X_root, [&](const aiNode& node, const Eigen::Matrix4d& X_WN) {
    const Eigen::Matrix3d R = X_WN.topLeftCorner<3, 3>();
    const Vec3 t = X_WN.topRightCorner<3, 1>();
    const bool mirrored = R.determinant() < 0;
    for_node_meshes(scene, node, [&](const aiMesh& mesh) {
      if (mesh.mVertices == nullptr || mesh.mFaces == nullptr) return;
      // this mesh's vertices, placed in the loader's frame
      const int base = static_cast<int>(soup.vertices.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& p = mesh.mVertices[v];
        soup.vertices.push_back(R * Vec3(p.x, p.y, p.z) + t);
      }
      // its triangles; a mirroring transform turns the winding, so swap it back
      const aiVector3D* uv = mesh.mTextureCoords[0];
      if (uv == nullptr) soup.all_uvs = false;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;
        unsigned a = face.mIndices[0], b = face.mIndices[1], c = face.mIndices[2];
        if (a >= mesh.mNumVertices || b >= mesh.mNumVertices || c >= mesh.mNumVertices) continue;
        if (mirrored) std::swap(b, c);
        soup.triangles.push_back({base + static_cast<int>(a), base + static_cast<int>(b), base + static_cast<int>(c)});
        const auto corner = [&](unsigned i) { return uv ? Vec2(uv[i].x, uv[i].y) : Vec2(0, 0); };
        soup.corner_uvs.push_back({corner(a), corner(b), corner(c)});
      }
    });
  });
  return soup;
}

std::optional<Vec3> first_diffuse_color(const aiScene& scene, bool last_material_is_default, bool linear_color) {
  std::optional<Vec3> found;
  walk_nodes(scene, Eigen::Matrix4d::Identity(), [&](const aiNode& node, const Eigen::Matrix4d&) {
    for_node_meshes(scene, node, [&](const aiMesh& mesh) {
      if (found || mesh.mMaterialIndex >= scene.mNumMaterials) return;
      if (last_material_is_default && mesh.mMaterialIndex + 1 == scene.mNumMaterials) return;
      const aiMaterial* material = scene.mMaterials[mesh.mMaterialIndex];
      if (material == nullptr) return;
      // assimp's stand-in for files without materials is not the author's colour
      aiString name;
      if (material->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::strcmp(name.C_Str(), AI_DEFAULT_MATERIAL_NAME) == 0) return;
      aiColor4D diffuse;
      if (material->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != AI_SUCCESS) return;
      Vec3 rgb(diffuse.r, diffuse.g, diffuse.b);
      rgb = rgb.cwiseMax(0.0).cwiseMin(1.0);
      if (linear_color) rgb = rgb.unaryExpr([](double c) { return linear_to_srgb(c); });
      found = rgb;
    });
  });
  return found;
}

std::string first_diffuse_texture(const aiScene& scene) {
  std::string found;
  walk_nodes(scene, Eigen::Matrix4d::Identity(), [&](const aiNode& node, const Eigen::Matrix4d&) {
    for_node_meshes(scene, node, [&](const aiMesh& mesh) {
      if (!found.empty() || mesh.mMaterialIndex >= scene.mNumMaterials || scene.mMaterials[mesh.mMaterialIndex] == nullptr) return;
      const aiMaterial& material = *scene.mMaterials[mesh.mMaterialIndex];
      for (const aiTextureType type : {aiTextureType_DIFFUSE, aiTextureType_BASE_COLOR}) {
        aiString path;
        if (material.GetTextureCount(type) == 0 || material.GetTexture(type, 0, &path) != AI_SUCCESS) continue;
        // "*0": a texture embedded in a glTF/GLB, not a file
        if (path.length > 0 && path.C_Str()[0] != '*') found = path.C_Str();
        return;
      }
    });
  });
  return found;
}

}  // namespace rescuesim::mesh_detail
