#include "raycast/ray_scene.h"

#include <algorithm>
#include <cstdint>
#include <list>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "raycast/embree_support.h"

namespace rescuesim {

using raycast_detail::FloatMesh;

namespace {

/// Below this many rays a batch is traced on the calling thread.
constexpr std::size_t kParallelMinRays = 384;
/// Packets of 16 rays handed to one task of the pool at a time.
constexpr std::size_t kPacketsPerTask = 4;
/// Above this many static triangles rubble is never folded into the flat geometry: each time a
/// body falls asleep or wakes the flat BVH is rebuilt (about 1 ms for a maze of a few thousand
/// triangles, tens of ms for a 100 000-triangle mesh world), which would cost more than tracing
/// the rubble as instances saves.
constexpr std::size_t kFlatRubbleMaxStaticTriangles = 20000;
/// Surfaces this close to the end of an occlusion segment do not occlude it (m).
constexpr double kOcclusionSlack = 1e-4;

/// Embree's intersect context with the robot whose links rays must not see. Embree hands the
/// context pointer back to filter functions unchanged, so it can carry our own fields.
struct CastContext {
  RTCIntersectContext rtc;
  RobotIndex ignore_robot = {};
};

/// The context of every query. Coherent mode: lidar and sonar batches fan out from one origin,
/// where embree's coherent packet traversal is about twice as fast as the incoherent one.
CastContext make_context(RobotIndex ignore_robot) {
  CastContext c;
  rtcInitIntersectContext(&c.rtc);
  c.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  c.ignore_robot = ignore_robot;
  return c;
}

/// Filter on every robot-link triangle: rejects the hit when the link belongs to the robot the
/// rays ignore. The geometry's user data is its robot index.
void link_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const CastContext*>(args->context);
  const RobotIndex robot(static_cast<int>(reinterpret_cast<std::intptr_t>(args->geometryUserPtr)));
  if (robot != ctx->ignore_robot) return;
  for (unsigned i = 0; i < args->N; ++i) args->valid[i] = 0;
}

/// Pose as Embree's 3×4 column-major float transform.
void to_embree_transform(const Pose3& X, float out[12]) {
  const Eigen::Matrix3d R = X.q.toRotationMatrix();
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) out[c * 3 + r] = static_cast<float>(R(r, c));
  }
  for (int r = 0; r < 3; ++r) out[9 + r] = static_cast<float>(X.p[r]);
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

/// One geometry of the top-level scene (the static triangles, or an instance of a rubble or
/// link prototype); its position in Impl::instances is its embree geomID.
struct Instance {
  RTCGeometry geometry = nullptr;
  RayHit::Source source = RayHit::Source::none;
  int index = -1;                       ///< statics: unused (per triangle); dynamics / link index
  RobotIndex robot;
  const std::vector<Vec3>* normals = nullptr;  ///< unit normal per prototype triangle, prototype frame
  Eigen::Matrix3d R_WP = Eigen::Matrix3d::Identity();  ///< rotation prototype → world, for normals
};

}  // namespace

/// Who owns a triangle of the flat geometry: a static object or a sleeping rubble body.
struct FlatOwner {
  RayHit::Source source = RayHit::Source::static_object;
  int index = -1;  ///< World::statics or World::dynamics index
};

struct RayScene::Impl {
  RTCScene top = nullptr;
  std::vector<RTCScene> prototypes;          ///< owned prototype scenes (rubble, links)
  /// Unit triangle normals of each prototype (a list, so their addresses stay put as it grows):
  /// looking them up is cheaper than normalising embree's geometric normal on every hit.
  std::list<std::vector<Vec3>> prototype_normals;
  /// By geomID in `top`. Slot 0 is the flat geometry (below), attached only when it has
  /// triangles; the others are instances of rubble and link prototypes.
  std::vector<Instance> instances;
  std::vector<int> dynamic_instance;         ///< per World::dynamics: instance index (-1: empty mesh)
  std::vector<std::vector<int>> link_instance;  ///< per robot, per link: instance index or -1
  std::size_t triangles = 0;

  /// The flat geometry: the static objects' triangles and those of every sleeping rubble body,
  /// in the world frame, in one BVH. A ray through it visits no instance (the bare-Embree speed
  /// the lidar bench compares against); a rubble body leaves it while awake and is traced as an
  /// instance at its pose. Which bodies are in it is a function of State alone (their sleep),
  /// so a run, and a run restored from a snapshot, trace the same triangles.
  FloatMesh statics;                         ///< the static objects' triangles (world frame)
  std::vector<int> static_owner;             ///< per static triangle: World::statics index
  std::vector<FlatOwner> flat_owner;         ///< per flat triangle
  std::vector<Vec3> flat_normals;            ///< per flat triangle, unit, world frame
  std::vector<FloatMesh> rubble_mesh;        ///< per World::dynamics: its triangles in the body frame
  std::vector<char> flat_rubble;             ///< per World::dynamics: in the flat geometry now
  std::vector<Pose3> flat_pose;              ///< per World::dynamics: the pose it was flattened at

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    for (auto& i : instances) {
      if (i.geometry) rtcReleaseGeometry(i.geometry);
    }
    if (top) rtcReleaseScene(top);
    for (RTCScene s : prototypes) rtcReleaseScene(s);
  }

  /// (Re)builds the flat geometry (slot 0) from the statics and the rubble bodies marked in
  /// flat_rubble at flat_pose: the static triangles first, then each body's in World order.
  void build_flat() {
    FloatMesh mesh = statics;
    flat_owner.clear();
    for (int owner : static_owner) flat_owner.push_back({RayHit::Source::static_object, owner});
    for (std::size_t i = 0; i < rubble_mesh.size(); ++i) {
      if (!flat_rubble[i]) continue;
      const FloatMesh& body = rubble_mesh[i];
      const Eigen::Matrix3f R = flat_pose[i].q.toRotationMatrix().cast<float>();
      const Eigen::Vector3f p = flat_pose[i].p.cast<float>();
      const auto first = static_cast<unsigned>(mesh.vertex_count());
      for (std::size_t v = 0; v < body.vertex_count(); ++v) {
        const Eigen::Vector3f x = R * Eigen::Vector3f(body.vertices[3 * v], body.vertices[3 * v + 1], body.vertices[3 * v + 2]) + p;
        mesh.vertices.insert(mesh.vertices.end(), {x.x(), x.y(), x.z()});
      }
      for (unsigned idx : body.indices) mesh.indices.push_back(first + idx);
      flat_owner.insert(flat_owner.end(), body.triangle_count(), FlatOwner{RayHit::Source::dynamic_object, static_cast<int>(i)});
    }
    flat_normals = mesh.unit_normals();
    Instance& flat = instances[0];
    if (flat.geometry) {
      rtcDetachGeometry(top, 0);
      rtcReleaseGeometry(flat.geometry);
      flat.geometry = nullptr;
    }
    if (mesh.triangle_count() == 0) return;
    flat.geometry = raycast_detail::new_triangle_geometry(mesh);
    rtcSetGeometryBuildQuality(flat.geometry, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(flat.geometry);
    rtcAttachGeometryByID(top, flat.geometry, 0);
  }

  /// Keeps `prototype` (built from `mesh`) and adds an instance of it to the top-level scene at
  /// pose X_WP.
  int add_instance(RTCScene prototype, const FloatMesh& mesh, const Pose3& X_WP, RayHit::Source source, int index, RobotIndex robot) {
    prototypes.push_back(prototype);
    prototype_normals.push_back(mesh.unit_normals());
    triangles += mesh.triangle_count();
    Instance inst;
    inst.geometry = rtcNewGeometry(raycast_detail::embree_device(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst.geometry, prototype);
    inst.normals = &prototype_normals.back();
    inst.source = source;
    inst.index = index;
    inst.robot = robot;
    const auto id = static_cast<unsigned>(instances.size());
    instances.push_back(inst);
    move_instance(static_cast<int>(id), X_WP);
    rtcAttachGeometryByID(top, inst.geometry, id);
    return static_cast<int>(id);
  }

  /// Places an instance at X_WP (the top-level scene still needs a commit).
  void move_instance(int id, const Pose3& X_WP) {
    Instance& inst = instances[static_cast<std::size_t>(id)];
    float xfm[12];
    to_embree_transform(X_WP, xfm);
    rtcSetGeometryTransform(inst.geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(inst.geometry);
    inst.R_WP = X_WP.q.toRotationMatrix();
  }

  /// A prototype scene for the links of one robot: its triangles carry the ignore filter.
  RTCScene link_prototype(const FloatMesh& mesh, RobotIndex robot) {
    RTCScene s = rtcNewScene(raycast_detail::embree_device());
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = raycast_detail::new_triangle_geometry(mesh);
    // the robot's number rides in Embree's user pointer and comes back out in link_filter; never dereferenced
    rtcSetGeometryUserData(g, reinterpret_cast<void*>(static_cast<std::intptr_t>(robot.value())));  // NOLINT(performance-no-int-to-ptr)
    rtcSetGeometryIntersectFilterFunction(g, link_filter);
    rtcSetGeometryOccludedFilterFunction(g, link_filter);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    return s;
  }

  /// Traces up to 16 rays as one packet.
  void trace_packet(const Ray* rays, RayHit* hits, int n, RobotIndex ignore_robot) const {
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    // load the packet; lanes past the end and rays that are not finite stay inactive
    const Ray benign{Vec3::Zero(), Vec3::UnitX(), 0.0f};
    for (int i = 0; i < 16; ++i) {
      const bool active = i < n && finite(rays[i].origin) && finite(rays[i].direction);
      const Ray& r = active ? rays[i] : benign;
      valid[i] = active ? -1 : 0;
      rh.ray.org_x[i] = static_cast<float>(r.origin.x());
      rh.ray.org_y[i] = static_cast<float>(r.origin.y());
      rh.ray.org_z[i] = static_cast<float>(r.origin.z());
      rh.ray.dir_x[i] = static_cast<float>(r.direction.x());
      rh.ray.dir_y[i] = static_cast<float>(r.direction.y());
      rh.ray.dir_z[i] = static_cast<float>(r.direction.z());
      rh.ray.tnear[i] = 0.0f;
      rh.ray.tfar[i] = r.max_distance;
      rh.ray.time[i] = 0.0f;
      rh.ray.mask[i] = 0xFFFFFFFFu;
      rh.ray.id[i] = static_cast<unsigned>(i);
      rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    CastContext ctx = make_context(ignore_robot);
    rtcIntersect16(valid, top, &ctx.rtc, &rh);

    // turn embree hits into ours: which object, and the normal in the world facing the ray
    for (int i = 0; i < n; ++i) {
      RayHit h;
      if (!valid[i]) {
        h.distance = NAN;
      } else if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
        const unsigned inst_id = rh.hit.instID[0][i];
        const unsigned prim = rh.hit.primID[i];
        h.distance = rh.ray.tfar[i];
        Vec3 normal;
        if (inst_id == RTC_INVALID_GEOMETRY_ID) {
          // the flat geometry (slot 0): statics and sleeping rubble, world frame
          h.source = flat_owner[prim].source;
          h.index = flat_owner[prim].index;
          normal = flat_normals[prim];
        } else {
          const Instance& inst = instances[inst_id];
          h.source = inst.source;
          h.robot = inst.robot;
          h.index = inst.index;
          normal = inst.R_WP * (*inst.normals)[prim];
        }
        h.normal = normal.dot(rays[i].direction) > 0 ? Vec3(-normal) : normal;
      }
      hits[i] = h;
    }
  }
};

RayScene::RayScene(const World& world) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.top = rtcNewScene(raycast_detail::embree_device());
  // the top level is rebuilt at every update: a fast build over the static triangles (whose
  // own BVH is built once) and the instances
  rtcSetSceneFlags(s.top, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.top, RTC_BUILD_QUALITY_LOW);

  // slot 0: the flat geometry, all static objects (and later the sleeping rubble) in one
  // high-quality triangle geometry in the world frame
  s.statics = raycast_detail::static_triangles(world, &s.static_owner);
  s.triangles += s.statics.triangle_count();
  s.instances.emplace_back();
  s.instances[0].source = RayHit::Source::static_object;

  // each rubble body: its mesh in the body frame, instanced at its initial pose (it joins the
  // flat geometry when update() sees it asleep)
  for (std::size_t i = 0; i < world.dynamics.size(); ++i) {
    const DynamicObject& d = world.dynamics[i];
    FloatMesh mesh;
    mesh.append(mesh_of(d.geometry, raycast_detail::kRoundSegments), Pose3{});
    s.dynamic_instance.push_back(-1);
    s.rubble_mesh.push_back(mesh);
    if (mesh.triangle_count() == 0) continue;
    s.dynamic_instance.back() = s.add_instance(raycast_detail::new_mesh_scene(mesh, RTC_BUILD_QUALITY_MEDIUM), mesh, d.X_WO,
                                               RayHit::Source::dynamic_object, static_cast<int>(i), RobotIndex());
  }
  s.flat_rubble.assign(world.dynamics.size(), 0);
  s.flat_pose.assign(world.dynamics.size(), Pose3{});
  s.build_flat();

  // each robot link: all its shapes in the link frame, instanced at the start pose
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    const RobotInstance& robot = world.robots[r];
    const auto X_BL = link_poses(robot.spec, initial_positions(robot.spec));
    s.link_instance.emplace_back(robot.spec.links.size(), -1);
    for (std::size_t l = 0; l < robot.spec.links.size(); ++l) {
      FloatMesh mesh;
      for (const LinkShape& shape : robot.spec.links[l].shapes)
        mesh.append(mesh_of(shape.geometry, raycast_detail::kRoundSegments), shape.X_LG);
      if (mesh.triangle_count() == 0) continue;
      s.link_instance[r][l] = s.add_instance(s.link_prototype(mesh, RobotIndex::at(r)), mesh, robot.X_W_start * X_BL[l],
                                             RayHit::Source::robot_link, static_cast<int>(l), RobotIndex::at(r));
    }
  }
  rtcCommitScene(s.top);
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

void RayScene::update(const State& state) {
  Impl& s = *impl_;
  RS_DEMAND(state.dynamics.size() == s.dynamic_instance.size(), "RayScene::update: State::dynamics does not match the World");
  RS_DEMAND(state.robots.size() == s.link_instance.size(), "RayScene::update: State::robots does not match the World");
  // a sleeping body is part of the flat geometry at its pose; an awake one is an instance
  bool rebuild = false;
  for (std::size_t i = 0; i < s.dynamic_instance.size(); ++i) {
    const int inst = s.dynamic_instance[i];
    if (inst < 0) continue;
    const BodyState& b = state.dynamics[i];
    const bool flat = b.sleep == BodyState::Sleep::asleep && s.statics.triangle_count() <= kFlatRubbleMaxStaticTriangles;
    if (flat != static_cast<bool>(s.flat_rubble[i]) ||
        (flat && !(b.X_WB.p == s.flat_pose[i].p && b.X_WB.q.coeffs() == s.flat_pose[i].q.coeffs()))) {
      s.flat_rubble[i] = flat;
      s.flat_pose[i] = b.X_WB;
      rebuild = true;
      if (flat) rtcDisableGeometry(s.instances[static_cast<std::size_t>(inst)].geometry);
      else rtcEnableGeometry(s.instances[static_cast<std::size_t>(inst)].geometry);
    }
    if (!flat) s.move_instance(inst, b.X_WB);
  }
  if (rebuild) s.build_flat();
  for (std::size_t r = 0; r < s.link_instance.size(); ++r) {
    const auto& links = s.link_instance[r];
    RS_DEMAND(state.robots[r].X_WL.size() == links.size(), "RayScene::update: RobotState::X_WL needs one pose per link");
    for (std::size_t l = 0; l < links.size(); ++l) {
      if (links[l] >= 0) s.move_instance(links[l], state.robots[r].X_WL[l]);
    }
  }
  rtcCommitScene(s.top);
}

void RayScene::cast(std::span<const Ray> rays, std::span<RayHit> hits, RobotIndex ignore_robot) const {
  RS_DEMAND(rays.size() == hits.size(), "RayScene::cast: rays and hits differ in size");
  const Impl& s = *impl_;
  const std::size_t n = rays.size();
  const std::size_t packets = (n + 15) / 16;
  auto run = [&](std::size_t first, std::size_t last) {
    for (std::size_t p = first; p < last; ++p) {
      const std::size_t begin = p * 16;
      s.trace_packet(rays.data() + begin, hits.data() + begin, static_cast<int>(std::min<std::size_t>(16, n - begin)), ignore_robot);
    }
  };
  // each packet writes only its own hits, so any split over threads gives the same answer; the
  // work is isolated so a thread waiting here never picks up its caller's other tasks (callers
  // keep per-thread buffers across this call)
  if (n < kParallelMinRays || worker_threads() == 1) {
    run(0, packets);
  } else {
    // on the process's pool (core/parallel.h, isolated like this), kPacketsPerTask a task
    const std::size_t tasks = (packets + kPacketsPerTask - 1) / kPacketsPerTask;
    parallel_for(tasks, [&](std::size_t t) { run(t * kPacketsPerTask, std::min(packets, (t + 1) * kPacketsPerTask)); });
  }
}

bool RayScene::occluded(const Vec3& from, const Vec3& to, RobotIndex ignore_robot) const {
  const Vec3 d = to - from;
  const double length = d.norm();
  if (!(length > kOcclusionSlack) || !finite(from) || !finite(to)) return false;
  const Vec3 dir = d / length;
  RTCRay ray;
  ray.org_x = static_cast<float>(from.x());
  ray.org_y = static_cast<float>(from.y());
  ray.org_z = static_cast<float>(from.z());
  ray.dir_x = static_cast<float>(dir.x());
  ray.dir_y = static_cast<float>(dir.y());
  ray.dir_z = static_cast<float>(dir.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(length - kOcclusionSlack);
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  CastContext ctx = make_context(ignore_robot);
  rtcOccluded1(impl_->top, &ctx.rtc, &ray);
  // embree marks an occluded ray by setting tfar to -inf
  return ray.tfar < 0.0f;
}

std::size_t RayScene::triangle_count() const { return impl_->triangles; }

}  // namespace rescuesim
