#pragma once
/// Private to src/raycast: the process's Embree device and the step from our triangle meshes to
/// Embree triangle geometry. Never include this outside src/raycast.

#include <embree3/rtcore.h>

#include <cstddef>
#include <vector>

#include "world/world.h"

namespace rescuesim::raycast_detail {

/// The process-wide Embree device, created on first use; Embree errors abort with a message
/// (they are bugs here: bad arguments or out of memory).
RTCDevice embree_device();

/// Triangles as Embree wants them: float xyz triples and unsigned index triples.
struct FloatMesh {
  std::vector<float> vertices;     ///< x, y, z per vertex (m, in the frame the mesh is built in)
  std::vector<unsigned> indices;   ///< three per triangle

  /// Appends `mesh` with its vertices mapped through X (mesh frame → this mesh's frame).
  void append(const TriangleMesh& mesh, const Pose3& X);
  /// Unit normal of every triangle, (v1 − v0) × (v2 − v0) normalised (zero for a degenerate one).
  std::vector<Vec3> unit_normals() const;
  std::size_t triangle_count() const { return indices.size() / 3; }
  std::size_t vertex_count() const { return vertices.size() / 3; }
};

/// Segments around round shapes (cylinders, spheres) in the ray-tracing meshes.
inline constexpr int kRoundSegments = 24;

/// Every static object's triangles in the world frame; owner[t] is the World::statics index of
/// triangle t.
FloatMesh static_triangles(const World& world, std::vector<int>* owner);

/// A new (uncommitted) Embree triangle geometry holding a copy of `mesh`.
RTCGeometry new_triangle_geometry(const FloatMesh& mesh);

/// A committed scene holding `mesh` as its only geometry (robust, at the given build quality).
RTCScene new_mesh_scene(const FloatMesh& mesh, RTCBuildQuality quality);

}  // namespace rescuesim::raycast_detail
