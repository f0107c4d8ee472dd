#include <cctype>
#include <algorithm>
#include <cmath>
#include <limits>

#include "world/world.h"
#include "world/terrain.h"

namespace rescuesim {

int World::material_index(const std::string& name) const {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return static_cast<int>(i);
  }
  throw Error({"", 0, "material '" + name + "'"}, "unknown material");
}

double World::temperature_of(const StaticObject& o) const {
  if (o.temperature > 0) return o.temperature;
  const double t = materials[static_cast<std::size_t>(o.material)].temperature;
  return t > 0 ? t : ambient_temperature;
}

namespace {

Pose3 pose_at(const Vec2& p, double z, double yaw) { return Pose3::from_pose2({p.x(), p.y(), yaw}, z); }

/// A prism from a planar outline, as a convex shape when it is convex.
Geometry prism(const Polygon2& outline, double z0, double z1) {
  TriangleMesh m = extrude(outline, z0, z1);
  return is_convex(outline) ? Geometry::convex(std::move(m)) : Geometry::triangles(std::move(m));
}

/// The wedge of a ramp: high along the platform edge (a, b), down to the floor `out` away.
Geometry ramp_wedge(const Polygon2& quad, double height) {
  // quad = {a_out, b_out, b, a} from WorldSpec::ramp_outline
  TriangleMesh m;
  m.vertices = {{quad[0].x(), quad[0].y(), 0}, {quad[1].x(), quad[1].y(), 0}, {quad[2].x(), quad[2].y(), 0},
                {quad[3].x(), quad[3].y(), 0}, {quad[2].x(), quad[2].y(), height}, {quad[3].x(), quad[3].y(), height}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}, {0, 4, 5}, {2, 3, 5}, {2, 5, 4}, {1, 2, 4}, {0, 3, 5}};
  orient_outward(m);
  return Geometry::convex(std::move(m));
}

}  // namespace

std::vector<BodyPart> victim_body(const VictimSpec& v) {
  std::vector<BodyPart> parts;
  const double L = v.length, W = v.width;
  const Pose3 X_WV = Pose3::from_pose2(v.pose);
  // local frame: x from feet to head, y to the victim's left, z up
  const double head_r = 0.07 * L;
  const double limb_r = 0.035 * L;
  const double torso_len = 0.36 * L, torso_th = 0.12 * L;
  const double leg_len = 0.46 * L, arm_len = 0.33 * L;
  auto add = [&](const Geometry& g, const Pose3& X_VP, bool skin) { parts.push_back({g, X_WV * X_VP, skin}); };
  const Quat along_x(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
  if (v.posture == VictimSpec::Posture::lying) {
    const double x_head = L / 2 - head_r;
    const double x_torso = x_head - head_r - 0.03 * L - torso_len / 2;
    const double x_legs = -L / 2 + leg_len / 2;
    add(Geometry::sphere(head_r), {Vec3(x_head, 0, head_r), Quat::Identity()}, true);
    add(Geometry::box({torso_len, 0.8 * W, torso_th}), {Vec3(x_torso, 0, torso_th / 2), Quat::Identity()}, false);
    for (double side : {-1.0, 1.0}) {
      add(Geometry::cylinder(limb_r * 1.3, leg_len), {Vec3(x_legs, side * 0.18 * W, limb_r * 1.3), along_x}, false);
      const double y_arm = side * (0.4 * W + limb_r);
      add(Geometry::cylinder(limb_r, arm_len), {Vec3(x_torso - 0.05 * L, y_arm, limb_r), along_x}, false);
      add(Geometry::sphere(limb_r * 1.2), {Vec3(x_torso - 0.05 * L - arm_len / 2 - limb_r, y_arm, limb_r * 1.2), Quat::Identity()}, true);
    }
  } else {
    // seated on the floor against something behind them (-x), legs stretched forward (+x)
    const double hip_x = -0.12 * L;
    const double torso_h = torso_len;
    add(Geometry::box({torso_th, 0.8 * W, torso_h}), {Vec3(hip_x, 0, torso_h / 2 + 0.02 * L), Quat::Identity()}, false);
    add(Geometry::sphere(head_r), {Vec3(hip_x, 0, torso_h + 0.02 * L + head_r * 1.1), Quat::Identity()}, true);
    for (double side : {-1.0, 1.0}) {
      add(Geometry::cylinder(limb_r * 1.3, leg_len), {Vec3(hip_x + leg_len / 2, side * 0.18 * W, limb_r * 1.3), along_x}, false);
      const double y_arm = side * (0.4 * W + limb_r);
      add(Geometry::cylinder(limb_r, arm_len), {Vec3(hip_x + 0.02, y_arm, 0.02 * L + arm_len / 2 + 0.05 * L), Quat::Identity()}, false);
      add(Geometry::sphere(limb_r * 1.2), {Vec3(hip_x + 0.02, y_arm, 0.02 * L + 0.05 * L), Quat::Identity()}, true);
    }
  }
  return parts;
}

namespace {
/// Adds `m` unless a material of its name is already there.
void add_missing(std::vector<MaterialSpec>& materials, const MaterialSpec& m) {
  for (const auto& x : materials) {
    if (x.name == m.name) return;
  }
  materials.push_back(m);
}

}  // namespace

/// Adds every robot's own materials (RobotSpec::materials, e.g. a URDF's) to the world's.
void add_robot_materials(World& world) {
  for (const auto& r : world.robots) {
    for (const auto& m : r.spec.materials) add_missing(world.materials, m);
  }
}

namespace {

/// The lowest z of a robot's collision shapes with its base frame at `X_W`, at its initial
/// joint positions; +infinity when it has no collision shape.
double lowest_point(const RobotSpec& spec, const Pose3& X_W) {
  const auto X_BL = link_poses(spec, initial_positions(spec));
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < spec.links.size(); ++l) {
    for (const auto& shape : spec.links[l].shapes) {
      if (!shape.collides) continue;
      for (const auto& v : mesh_of(shape.geometry, 16).vertices) lowest = std::min(lowest, (X_W * (X_BL[l] * (shape.X_LG * v))).z());
    }
  }
  return lowest;
}

}  // namespace

RobotInstance place_robot(std::string name, RobotSpec spec, const Pose3& X_W) {
  RobotInstance r;
  r.name = std::move(name);
  r.X_W_start = X_W;
  // the lowest point at this pose, in the world: raise the robot when it is below the floor
  const double floor_gap = 0.002;
  const double lowest = lowest_point(spec, X_W);
  if (std::isfinite(lowest) && lowest < floor_gap) r.X_W_start.p.z() += floor_gap - lowest;
  r.spec = std::move(spec);
  return r;
}

World compile_world(const WorldSpec& spec, const std::map<std::string, RobotSpec>& models, const CompileOptions& options) {
  World w;
  w.name = spec.name;
  w.floor = Box2{spec.floor_min, spec.floor_max};
  w.ambient_temperature = spec.ambient_temperature;
  w.gravity = spec.gravity;
  w.materials = spec.materials;
  w.lights = spec.lights;
  w.ambient_light = spec.ambient_light;
  w.sun = spec.sun;
  // no sun: the lights the SVG and maze loaders made up (unnamed) go, and a Gazebo world's sun
  // (a directional light named "sun", as gz-sim's worlds name theirs); a model file's other
  // lights stay
  if (!spec.sun) {
    std::erase_if(w.lights, [](const LightSpec& l) {
      std::string name = l.name;
      for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return l.name.empty() || (l.type == LightSpec::Type::directional && name == "sun");
    });
  }
  w.media = spec.media;
  w.world_seed = spec.seed;
  // robots need their materials even when a hand-built spec left them out
  for (const auto& m : default_materials()) add_missing(w.materials, m);

  // the floor: a slab whose top is z = 0, a margin wider than the drawing
  {
    const Vec2 size = spec.floor_max - spec.floor_min + Vec2::Constant(2 * options.floor_margin);
    const Vec2 c = 0.5 * (spec.floor_min + spec.floor_max);
    w.statics.push_back({"floor", ObjectKind::floor, Geometry::box({size.x(), size.y(), options.floor_thickness}),
                         pose_at(c, -options.floor_thickness / 2, 0), w.material_index(spec.floor_material), -1, VictimIndex()});
  }
  for (std::size_t i = 0; i < spec.walls.size(); ++i) {
    const WallSpec& s = spec.walls[i];
    const Vec2 d = s.b - s.a;
    w.statics.push_back({"wall_" + std::to_string(i), ObjectKind::wall, Geometry::box({d.norm(), s.thickness, s.height}),
                         pose_at(0.5 * (s.a + s.b), s.height / 2, std::atan2(d.y(), d.x())), w.material_index(s.material), -1,
                         VictimIndex()});
  }
  for (std::size_t i = 0; i < spec.blocks.size(); ++i) {
    const BlockSpec& b = spec.blocks[i];
    w.statics.push_back({"obstacle_" + std::to_string(i), ObjectKind::obstacle, prism(normalized(b.outline), 0, b.height), Pose3{},
                         w.material_index(b.material), -1, VictimIndex()});
  }
  for (std::size_t i = 0; i < spec.raised_areas.size(); ++i) {
    const RaisedAreaSpec& r = spec.raised_areas[i];
    const int mat = w.material_index(r.material);
    w.statics.push_back(
        {"platform_" + std::to_string(i), ObjectKind::platform, prism(r.outline, 0, r.height), Pose3{}, mat, -1, VictimIndex()});
    for (int e : r.ramp_edges) {
      w.statics.push_back({"ramp_" + std::to_string(i) + "_" + std::to_string(e), ObjectKind::ramp,
                           ramp_wedge(WorldSpec::ramp_outline(r, e), r.height), Pose3{}, mat, -1, VictimIndex()});
    }
  }
  // test-method terrain: posts, steps and decks are platforms (ground to drive on), wedges ramps
  for (const TerrainSpec& t : spec.terrain) {
    const int mat = w.material_index(t.material);
    for (TerrainSolid& so : terrain_solids(t)) {
      w.statics.push_back(
          {std::move(so.name), so.ramp ? ObjectKind::ramp : ObjectKind::platform, std::move(so.geometry), so.X_WS, mat, -1, VictimIndex()});
    }
  }
  // floor patches: no solids, only the floor's material inside their footprints
  for (const GroundAreaSpec& g : spec.ground) {
    w.ground.push_back({g.name, normalized(g.outline), w.material_index(g.material)});
  }
  for (std::size_t i = 0; i < spec.rubble.size(); ++i) {
    const RubbleSpec& r = spec.rubble[i];
    DynamicObject d;
    d.name = "rubble_" + std::to_string(i);
    d.mass = r.mass;
    d.geometry = r.shape == RubbleSpec::Shape::box ? Geometry::box(r.size) : Geometry::cylinder(0.5 * r.size.x(), r.size.z());
    d.inertia = solid_inertia(d.geometry, r.mass);
    // resting on the ground: the floor, or the top of a platform under its centre
    double ground = 0;
    for (const auto& ra : spec.raised_areas) {
      if (contains(ra.outline, r.pose.position())) ground = std::max(ground, ra.height);
    }
    d.X_WO = pose_at(r.pose.position(), ground + r.size.z() / 2, r.pose.yaw);
    d.material = w.material_index(r.material);
    w.dynamics.push_back(std::move(d));
  }
  const int skin = w.material_index("victim_skin"), clothes = w.material_index("victim_clothes");
  for (std::size_t i = 0; i < spec.victims.size(); ++i) {
    const VictimSpec& v = spec.victims[i];
    Victim victim;
    victim.name = v.name.empty() ? "victim_" + std::to_string(i + 1) : v.name;
    victim.pose = v.pose;
    victim.posture = v.posture;
    victim.skin_temperature = v.skin_temperature;
    victim.clothes_temperature = v.clothes_temperature;
    if (!v.figure) {
      // the body is the model file's solids that name this victim (added with the solids below)
      victim.centre = Vec3(v.pose.x, v.pose.y, 0);
      w.victims.push_back(std::move(victim));
      continue;
    }
    Vec3 centre = Vec3::Zero();
    const auto parts = victim_body(v);
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const auto& p = parts[k];
      victim.parts.push_back(static_cast<int>(w.statics.size()));
      centre += p.X_WP.p;
      w.statics.push_back({victim.name + "_part" + std::to_string(k), ObjectKind::victim, p.geometry, p.X_WP, p.skin ? skin : clothes,
                           p.skin ? v.skin_temperature : v.clothes_temperature, VictimIndex::at(i)});
    }
    victim.centre = centre / static_cast<double>(parts.size());
    w.victims.push_back(std::move(victim));
  }
  // 3-D solids from model files: fixed obstacles, or the bodies of victims that name them
  for (const SolidSpec& so : spec.solids) {
    StaticObject o{so.name, ObjectKind::obstacle, so.geometry, so.X_WS, w.material_index(so.material), so.temperature, VictimIndex()};
    if (!so.victim.empty()) {
      const auto it = std::find_if(w.victims.begin(), w.victims.end(), [&](const Victim& v) { return v.name == so.victim; });
      if (it == w.victims.end())
        throw Error(so.source, "solid '" + so.name + "' names victim '" + so.victim + "', which the world does not have");
      const auto vi = static_cast<std::size_t>(it - w.victims.begin());
      o.kind = ObjectKind::victim;
      o.victim = VictimIndex::at(static_cast<std::size_t>(vi));
      if (o.temperature <= 0) o.temperature = spec.victims[vi].skin_temperature;
      it->parts.push_back(static_cast<int>(w.statics.size()));
    }
    w.statics.push_back(std::move(o));
  }
  for (Victim& v : w.victims) {
    // a model's victim: its centre is the middle of its parts' bounding box
    if (v.parts.empty() || spec.victims[static_cast<std::size_t>(&v - w.victims.data())].figure) continue;
    Eigen::AlignedBox3d box;
    for (int i : v.parts) {
      const StaticObject& o = w.statics[static_cast<std::size_t>(i)];
      for (const Vec3& p : mesh_of(o.geometry, 8).vertices) box.extend(o.X_WO * p);
    }
    v.centre = box.center();
  }
  for (const BodySpec& b : spec.bodies) {
    DynamicObject d;
    d.name = b.name;
    d.geometry = b.geometry;
    d.X_WO = b.X_WB;
    d.mass = b.mass;
    d.inertia = b.inertia;
    d.material = w.material_index(b.material);
    w.dynamics.push_back(std::move(d));
  }
  for (const auto& placement : spec.robots) {
    const auto it = models.find(placement.model);
    if (it == models.end()) {
      std::string known;
      for (const auto& [k, v] : models) known += (known.empty() ? "" : ", ") + k;
      throw Error(placement.source.element.empty() ? SourceRef{spec.source_file, 0, "robot '" + placement.name + "'"} : placement.source,
                  "unknown robot model '" + placement.model + "' (known: " + known + ")");
    }
    RobotInstance r;
    r.name = placement.name;
    r.spec = it->second;
    // stand the robot on the floor: its lowest point at the start pose touches z = 0
    r.X_W_start = Pose3::from_pose2(placement.start, placement.height - std::min(0.0, lowest_point(r.spec, Pose3{})) + 0.002);
    w.robots.push_back(std::move(r));
  }
  add_robot_materials(w);
  return w;
}

}  // namespace rescuesim
