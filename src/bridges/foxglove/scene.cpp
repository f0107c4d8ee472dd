#include "bridges/foxglove/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <map>

namespace rescuesim::foxglove {

namespace {

using json = nlohmann::json;

// numbers are rounded (10 µm, 1e-6 for rotations) so the JSON stays short and a scene that did
// not move reads exactly the same
double round_to(double x, double scale) { return std::round(x * scale) / scale; }

json vec3(const Vec3& v) { return {{"x", round_to(v.x(), 1e5)}, {"y", round_to(v.y(), 1e5)}, {"z", round_to(v.z(), 1e5)}}; }

json pose(const Pose3& X) {
  const Quat q = X.q.normalized();
  return {{"position", vec3(X.p)},
          {"orientation",
           {{"x", round_to(q.x(), 1e6)}, {"y", round_to(q.y(), 1e6)}, {"z", round_to(q.z(), 1e6)}, {"w", round_to(q.w(), 1e6)}}}};
}

json color(const Vec3& c, double a = 1.0) {
  return {{"r", round_to(c.x(), 1e3)}, {"g", round_to(c.y(), 1e3)}, {"b", round_to(c.z(), 1e3)}, {"a", a}};
}

json stamp(SimTime t) { return {{"sec", t.sec_part()}, {"nsec", t.nsec_part()}}; }

/// The primitive lists of one entity.
struct Primitives {
  json cubes = json::array(), spheres = json::array(), cylinders = json::array(), triangles = json::array(), texts = json::array();
  bool empty() const { return cubes.empty() && spheres.empty() && cylinders.empty() && triangles.empty() && texts.empty(); }
};

/// One shape as the primitive that fits it: boxes as cubes, spheres, upright-axis cylinders,
/// and everything else (extruded polygons, ramps, meshes) as an indexed triangle list.
void add_shape(Primitives& p, const Geometry& g, const Pose3& X_FG, const Vec3& rgb) {
  switch (g.type) {
    case Geometry::Type::box: p.cubes.push_back({{"pose", pose(X_FG)}, {"size", vec3(g.size)}, {"color", color(rgb)}}); return;
    case Geometry::Type::sphere: p.spheres.push_back({{"pose", pose(X_FG)}, {"size", vec3(g.size)}, {"color", color(rgb)}}); return;
    case Geometry::Type::cylinder:
      p.cylinders.push_back(
          {{"pose", pose(X_FG)}, {"size", vec3(g.size)}, {"bottom_scale", 1.0}, {"top_scale", 1.0}, {"color", color(rgb)}});
      return;
    case Geometry::Type::convex:
    case Geometry::Type::mesh: break;
  }
  const TriangleMesh m = g.mesh.triangles.empty() ? mesh_of(g) : g.mesh;
  json points = json::array(), indices = json::array();
  for (const Vec3& v : m.vertices) points.push_back(vec3(v));
  for (const auto& t : m.triangles) {
    for (int i : t) indices.push_back(i);
  }
  p.triangles.push_back({{"pose", pose(X_FG)}, {"points", points}, {"color", color(rgb)}, {"colors", json::array()}, {"indices", indices}});
}

json entity(const std::string& id, const std::string& frame, SimTime t, bool frame_locked, Primitives p,
            const std::vector<std::pair<std::string, std::string>>& metadata) {
  json meta = json::array();
  for (const auto& [k, v] : metadata) meta.push_back({{"key", k}, {"value", v}});
  return {{"timestamp", stamp(t)},
          {"frame_id", frame},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},
          {"frame_locked", frame_locked},
          {"metadata", meta},
          {"arrows", json::array()},
          {"cubes", std::move(p.cubes)},
          {"spheres", std::move(p.spheres)},
          {"cylinders", std::move(p.cylinders)},
          {"lines", json::array()},
          {"triangles", std::move(p.triangles)},
          {"texts", std::move(p.texts)},
          {"models", json::array()}};
}

Vec3 material_color(const World& w, const std::string& name) {
  for (const auto& m : w.materials) {
    if (m.name == name) return m.color;
  }
  return {0.6, 0.6, 0.6};
}

const char* group_of(ObjectKind k) {
  switch (k) {
    case ObjectKind::floor: return "floor";
    case ObjectKind::wall: return "walls";
    case ObjectKind::obstacle: return "obstacles";
    case ObjectKind::platform:
    case ObjectKind::ramp: return "raised_areas";
    case ObjectKind::victim: return "victims";
    case ObjectKind::rubble: return "rubble_static";
    case ObjectKind::robot: return "robot_static";
  }
  return "other";
}

/// Splices entity objects (a JSON array's text without its brackets) into a SceneUpdate.
std::string scene_update(const std::string& entities_a, const std::string& entities_b) {
  std::string s = R"({"deletions":[],"entities":[)";
  s += entities_a;
  if (!entities_a.empty() && !entities_b.empty()) s += ',';
  s += entities_b;
  s += "]}";
  return s;
}

std::string inner(const json& array) {
  const std::string s = array.dump();
  return s.substr(1, s.size() - 2);
}

}  // namespace

SceneBuilder::SceneBuilder(const World& world, SceneFrames frames) : frames_(std::move(frames)) {
  // static world geometry, grouped by kind; each victim's body is its own entity
  std::map<std::string, Primitives> groups;
  std::map<VictimIndex, Primitives> victims;
  for (const StaticObject& o : world.statics) {
    const Vec3 rgb = world.materials.at(static_cast<std::size_t>(o.material)).color;
    const Pose3 X_FO = frames_.X_FW * o.X_WO;
    if (o.victim.valid()) {
      add_shape(victims[o.victim], o.geometry, X_FO, rgb);
    } else {
      add_shape(groups[group_of(o.kind)], o.geometry, X_FO, rgb);
    }
  }
  json all = json::array();
  for (auto& [name, p] : groups) all.push_back(entity(name, frames_.world_frame, SimTime{}, false, std::move(p), {{"kind", name}}));
  for (auto& [v, p] : victims) {
    const Victim& victim = world.victim(v);
    all.push_back(
        entity("victim/" + victim.name, frames_.world_frame, SimTime{}, false, std::move(p), {{"kind", "victim"}, {"name", victim.name}}));
  }
  // each robot link's shapes in its own frame: /tf carries them along. A robot with a
  // description (URDF) is drawn by the 3D panel from /robot_description with its real meshes;
  // the scene shows its collision shapes (primitives and convex hulls), which are small, rather
  // than its visual meshes (often hundreds of thousands of triangles)
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    const RobotInstance& robot = world.robots[r];
    const bool described = !robot.spec.description.empty();
    for (std::size_t l = 0; l < robot.spec.links.size(); ++l) {
      const LinkSpec& link = robot.spec.links[l];
      Primitives p;
      for (const LinkShape& s : link.shapes) {
        if (described && !s.collides) continue;
        add_shape(p, s.geometry, s.X_LG, material_color(world, s.material));
      }
      if (p.empty()) continue;
      const std::string frame = r < frames_.link_frames.size() && l < frames_.link_frames[r].size() ? frames_.link_frames[r][l] : link.name;
      all.push_back(entity("robot/" + robot.name + "/" + link.name, frame, SimTime{}, true, std::move(p),
                           {{"kind", "robot"}, {"robot", robot.name}, {"link", link.name}}));
    }
  }
  static_count_ = all.size();
  static_json_ = inner(all);

  for (const DynamicObject& d : world.dynamics) {
    rubble_.push_back({d.name, d.geometry, world.materials.at(static_cast<std::size_t>(d.material)).color});
  }
  for (const Victim& v : world.victims) victims_.push_back({v.name, v.centre + Vec3(0, 0, 0.6)});
}

std::string SceneBuilder::moving_entities(SimTime t, const SceneState& state) const {
  json all = json::array();
  if (!rubble_.empty()) {
    Primitives p;
    for (std::size_t i = 0; i < rubble_.size() && i < state.rubble.size(); ++i) {
      add_shape(p, rubble_[i].geometry, frames_.X_FW * state.rubble[i], rubble_[i].color);
    }
    all.push_back(entity("rubble", frames_.world_frame, t, false, std::move(p), {{"kind", "rubble"}}));
  }
  if (!victims_.empty()) {
    Primitives p;
    for (std::size_t i = 0; i < victims_.size(); ++i) {
      const bool found = i < state.victim_found_at.size() && state.victim_found_at[i] >= 0;
      std::string text = victims_[i].name;
      if (found) {
        char when[32];
        std::snprintf(when, sizeof when, "%.1f", state.victim_found_at[i]);
        text += ": found at " + std::string(when) + " s";
        if (i < state.victim_found_by.size() && !state.victim_found_by[i].empty()) text += " by " + state.victim_found_by[i];
      }
      p.texts.push_back({{"pose", pose({frames_.X_FW * victims_[i].p_W, Quat::Identity()})},
                         {"billboard", true},
                         {"font_size", 0.2},
                         {"scale_invariant", false},
                         {"color", found ? color({0.1, 0.8, 0.2}) : color({1.0, 0.45, 0.0})},
                         {"text", text}});
    }
    all.push_back(entity("victim_labels", frames_.world_frame, t, false, std::move(p), {{"kind", "victim_labels"}}));
  }
  return inner(all);
}

bool same_scene(const SceneState& a, const SceneState& b) {
  if (a.rubble.size() != b.rubble.size() || a.victim_found_at.size() != b.victim_found_at.size()) return false;
  for (std::size_t i = 0; i < a.rubble.size(); ++i) {
    if ((a.rubble[i].p - b.rubble[i].p).norm() > 1e-3 || a.rubble[i].q.angularDistance(b.rubble[i].q) > 1e-3) return false;
  }
  for (std::size_t i = 0; i < a.victim_found_at.size(); ++i) {
    if ((a.victim_found_at[i] >= 0) != (b.victim_found_at[i] >= 0)) return false;
  }
  return true;
}

std::string SceneBuilder::full(SimTime t, const SceneState& state) const { return scene_update(static_json_, moving_entities(t, state)); }

std::string SceneBuilder::moving(SimTime t, const SceneState& state) const { return scene_update("", moving_entities(t, state)); }

std::string scene_update_schema() {
  // written out by hand from the foxglove.SceneUpdate message definition (the fields above)
  const json number = {{"type", "number"}};
  const json integer = {{"type", "integer"}};
  const json boolean = {{"type", "boolean"}};
  const json string = {{"type", "string"}};
  auto object = [](const std::string& title, json properties) {
    json required = json::array();
    for (const auto& [k, v] : properties.items()) required.push_back(k);
    return json{{"title", title}, {"type", "object"}, {"properties", std::move(properties)}, {"required", required}};
  };
  auto array = [](json items) { return json{{"type", "array"}, {"items", std::move(items)}}; };
  const json vector3 = object("foxglove.Vector3", {{"x", number}, {"y", number}, {"z", number}});
  const json point3 = object("foxglove.Point3", {{"x", number}, {"y", number}, {"z", number}});
  const json quaternion = object("foxglove.Quaternion", {{"x", number}, {"y", number}, {"z", number}, {"w", number}});
  const json pose_s = object("foxglove.Pose", {{"position", vector3}, {"orientation", quaternion}});
  const json color_s = object("foxglove.Color", {{"r", number}, {"g", number}, {"b", number}, {"a", number}});
  const json time_s = object("time", {{"sec", integer}, {"nsec", integer}});
  const json duration_s = object("duration", {{"sec", integer}, {"nsec", integer}});
  const json arrow = object("foxglove.ArrowPrimitive", {{"pose", pose_s},
                                                        {"shaft_length", number},
                                                        {"shaft_diameter", number},
                                                        {"head_length", number},
                                                        {"head_diameter", number},
                                                        {"color", color_s}});
  const json cube = object("foxglove.CubePrimitive", {{"pose", pose_s}, {"size", vector3}, {"color", color_s}});
  const json sphere = object("foxglove.SpherePrimitive", {{"pose", pose_s}, {"size", vector3}, {"color", color_s}});
  const json cylinder = object("foxglove.CylinderPrimitive",
                               {{"pose", pose_s}, {"size", vector3}, {"bottom_scale", number}, {"top_scale", number}, {"color", color_s}});
  const json line = object("foxglove.LinePrimitive", {{"type", {{"type", "integer"}, {"enum", {0, 1, 2}}}},
                                                      {"pose", pose_s},
                                                      {"thickness", number},
                                                      {"scale_invariant", boolean},
                                                      {"points", array(point3)},
                                                      {"color", color_s},
                                                      {"colors", array(color_s)},
                                                      {"indices", array(integer)}});
  const json triangles = object("foxglove.TriangleListPrimitive", {{"pose", pose_s},
                                                                   {"points", array(point3)},
                                                                   {"color", color_s},
                                                                   {"colors", array(color_s)},
                                                                   {"indices", array(integer)}});
  const json text = object("foxglove.TextPrimitive", {{"pose", pose_s},
                                                      {"billboard", boolean},
                                                      {"font_size", number},
                                                      {"scale_invariant", boolean},
                                                      {"color", color_s},
                                                      {"text", string}});
  const json model = object("foxglove.ModelPrimitive", {{"pose", pose_s},
                                                        {"scale", vector3},
                                                        {"color", color_s},
                                                        {"override_color", boolean},
                                                        {"url", string},
                                                        {"media_type", string},
                                                        {"data", {{"type", "string"}, {"contentEncoding", "base64"}}}});
  const json key_value = object("foxglove.KeyValuePair", {{"key", string}, {"value", string}});
  const json entity_s = object("foxglove.SceneEntity", {{"timestamp", time_s},
                                                        {"frame_id", string},
                                                        {"id", string},
                                                        {"lifetime", duration_s},
                                                        {"frame_locked", boolean},
                                                        {"metadata", array(key_value)},
                                                        {"arrows", array(arrow)},
                                                        {"cubes", array(cube)},
                                                        {"spheres", array(sphere)},
                                                        {"cylinders", array(cylinder)},
                                                        {"lines", array(line)},
                                                        {"triangles", array(triangles)},
                                                        {"texts", array(text)},
                                                        {"models", array(model)}});
  const json deletion = object("foxglove.SceneEntityDeletion",
                               {{"timestamp", time_s}, {"type", {{"type", "integer"}, {"enum", {0, 1}}}}, {"id", string}});
  json schema = object("foxglove.SceneUpdate", {{"deletions", array(deletion)}, {"entities", array(entity_s)}});
  schema["$schema"] = "http://json-schema.org/draft-07/schema#";
  schema["description"] = "An update to the entities displayed in a 3D scene";
  return schema.dump();
}

}  // namespace rescuesim::foxglove
