// mass_properties against solids whose volume, centroid and inertia are known in closed form.

#include <gtest/gtest.h>

#include "import/mesh/mesh.h"

namespace rescuesim {
namespace {

void expect_matrix(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double tol = 1e-12) {
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tol) << "got\n" << a << "\nexpected\n" << b;
}

TriangleMesh moved(TriangleMesh m, const Vec3& offset) {
  for (Vec3& v : m.vertices) v += offset;
  return m;
}

TEST(MeshMass, BoxOneByTwoByThreeAwayFromTheOrigin) {
  const Vec3 offset(0.3, -0.2, 5.0);
  const MassProperties mp = mass_properties(moved(mesh_of(Geometry::box({1, 2, 3})), offset));
  EXPECT_NEAR(mp.volume, 6.0, 1e-12);
  EXPECT_NEAR((mp.centroid - offset).norm(), 0, 1e-12);
  // m/12 (b^2 + c^2, a^2 + c^2, a^2 + b^2) with m = 6, a = 1, b = 2, c = 3
  expect_matrix(mp.inertia, Vec3(6.5, 5.0, 2.5).asDiagonal().toDenseMatrix());
}

TEST(MeshMass, InwardWindingGivesTheSameResult) {
  TriangleMesh box = moved(mesh_of(Geometry::box({1, 2, 3})), {1, 2, 3});
  const MassProperties outward = mass_properties(box);
  for (auto& t : box.triangles) std::swap(t[1], t[2]);
  const MassProperties inward = mass_properties(box);
  EXPECT_NEAR(inward.volume, 6.0, 1e-12);
  EXPECT_NEAR((inward.centroid - outward.centroid).norm(), 0, 1e-12);
  expect_matrix(inward.inertia, outward.inertia);
}

TEST(MeshMass, RotatingTheBoxRotatesItsInertia) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  TriangleMesh box = mesh_of(Geometry::box({1, 2, 3}));
  for (Vec3& v : box.vertices) v = R * v;
  const MassProperties mp = mass_properties(box);
  EXPECT_NEAR(mp.volume, 6.0, 1e-12);
  expect_matrix(mp.inertia, R * Vec3(6.5, 5.0, 2.5).asDiagonal() * R.transpose());
}

TEST(MeshMass, CornerTetrahedron) {
  // (0,0,0), e1, e2, e3: volume 1/6, centroid (1/4, 1/4, 1/4); about the origin the integral of
  // x^2 is 1/60 and of xy 1/120, so about the centroid 1/60 - (1/6)(1/16) = 1/160 and
  // 1/120 - (1/6)(1/16) = -1/480: inertia diagonal 2/160 = 1/80, off-diagonal +1/480
  TriangleMesh tet;
  tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const MassProperties mp = mass_properties(tet);
  EXPECT_NEAR(mp.volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR((mp.centroid - Vec3(0.25, 0.25, 0.25)).norm(), 0, 1e-15);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Constant(1.0 / 480.0);
  expected.diagonal().setConstant(1.0 / 80.0);
  expect_matrix(mp.inertia, expected, 1e-15);
}

TEST(MeshMass, CylinderMeshApproachesTheSolid) {
  // 96 sides: the inscribed prism has area (n/2) r^2 sin(2 pi / n), 0.07% below pi r^2
  const TriangleMesh cylinder = mesh_of(Geometry::cylinder(0.5, 2.0), 96);
  const MassProperties mp = mass_properties(cylinder);
  const double area = 48 * 0.25 * std::sin(2 * M_PI / 96);
  EXPECT_NEAR(mp.volume, area * 2.0, 1e-12);
  EXPECT_NEAR(mp.centroid.norm(), 0, 1e-12);
  // solid cylinder m (3 r^2 + h^2) / 12 across and m r^2 / 2 along, to the polygon's accuracy
  const double m = mp.volume;
  EXPECT_NEAR(mp.inertia(0, 0), m * (3 * 0.25 + 4.0) / 12, 1e-3 * m);
  EXPECT_NEAR(mp.inertia(2, 2), m * 0.25 / 2, 1e-3 * m);
}

TEST(MeshMass, EmptyMeshHasNothing) {
  const MassProperties mp = mass_properties(TriangleMesh{});
  EXPECT_EQ(mp.volume, 0);
  EXPECT_EQ(mp.inertia, Eigen::Matrix3d::Zero());
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

TEST(MeshMass, PrimitiveMeshesFaceOutward) {
  // geometry.h promises counter-clockwise triangles seen from outside: a positive signed volume
  for (const Geometry& g : {Geometry::box({1, 2, 3}), Geometry::cylinder(0.5, 2), Geometry::sphere(1)}) {
    const TriangleMesh m = mesh_of(g, 24);
    double signed_volume = 0;
    for (const auto& t : m.triangles) signed_volume += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    EXPECT_GT(signed_volume, 0) << static_cast<int>(g.type);
    EXPECT_NEAR(signed_volume, mass_properties(m).volume, 1e-12);
  }
  EXPECT_NEAR(mass_properties(mesh_of(Geometry::box({1, 2, 3}))).volume, 6.0, 1e-12);
}

}  // namespace
}  // namespace rescuesim
