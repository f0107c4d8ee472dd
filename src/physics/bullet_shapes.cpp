#include "physics/bullet_convert.h"

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
      auto hull = std::make_unique<btConvexHullShape>();
      for (const auto& v : g.mesh.vertices) hull->addPoint(to_bt(v), false);
      hull->recalcLocalAabb();
      // Bullet's default 4 cm margin would round off ramps and thin platforms
      hull->setMargin(0.002f);
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
