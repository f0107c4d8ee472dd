#pragma once
/// Private to import/mesh: welding a triangle soup into an indexed mesh (loader, decomposition) and
/// coarsening a mesh by vertex clustering (decomposition of large meshes).

#include <array>
#include <vector>

#include "world/geometry.h"

namespace rescuesim::mesh_detail {

/// Merges vertices with exactly equal coordinates, drops triangles that then repeat a vertex and
/// vertices no triangle uses. Vertices keep the order of their first use; triangle order and
/// winding are kept. Deterministic. `kept`, when given, receives for each output triangle the
/// index of the input triangle it came from.
TriangleMesh weld(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                  std::vector<int>* kept = nullptr);

/// A coarser mesh and where each original vertex went.
struct ClusteredMesh {
  TriangleMesh mesh;
  /// per original vertex: its merged vertex in `mesh`, or -1 when all its triangles collapsed
  std::vector<int> vertex_of;
};

/// Vertex clustering: vertices in the same cube of side `cell` (a grid from the bounding box's low
/// corner) merge into one at their mean; triangles that collapse, and repeats of a triangle (in
/// either winding), are dropped. Deterministic.
ClusteredMesh cluster_vertices(const TriangleMesh& mesh, double cell);

/// cluster_vertices with the smallest cell (growing by 1.25) that leaves at most `max_triangles`;
/// the mesh itself, unchanged, when it already has no more than that.
ClusteredMesh coarsen(const TriangleMesh& mesh, std::size_t max_triangles);

}  // namespace rescuesim::mesh_detail
