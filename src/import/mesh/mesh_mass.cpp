// mass_properties: volume, centroid and inertia of a closed triangle mesh by the divergence
// theorem. Every triangle and a reference point form a tetrahedron with a signed volume; the signed
// sums of the tetrahedra's volumes, first moments and second moments are the solid's. Outward
// triangles give positive sums; a mesh wound inward gives all of them negated, so the signs are
// flipped together at the end and the result does not depend on the winding.

#include "import/mesh/mesh.h"

namespace rescuesim {

MassProperties mass_properties(const TriangleMesh& mesh) {
  MassProperties out;
  if (mesh.vertices.empty() || mesh.triangles.empty()) return out;

  // the vertex mean as reference point keeps the sums well conditioned far from the origin
  Vec3 reference = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) reference += v;
  reference /= static_cast<double>(mesh.vertices.size());

  // sums over tetrahedra (reference, a, b, c), in coordinates relative to the reference: volume
  // a.(b x c)/6, first moment volume*(a+b+c)/4, and second moment (the integral of p p^T)
  // volume/20 * (a a^T + b b^T + c c^T + s s^T) with s = a + b + c
  double volume = 0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - reference;
    const Vec3 b = mesh.vertices[t[1]] - reference;
    const Vec3 c = mesh.vertices[t[2]] - reference;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Vec3 s = a + b + c;
    volume += v;
    first += v * s / 4.0;
    second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }

  // an inward-wound mesh negates every sum; a flat or open one may sum to no volume at all
  if (volume < 0) {
    volume = -volume;
    first = -first;
    second = -second;
  }
  if (!(volume > 0)) {
    out.centroid = reference;
    return out;
  }

  // centroid, then the second moment about it (parallel axis), then inertia = tr(C) I - C
  const Vec3 c = first / volume;
  const Eigen::Matrix3d central = second - volume * c * c.transpose();
  out.volume = volume;
  out.centroid = reference + c;
  out.inertia = central.trace() * Eigen::Matrix3d::Identity() - central;
  return out;
}

}  // namespace rescuesim
