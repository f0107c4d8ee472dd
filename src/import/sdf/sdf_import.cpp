// SDF worlds → WorldSpec: each model becomes what its name and kind say (victim, robot start,
// static geometry, loose bodies or a robot); lights, gravity and the physics step are kept.
#include "import/sdf/sdf_import.h"

#include <Eigen/Eigenvalues>

#include <chrono>
#include <cmath>

#include "import/sdf/sdf_detail.h"

namespace rescuesim {

namespace {

using namespace sdf_detail;
using Clock = std::chrono::steady_clock;

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

/// gz-sim systems whose work rescuesim does itself: listed as ignored without a warning.
bool is_standard_world_system(const std::string& filename) {
  for (const char* s : {"physics-system", "sensors-system", "scene-broadcaster-system", "user-commands-system", "contact-system",
                        "imu-system", "Physics", "Sensors", "SceneBroadcaster", "UserCommands"}) {
    if (filename.find(s) != std::string::npos) return true;
  }
  return false;
}

/// True when the element path below `e` is written in the file (sdformat fills in defaults).
bool explicitly_set(sdf::ElementPtr e, std::initializer_list<const char*> path) {
  for (const char* name : path) {
    if (!e || !e->HasElement(name)) return false;
    e = e->GetElement(name);
    if (!e->GetExplicitlySetInFile()) return false;
  }
  return true;
}

/// The name a robot_start model gives its robot: the rest of its name, or "robot".
std::string start_name(const std::string& model) {
  std::string rest = model.substr(std::string("robot_start").size());
  while (!rest.empty() && rest.front() == '_') rest.erase(rest.begin());
  return rest.empty() ? "robot" : rest;
}

/// True when a piece is, in the frame X_FP, the primitive itself at the origin of F.
bool is_primitive_at_origin(const Piece& p, const Pose3& X_FP) {
  const Geometry::Type t = p.geometry.type;
  if (t != Geometry::Type::box && t != Geometry::Type::sphere && t != Geometry::Type::cylinder) return false;
  if (X_FP.p.norm() > 1e-9) return false;
  return t == Geometry::Type::sphere || X_FP.q.angularDistance(Quat::Identity()) < 1e-9;
}

/// Principal moments and axes (rotation from the inertial frame I to the body frame B) of an
/// inertia tensor. A tensor that is already diagonal keeps its axes (no reordering).
std::pair<Vec3, Quat> principal(const Eigen::Matrix3d& I) {
  const double off = std::abs(I(0, 1)) + std::abs(I(0, 2)) + std::abs(I(1, 2));
  if (off <= 1e-12 * std::max(I.trace(), 1e-300)) return {I.diagonal(), Quat::Identity()};
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(I);
  Eigen::Matrix3d V = solver.eigenvectors();
  if (V.determinant() < 0) V.col(2) = -V.col(2);
  return {solver.eigenvalues(), Quat(V).normalized()};
}

/// Reads models, lights and settings of a world into an SdfWorld.
class WorldReader {
 public:
  WorldReader(SdfWorld& out, Reader& r) : out_(out), r_(r) {}

  void world(const sdf::World& w) {
    WorldSpec& spec = out_.spec;
    spec.name = w.Name();
    const SourceRef at_world = r_.at(w.Element());
    const Vec3 g = vec_of(w.Gravity());
    if (explicitly_set(w.Element(), {"gravity"})) {
      spec.gravity = g.norm();
      if (spec.gravity > 0 && g.normalized().z() > -1 + 1e-9) {
        r_.diagnostics.warn(
            at_world, "<gravity> does not point along -z: rescuesim uses its size, " + std::to_string(spec.gravity) + " m/s^2, downwards");
      }
    }
    if (explicitly_set(w.Element(), {"physics", "max_step_size"}) && w.PhysicsDefault())
      spec.physics_dt = w.PhysicsDefault()->MaxStepSize();
    for (const auto& [filename, plugin] : plugins_of(w.Element())) {
      out_.plugins_ignored.push_back("world::" + filename);
      if (!is_standard_world_system(filename))
        r_.diagnostics.warn(r_.at(plugin), "world plugin '" + filename + "' is ignored: rescuesim does not know what it does");
    }
    for (uint64_t i = 0; i < w.LightCount(); ++i) {
      const sdf::Light& l = *w.LightByIndex(i);
      light(l, resolve(l.SemanticPose(), "", r_.at(l.Element())));
    }
    for (uint64_t i = 0; i < w.ModelCount(); ++i) {
      const sdf::Model& m = *w.ModelByIndex(i);
      const SourceRef at = r_.at(m.Element());
      model(m, m.Name(), resolve(m.SemanticPose(), "", at), false);
    }
  }

  void light(const sdf::Light& l, const Pose3& X_WL) {
    const SourceRef at = r_.at(l.Element());
    check_pose(X_WL, r_.options.max_extent, at, "the light's pose");
    LightSpec ls;
    ls.type = l.Type() == sdf::LightType::POINT ? LightSpec::Type::point
              : l.Type() == sdf::LightType::SPOT ? LightSpec::Type::spot
                                                 : LightSpec::Type::directional;
    ls.name = l.Name();
    ls.position = X_WL.p;
    const Vec3 d = X_WL.q * vec_of(l.Direction());
    ls.direction = d.norm() > 1e-12 ? Vec3(d.normalized()) : Vec3(-Vec3::UnitZ());
    ls.range = std::isfinite(l.AttenuationRange()) ? std::max(0.0, l.AttenuationRange()) : 0.0;
    // SDF's outer_angle is the whole cone (as Ogre's spotlight range); LightSpec keeps the half
    ls.spot_angle = ls.type == LightSpec::Type::spot ? 0.5 * l.SpotOuterAngle().Radian() : 0.0;
    ls.color = color_of(l.Diffuse()).cwiseMax(0.0).cwiseMin(1.0);
    ls.intensity = l.Element()->HasElement("intensity") ? l.Intensity() : 1.0;
    ls.casts_shadows = l.CastShadows();
    out_.spec.lights.push_back(ls);
    SdfModelReport rep;
    rep.name = l.Name();
    rep.becomes = "light";
    rep.source = at.str();
    out_.models.push_back(rep);
  }

  /// A model named `name` (scoped for nested models) at X_WM.
  void model(const sdf::Model& m, const std::string& name, const Pose3& X_WM, bool parent_static) {
    const SourceRef at = r_.at(m.Element());
    check_pose(X_WM, r_.options.max_extent, at, "the pose of model '" + name + "'");
    SdfModelReport rep;
    rep.name = name;
    rep.is_static = parent_static || m.Static();
    rep.links = static_cast<int>(m.LinkCount());
    rep.joints = static_cast<int>(m.JointCount());
    for (uint64_t i = 0; i < m.LinkCount(); ++i) {
      rep.collisions += static_cast<int>(m.LinkByIndex(i)->CollisionCount());
      rep.visuals += static_cast<int>(m.LinkByIndex(i)->VisualCount());
    }
    rep.source = at.str();
    const std::string own = name.substr(name.rfind("::") == std::string::npos ? 0 : name.rfind("::") + 2);
    if (starts_with(own, "robot_start")) {
      rep.becomes = "robot start";
      out_.spec.robots.push_back({start_name(own), "rescue_robot", X_WM.to_pose2(), at, X_WM.p.z()});
    } else if (starts_with(own, "victim")) {
      rep.becomes = "victim";
      victim(m, name, X_WM, at);
    } else {
      rep.becomes = body_of_model(m, name, X_WM, rep.is_static, at);
      for (uint64_t i = 0; i < m.ModelCount(); ++i) {
        const sdf::Model& n = *m.ModelByIndex(i);
        model(n, name + "::" + n.Name(), X_WM * resolve(n.SemanticPose(), "", r_.at(n.Element())), rep.is_static);
      }
    }
    out_.models.push_back(rep);
  }

 private:
  /// The links of a model that are not a victim or a start; returns what the model became.
  std::string body_of_model(const sdf::Model& m, const std::string& name, const Pose3& X_WM, bool is_static, const SourceRef& at) {
    if (m.LinkCount() == 0) return m.ModelCount() > 0 ? "nested models" : "ignored";
    // links fixed to the world stand still, whatever the model
    std::vector<std::string> fixed;
    int moving_joints = 0;
    for (uint64_t i = 0; i < m.JointCount(); ++i) {
      const sdf::Joint& j = *m.JointByIndex(i);
      std::string parent, child;
      if (j.ResolveParentLink(parent).empty() && j.ResolveChildLink(child).empty() && parent == "world" &&
          j.Type() == sdf::JointType::FIXED) {
        fixed.push_back(child);
      } else {
        ++moving_joints;
      }
    }
    std::vector<const sdf::Link*> still, loose;
    for (uint64_t i = 0; i < m.LinkCount(); ++i) {
      const sdf::Link* l = m.LinkByIndex(i);
      (is_static || std::find(fixed.begin(), fixed.end(), l->Name()) != fixed.end() ? still : loose).push_back(l);
    }
    int solids = 0, floors = 0;
    for (const sdf::Link* l : still) {
      const auto [added, skipped] = solids_of(*l, name, X_WM, "", "obstacle");
      solids += added;
      floors += skipped;
      link_lights(*l, name, X_WM, true);
    }
    if (loose.empty()) return solids == 0 && floors > 0 ? "floor" : "static geometry";
    if (moving_joints == 0) {
      for (const sdf::Link* l : loose) {
        body(*l, name, X_WM);
        link_lights(*l, name, X_WM, false);
      }
      return "rigid body";
    }
    robot(m, name, X_WM, fixed, at);
    return "robot";
  }

  /// The lights of a world model's link (a robot's are its lamps, sdf_robot.cpp): on a link that
  /// stands still they are world lights where the link puts them; on a loose body they are left
  /// out with a warning, as the renderer moves only robots' lamps.
  void link_lights(const sdf::Link& l, const std::string& name, const Pose3& X_WM, bool still) {
    if (l.LightCount() == 0) return;
    const std::string context = "<model name=\"" + name + "\">";
    const Pose3 X_WL = X_WM * resolve(l.SemanticPose(), "__model__", r_.at(l.Element(), context));
    for (uint64_t i = 0; i < l.LightCount(); ++i) {
      const sdf::Light& light_L = *l.LightByIndex(i);
      const SourceRef at = r_.at(light_L.Element(), context);
      if (still) {
        light(light_L, X_WL * resolve(light_L.SemanticPose(), "", at));
      } else {
        r_.diagnostics.warn(at, "light '" + light_L.Name() + "' on the loose body '" + name + "::" + l.Name() +
                                    "' is left out: only robots' lights move with their links");
      }
    }
  }

  /// Adds the solids of a link's collisions; returns (solids added, floor planes skipped).
  std::pair<int, int> solids_of(const sdf::Link& l, const std::string& name, const Pose3& X_WM, const std::string& victim,
                                const std::string& fallback) {
    const std::string context = "<model name=\"" + name + "\">";
    const Pose3 X_WL = X_WM * resolve(l.SemanticPose(), "__model__", r_.at(l.Element(), context));
    int solids = 0, floors = 0;
    for (uint64_t i = 0; i < l.CollisionCount(); ++i) {
      const sdf::Collision& c = *l.CollisionByIndex(i);
      const SourceRef at = r_.at(c.Element(), context);
      const Pose3 X_WC = X_WL * resolve(c.SemanticPose(), "", at);
      check_pose(X_WC, r_.options.max_extent, at, "the collision's pose");
      const Shape shape = shape_of(*c.Geom(), X_WC, MeshUse::exact, {name, l.Name(), describe(c.Element()), true}, r_);
      floors += shape.floor;
      const std::string material =
          material_of(l, &c, name, shape.mesh_color, *out_.spec.find_material(fallback), out_.spec.materials);
      for (std::size_t k = 0; k < shape.pieces.size(); ++k) {
        SolidSpec s;
        s.name = name + "::" + l.Name() + "::" + c.Name() + (shape.pieces.size() > 1 ? "#" + std::to_string(k) : "");
        s.geometry = shape.pieces[k].geometry;
        s.X_WS = X_WC * shape.pieces[k].X_GP;
        s.material = material;
        s.victim = victim;
        s.source = at;
        out_.spec.solids.push_back(std::move(s));
        ++solids;
      }
    }
    return {solids, floors};
  }

  void victim(const sdf::Model& m, const std::string& name, const Pose3& X_WM, const SourceRef& at) {
    VictimSpec v;
    v.name = name;
    v.figure = false;
    v.pose = X_WM.to_pose2();
    v.skin_temperature = 307.15;
    v.source = at;
    const std::size_t first = out_.spec.solids.size();
    for (uint64_t i = 0; i < m.LinkCount(); ++i) solids_of(*m.LinkByIndex(i), name, X_WM, name, "victim_clothes");
    // its extent along and across the model's x axis, from its solids' vertices
    const Pose3 X_MW = Pose3::from_pose2(v.pose).inverse();
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (std::size_t k = first; k < out_.spec.solids.size(); ++k) {
      const SolidSpec& s = out_.spec.solids[k];
      const TriangleMesh mesh =
          s.geometry.type == Geometry::Type::mesh || s.geometry.type == Geometry::Type::convex ? s.geometry.mesh : mesh_of(s.geometry, 8);
      for (const Vec3& p : mesh.vertices) {
        const Vec3 q = X_MW * (s.X_WS * p);
        lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      }
    }
    if (first == out_.spec.solids.size()) {
      r_.diagnostics.warn(at, "victim model '" + name + "' has no collision shapes: it has no body to find");
    } else {
      v.length = std::max(0.05, hi.x() - lo.x());
      v.width = std::max(0.05, hi.y() - lo.y());
    }
    out_.spec.victims.push_back(v);
  }

  /// A loose rigid body: one shape in its principal-axes frame at the centre of mass.
  void body(const sdf::Link& l, const std::string& name, const Pose3& X_WM) {
    const std::string context = "<model name=\"" + name + "\">";
    const SourceRef at = r_.at(l.Element(), context);
    const Pose3 X_WL = X_WM * resolve(l.SemanticPose(), "__model__", at);
    std::vector<Piece> pieces_L;
    std::optional<Vec3> mesh_color;
    for (uint64_t i = 0; i < l.CollisionCount(); ++i) {
      const sdf::Collision& c = *l.CollisionByIndex(i);
      const SourceRef at_c = r_.at(c.Element(), context);
      const Pose3 X_LC = resolve(c.SemanticPose(), "", at_c);
      check_pose(X_WL * X_LC, r_.options.max_extent, at_c, "the collision's pose");
      const Shape shape = shape_of(*c.Geom(), X_WL * X_LC, MeshUse::convex, {name, l.Name(), describe(c.Element()), true}, r_);
      if (shape.mesh_color && !mesh_color) mesh_color = shape.mesh_color;
      for (const Piece& p : shape.pieces) pieces_L.push_back({p.geometry, X_LC * p.X_GP});
    }
    if (pieces_L.empty()) {
      r_.diagnostics.warn(at, "link '" + l.Name() + "' of model '" + name + "' has no collision shape: it is left out");
      return;
    }
    const Inertial in = inertial_of(l, pieces_L, name, r_);
    const auto [moments, q_IB] = principal(in.I);
    const Pose3 X_LB = in.X_LI * Pose3{Vec3::Zero(), q_IB};
    const Pose3 X_BL = X_LB.inverse();

    BodySpec b;
    b.name = name + "::" + l.Name();
    b.X_WB = X_WL * X_LB;
    b.mass = in.mass;
    b.inertia = moments;
    b.source = at;
    if (pieces_L.size() == 1 && is_primitive_at_origin(pieces_L.front(), X_BL * pieces_L.front().X_GP)) {
      b.geometry = pieces_L.front().geometry;
    } else if (pieces_L.size() == 1 && pieces_L.front().geometry.type == Geometry::Type::convex) {
      // one convex shape (a capsule, an ellipsoid, a mesh's hull): moved into the body frame as
      // it is, not hulled again to the vertex budget, which would cut off a capsule's poles
      TriangleMesh mesh = pieces_L.front().geometry.mesh;
      const Pose3 X_BG = X_BL * pieces_L.front().X_GP;
      for (Vec3& v : mesh.vertices) v = X_BG * v;
      b.geometry = Geometry::convex(std::move(mesh));
    } else {
      // the union of the shapes as one convex hull in the body frame
      std::vector<Vec3> points;
      for (const Piece& p : pieces_L) {
        const TriangleMesh mesh = p.geometry.type == Geometry::Type::convex ? p.geometry.mesh : mesh_of(p.geometry, 24);
        for (const Vec3& v : mesh.vertices) points.push_back(X_BL * (p.X_GP * v));
      }
      b.geometry = Geometry::convex(convex_hull(points, r_.options.hull_vertices));
      if (pieces_L.size() > 1) {
        r_.diagnostics.warn(at, "link '" + l.Name() + "' of model '" + name + "' has " + std::to_string(pieces_L.size()) +
                                    " collision shapes: the loose body is their convex hull");
      }
    }
    b.material = material_of(l, l.CollisionByIndex(0), name, mesh_color, *out_.spec.find_material("rubble"), out_.spec.materials);
    out_.spec.bodies.push_back(std::move(b));
  }

  void robot(const sdf::Model& m, const std::string& name, const Pose3& X_WM, const std::vector<std::string>& fixed, const SourceRef& at) {
    RobotExtras extras;
    RobotSpec spec = build_robot(m, name, fixed, r_, extras);
    spec.source_file = at.file;
    out_.plugins_honoured.insert(out_.plugins_honoured.end(), extras.plugins_honoured.begin(), extras.plugins_honoured.end());
    out_.plugins_ignored.insert(out_.plugins_ignored.end(), extras.plugins_ignored.begin(), extras.plugins_ignored.end());
    // the robot stands where its root link is
    const sdf::Link& root = *m.LinkByName(spec.links.front().name);
    const Pose3 X_WR = X_WM * resolve(root.SemanticPose(), "__model__", r_.at(root.Element()));
    out_.robots[name] = std::move(spec);
    out_.spec.robots.push_back({name, name, X_WR.to_pose2(), at, X_WR.p.z()});
  }

  SdfWorld& out_;
  Reader& r_;
};

/// Sets (or, `grow`, widens) the floor to what the world holds, 1 m around it, at least 2 x 2 m.
void fit_floor(WorldSpec& spec, bool grow) {
  Box2 b = spec.content_bounds();
  if (b.empty()) b.extend(Vec2::Zero());
  Vec2 lo = b.min - Vec2::Ones(), hi = b.max + Vec2::Ones();
  const Vec2 centre = 0.5 * (lo + hi);
  lo = lo.cwiseMin(centre - Vec2::Ones());
  hi = hi.cwiseMax(centre + Vec2::Ones());
  spec.floor_min = grow ? Vec2(spec.floor_min.cwiseMin(lo)) : lo;
  spec.floor_max = grow ? Vec2(spec.floor_max.cwiseMax(hi)) : hi;
}

}  // namespace

bool is_sdf_path(const std::filesystem::path& file) { return file.extension() == ".sdf" || file.extension() == ".world"; }

SdfWorld parse_sdf_world(const std::string& text, const std::string& file, const SdfOptions& options) {
  const auto t0 = Clock::now();
  SdfWorld out;
  out.spec.materials = default_materials();
  out.spec.source_file = file;
  Parsed parsed;
  parse_sdf(text, file, options, parsed, out.diagnostics);
  out.sdf_version = parsed.declared_version;
  out.parse_seconds = parsed.seconds;
  Reader reader{options, file, out.diagnostics, out.meshes, {}};
  WorldReader world(out, reader);
  if (parsed.root.WorldCount() > 0) {
    if (parsed.root.WorldCount() > 1) out.diagnostics.warn({file, 0, "<world>"}, "the file holds several worlds: only the first is read");
    world.world(*parsed.root.WorldByIndex(0));
  } else if (const sdf::Model* m = parsed.root.Model()) {
    out.spec.name = m->Name();
    world.model(*m, m->Name(), pose_of(m->RawPose()), false);
  } else if (const sdf::Light* l = parsed.root.Light()) {
    world.light(*l, pose_of(l->RawPose()));
  } else {
    throw Error({file, 0, "<sdf>"}, "no <world>, <model> or <light> in the file");
  }
  if (out.spec.name.empty()) out.spec.name = std::filesystem::path(file).stem().string();
  fit_floor(out.spec, false);
  out.load_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

SdfWorld load_sdf_world(const std::filesystem::path& file, const SdfOptions& options) {
  return parse_sdf_world(read_text(file), file.string(), options);
}

void add_sdf_includes(const std::vector<SdfInclude>& includes, const SdfOptions& options, SdfWorld& report) {
  const auto t0 = Clock::now();
  if (report.spec.materials.empty()) report.spec.materials = default_materials();
  Reader reader{options, "", report.diagnostics, report.meshes, {}};
  WorldReader world(report, reader);
  for (const SdfInclude& inc : includes) {
    const std::filesystem::path file = resolve_model_uri(inc.uri, options, inc.source);
    Parsed parsed;
    parse_sdf(read_text(file), file.string(), options, parsed, report.diagnostics);
    report.parse_seconds += parsed.seconds;
    const sdf::Model* m = parsed.root.Model();
    if (!m) throw Error(inc.source, "'" + inc.uri + "' (" + file.string() + ") holds no <model> to include");
    reader.file = file.string();
    const std::string name = inc.name.empty() ? m->Name() : inc.name;
    world.model(*m, name, inc.has_pose ? inc.pose : pose_of(m->RawPose()), false);
  }
  fit_floor(report.spec, true);
  report.load_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace rescuesim
