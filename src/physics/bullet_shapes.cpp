#include "physics/bullet_convert.h"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <vector>

namespace rescuesim::bullet {

btCollisionShape* ShapeStore::make(const Geometry& g) {
  std::unique_ptr<btCollisionShape> s;
  switch (g.type) {
    case Geometry::Type::box: s = std::make_unique<btBoxShape>(to_bt(0.5 * g.size)); break;
    case Geometry::Type::cylinder:
      s = std::make_unique<btCylinderShapeZ>(btVector3(btScalar(0.5 * g.size.x()), btScalar(0.5 * g.size.y()), btScalar(0.5 * g.size.z())));
      break;
    case Geometry::Type::sphere: s = std::make_unique<btSphereShape>(btScalar(0.5 * g.size.x())); break;
    case Geometry::Type::convex: {
      // Bullet puts its collision margin outside a hull; the points are moved in by the margin
      // first (the hull's face planes shifted inward, as btConvexHullComputer's shrink does), so
      // hull plus margin is the drawn surface rather than 2 mm more. Bullet's default 4 cm margin
      // would round off ramps and thin platforms; 2 mm keeps GJK robust.
      constexpr double kMargin = 0.002;
      std::vector<double> coords;
      for (const auto& v : g.mesh.vertices) coords.insert(coords.end(), {v.x(), v.y(), v.z()});
      btConvexHullComputer computer;
      const int n = static_cast<int>(g.mesh.vertices.size());
      const double shrunk = computer.compute(coords.data(), 3 * sizeof(double), n, btScalar(kMargin), btScalar(0.25));
      auto hull = std::make_unique<btConvexHullShape>();
      if (shrunk > 1e-5 && computer.vertices.size() >= 4) {
        for (int i = 0; i < computer.vertices.size(); ++i) hull->addPoint(computer.vertices[i], false);
        hull->setMargin(btScalar(std::min(kMargin, shrunk)));
      } else {
        for (const auto& v : g.mesh.vertices) hull->addPoint(to_bt(v), false);
        hull->setMargin(btScalar(kMargin));
      }
      hull->recalcLocalAabb();
      s = std::move(hull);
      break;
    }
    case Geometry::Type::mesh: {
      auto mesh = std::make_unique<btTriangleMesh>();
      for (const auto& t : g.mesh.triangles) {
        mesh->addTriangle(to_bt(g.mesh.vertices[static_cast<std::size_t>(t[0])]), to_bt(g.mesh.vertices[static_cast<std::size_t>(t[1])]),
                          to_bt(g.mesh.vertices[static_cast<std::size_t>(t[2])]));
      }
      s = std::make_unique<btBvhTriangleMeshShape>(mesh.get(), true);
      meshes_.push_back(std::move(mesh));
      break;
    }
  }
  shapes_.push_back(std::move(s));
  return shapes_.back().get();
}

btCollisionShape* ShapeStore::plane() {
  shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(0)));
  return shapes_.back().get();
}

btCompoundShape* ShapeStore::compound() {
  auto c = std::make_unique<btCompoundShape>();
  btCompoundShape* raw = c.get();
  shapes_.push_back(std::move(c));
  return raw;
}

}  // namespace rescuesim::bullet
