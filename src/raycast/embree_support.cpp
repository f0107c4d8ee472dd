#include "raycast/embree_support.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/tsan.h"

namespace rescuesim::raycast_detail {

namespace {

void on_embree_error(void*, RTCError code, const char* text) {
  const std::string message = std::string("Embree error ") + std::to_string(static_cast<int>(code)) + ": " + (text ? text : "");
  demand_failed("Embree call succeeded", __FILE__, __LINE__, message.c_str());
}

/// The device's configuration. Embree builds a scene (rtcCommitScene) on TBB's threads and
/// hands it back through TBB's own synchronisation, which ThreadSanitizer cannot see in
/// Debian's uninstrumented libraries: what the builders allocated and the thread that later
/// releases the scene would look like a race. Under TSan, "threads=1" caps TBB at one thread,
/// so every build runs on the thread that commits, and each scene passes between our threads
/// only through the worker pool's mutex (core/parallel.cpp) or the caller's own locks.
constexpr const char* kDeviceConfig = kUnderTsan ? "threads=1" : nullptr;

/// Owns the device for the life of the process; scenes retain it themselves, so static
/// destruction order does not matter.
struct DeviceHolder {
  RTCDevice device;
  DeviceHolder() : device(rtcNewDevice(kDeviceConfig)) {
    RS_DEMAND(device != nullptr, "rtcNewDevice failed");
    rtcSetDeviceErrorFunction(device, on_embree_error, nullptr);
  }
  ~DeviceHolder() { rtcReleaseDevice(device); }
  DeviceHolder(const DeviceHolder&) = delete;
  DeviceHolder& operator=(const DeviceHolder&) = delete;
};

}  // namespace

RTCDevice embree_device() {
  static DeviceHolder holder;
  return holder.device;
}

void FloatMesh::append(const TriangleMesh& mesh, const Pose3& X) {
  const auto base = static_cast<unsigned>(vertex_count());
  for (const Vec3& v : mesh.vertices) {
    const Vec3 p = X * v;
    vertices.push_back(static_cast<float>(p.x()));
    vertices.push_back(static_cast<float>(p.y()));
    vertices.push_back(static_cast<float>(p.z()));
  }
  for (const auto& t : mesh.triangles) {
    for (int k : t) indices.push_back(base + static_cast<unsigned>(k));
  }
}

std::vector<Vec3> FloatMesh::unit_normals() const {
  std::vector<Vec3> normals(triangle_count());
  auto vertex = [&](unsigned k) { return Vec3(vertices[3 * k], vertices[3 * k + 1], vertices[3 * k + 2]); };
  for (std::size_t t = 0; t < normals.size(); ++t) {
    const Vec3 a = vertex(indices[3 * t]), b = vertex(indices[3 * t + 1]), c = vertex(indices[3 * t + 2]);
    normals[t] = (b - a).cross(c - a);
    const double length = normals[t].norm();
    normals[t] = length > 0 ? Vec3(normals[t] / length) : Vec3::Zero();
  }
  return normals;
}

FloatMesh static_triangles(const World& world, std::vector<int>* owner) {
  FloatMesh m;
  for (std::size_t i = 0; i < world.statics.size(); ++i) {
    const StaticObject& o = world.statics[i];
    const std::size_t before = m.triangle_count();
    m.append(mesh_of(o.geometry, kRoundSegments), o.X_WO);
    if (owner) owner->insert(owner->end(), m.triangle_count() - before, static_cast<int>(i));
  }
  return m;
}

RTCGeometry new_triangle_geometry(const FloatMesh& mesh) {
  RTCGeometry g = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  // embree pads the buffers it allocates itself, so the last vertex may be read as 16 bytes
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertex_count()));
  std::copy(mesh.vertices.begin(), mesh.vertices.end(), v);
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangle_count()));
  std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
  return g;
}

RTCScene new_mesh_scene(const FloatMesh& mesh, RTCBuildQuality quality) {
  RTCScene s = rtcNewScene(embree_device());
  rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s, quality);
  RTCGeometry g = new_triangle_geometry(mesh);
  rtcSetGeometryBuildQuality(g, quality);
  rtcCommitGeometry(g);
  rtcAttachGeometry(s, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(s);
  return s;
}

}  // namespace rescuesim::raycast_detail
