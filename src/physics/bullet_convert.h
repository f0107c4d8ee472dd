#pragma once
// Internal to src/physics: conversions between our Eigen types and Bullet's, and shapes.

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "core/pose.h"
#include "world/geometry.h"

namespace rescuesim::bullet {

inline btVector3 to_bt(const Vec3& v) { return {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())}; }
inline btQuaternion to_bt(const Quat& q) { return {btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())}; }
inline btTransform to_bt(const Pose3& X) { return btTransform(to_bt(X.q), to_bt(X.p)); }
inline Vec3 from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline Quat from_bt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()).normalized(); }
inline Pose3 from_bt(const btTransform& T) { return {from_bt(T.getOrigin()), from_bt(T.getRotation())}; }

/// Owns Bullet shapes and the mesh data they point into.
class ShapeStore {
 public:
  /// A collision shape for a geometry (primitives where Bullet has them).
  btCollisionShape* make(const Geometry& g);
  /// The plane z = 0 (normal +z).
  btCollisionShape* plane();
  /// A compound of several shapes at local poses.
  btCompoundShape* compound();

 private:
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
};

}  // namespace rescuesim::bullet
