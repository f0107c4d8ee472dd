#pragma once
/// Shapes of compiled objects, shared by physics (primitives where it has them), ray casting
/// and rendering (triangle meshes). All in the object's own frame, metres.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/pose.h"

namespace rescuesim {

/// A triangle mesh: vertices and counter-clockwise (outward-facing) index triples.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// An image on a triangle mesh, for the cameras (physics and the ray sensors ignore it): the
/// texture a mesh file names, with the texture coordinates of each triangle's corners.
struct SurfaceImage {
  std::string file;                                ///< the image file (PNG, JPEG, BMP, TGA), absolute
  std::vector<std::array<Vec2, 3>> corner_uvs;     ///< per triangle of the mesh: (u, v) of its corners, v up
};

/// A collision and visual shape.
struct Geometry {
  enum class Type { box, cylinder, sphere, convex, mesh };
  Type type = Type::box;
  /// box: full extents (x, y, z); cylinder: (diameter, diameter, length) along its z axis;
  /// sphere: (diameter, diameter, diameter); convex and mesh: their bounding box.
  Vec3 size{1, 1, 1};
  /// convex: hull points; mesh: triangles (both also carry a mesh for rendering)
  TriangleMesh mesh;
  /// mesh only: an image drawn on it (null: the material's colour). Shared: copies are cheap.
  std::shared_ptr<const SurfaceImage> image;

  static Geometry box(const Vec3& full_extents);
  static Geometry cylinder(double radius, double length);
  static Geometry sphere(double radius);
  /// A convex solid given by its surface mesh (its vertices are the hull points).
  static Geometry convex(TriangleMesh hull);
  static Geometry triangles(TriangleMesh mesh);
};

/// The triangles of any geometry; round shapes use `segments` around.
TriangleMesh mesh_of(const Geometry& g, int segments = 24);

/// Principal moments of inertia (kg m^2) of a solid, uniform body of `mass` in the shape of `g`
/// about its centre: box, cylinder (about its z axis), sphere; a convex or mesh shape as its
/// bounding box.
Vec3 solid_inertia(const Geometry& g, double mass);

/// A planar polygon (counter-clockwise) extruded from z0 to z1, closed with caps.
TriangleMesh extrude(const std::vector<Vec2>& polygon, double z0, double z1);

/// Flips triangles of a convex mesh so every normal points away from the vertex centroid.
void orient_outward(TriangleMesh& convex_mesh);

/// True when the counter-clockwise polygon is convex.
bool is_convex(const std::vector<Vec2>& polygon);

}  // namespace rescuesim
