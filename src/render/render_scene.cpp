#include "render/render_scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim {

namespace {

/// Thickness of the sheet a floor patch is drawn as (m).
constexpr double kGroundSheet = 0.002;

TextureKind texture_kind(const std::string& name) {
  if (name == "tiles") return TextureKind::tiles;
  if (name == "concrete") return TextureKind::concrete;
  if (name == "wood") return TextureKind::wood;
  if (name == "fabric") return TextureKind::fabric;
  if (name == "skin") return TextureKind::skin;
  return TextureKind::none;
}

RenderMaterial render_material(const MaterialSpec& m, double ambient) {
  RenderMaterial r;
  r.name = m.name;
  r.albedo = Vec3(srgb_to_linear(m.color.x()), srgb_to_linear(m.color.y()), srgb_to_linear(m.color.z()));
  r.roughness = std::clamp(m.roughness, 0.0, 1.0);
  r.texture = texture_kind(m.texture);
  r.temperature = m.temperature > 0 ? m.temperature : ambient;
  r.emissivity = std::clamp(m.emissivity, 0.01, 1.0);
  return r;
}

/// Index of a material by name, or -1.
int find_material(const RenderScene& s, const std::string& name) {
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    if (s.materials[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

/// The material of a robot link shape: its own name, else robot_body, else a grey added once.
int link_material(RenderScene& s, const std::string& name, double ambient) {
  for (const std::string& n : {name, std::string("robot_body"), std::string("robot_fallback_grey")}) {
    const int i = find_material(s, n);
    if (i >= 0) return i;
  }
  MaterialSpec grey;
  grey.name = "robot_fallback_grey";
  s.materials.push_back(render_material(grey, ambient));
  return static_cast<int>(s.materials.size()) - 1;
}

/// The material `m` with an image drawn on it: a copy of it named after both, added once. The
/// image replaces the albedo (Gazebo multiplies a texture by the diffuse colour, which files
/// that carry a texture leave white).
int image_material(RenderScene& s, int m, const std::string& image) {
  const std::string name = s.materials[static_cast<std::size_t>(m)].name + " + " + image;
  if (const int i = find_material(s, name); i >= 0) return i;
  RenderMaterial r = s.materials[static_cast<std::size_t>(m)];
  r.name = name;
  r.image = image;
  r.albedo = Vec3::Ones();
  r.texture = TextureKind::none;
  s.materials.push_back(std::move(r));
  return static_cast<int>(s.materials.size()) - 1;
}

int add_mesh(RenderScene& s, const Geometry& g) {
  s.meshes.push_back(render_mesh_of(g));
  return static_cast<int>(s.meshes.size()) - 1;
}

}  // namespace

double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

double srgb_to_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::size_t RenderScene::triangle_count() const {
  std::size_t n = 0;
  for (const auto& item : items) n += meshes[static_cast<std::size_t>(item.mesh)].indices.size() / 3;
  return n;
}

RenderScene build_render_scene(const World& world) {
  RenderScene s;
  s.ambient_temperature = world.ambient_temperature;
  s.media = world.media;
  for (const auto& m : world.materials) s.materials.push_back(render_material(m, world.ambient_temperature));
  const auto material_temperature = [&](int m) { return s.materials[static_cast<std::size_t>(m)].temperature; };

  // statics: floor, walls, obstacles, platforms, ramps, victim body parts
  for (std::size_t i = 0; i < world.statics.size(); ++i) {
    const StaticObject& o = world.statics[i];
    RenderItem item;
    item.source = RenderItem::Source::static_object;
    item.index = static_cast<int>(i);
    item.mesh = add_mesh(s, o.geometry);
    item.material = o.geometry.image ? image_material(s, o.material, o.geometry.image->file) : o.material;
    item.temperature = world.temperature_of(o);
    item.X_WI = o.X_WO;
    item.casts_shadows = o.kind != ObjectKind::floor;
    s.items.push_back(item);
  }
  // floor patches of other materials: a sheet 2 mm thick on the floor, in the patch's material
  // (2 mm is nothing to a camera, and enough depth for the two surfaces not to flicker); the
  // patches are not solids, so the sheet has no StaticObject (index -1) and casts no shadow
  for (const GroundArea& g : world.ground) {
    RenderItem item;
    item.source = RenderItem::Source::static_object;
    item.index = -1;
    item.mesh = add_mesh(s, Geometry::triangles(extrude(g.outline, 0, kGroundSheet)));
    item.material = g.material;
    item.temperature = material_temperature(g.material);
    item.casts_shadows = false;
    s.items.push_back(item);
  }
  // rubble at its initial pose
  for (std::size_t i = 0; i < world.dynamics.size(); ++i) {
    const DynamicObject& d = world.dynamics[i];
    RenderItem item;
    item.source = RenderItem::Source::dynamic_object;
    item.index = static_cast<int>(i);
    item.mesh = add_mesh(s, d.geometry);
    item.material = d.material;
    item.temperature = material_temperature(d.material);
    item.X_WI = d.X_WO;
    s.items.push_back(item);
  }
  // robot link shapes at the start pose, joints at their initial positions
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    const RobotInstance& robot = world.robots[r];
    const std::vector<Pose3> X_BL = link_poses(robot.spec, initial_positions(robot.spec));
    for (std::size_t l = 0; l < robot.spec.links.size(); ++l) {
      for (const LinkShape& shape : robot.spec.links[l].shapes) {
        if (!shape.visible) continue;  // a URDF's collision shapes: its visuals are drawn instead
        RenderItem item;
        item.source = RenderItem::Source::robot_link;
        item.index = static_cast<int>(l);
        item.robot = RobotIndex::at(r);
        item.mesh = add_mesh(s, shape.geometry);
        item.material = link_material(s, shape.material, world.ambient_temperature);
        item.temperature = material_temperature(item.material);
        item.X_PI = shape.X_LG;
        item.X_WI = robot.X_W_start * X_BL[l] * shape.X_LG;
        s.items.push_back(item);
      }
    }
  }
  // lights, or a default sun from the south-east, high in the sky
  for (const LightSpec& l : world.lights) {
    RenderLight light;
    light.directional = l.type == LightSpec::Type::directional;
    light.direction = l.direction.norm() > 1e-9 ? l.direction.normalized() : Vec3(0, 0, -1);
    light.position = l.position;
    light.color = l.color * l.intensity;
    light.casts_shadows = l.casts_shadows;
    s.lights.push_back(light);
  }
  if (s.lights.empty() && world.sun) {
    RenderLight sun;
    sun.direction = Vec3(-0.35, 0.45, -1.0).normalized();
    sun.color = Vec3(1.0, 0.96, 0.90);
    s.lights.push_back(sun);
  }
  s.world_lights = s.lights.size();
  s.ambient_light = world.ambient_light;
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    const RobotSpec& spec = world.robots[r].spec;
    for (const RobotLightSpec& l : spec.lights) {
      RenderLamp lamp;
      lamp.robot = RobotIndex::at(r);
      lamp.link = spec.link_index(l.link);
      lamp.X_LF = l.X_LF;
      lamp.light.directional = false;
      lamp.light.spot = true;
      lamp.light.casts_shadows = false;
      lamp.light.color = l.color * l.intensity;
      lamp.light.cone = l.cone;
      lamp.light.inner_cone = std::min(l.inner_cone, l.cone);
      lamp.light.range = l.range;
      if (lamp.link >= 0) s.lamps.push_back(lamp);
    }
  }
  return s;
}

void update_render_scene(RenderScene& scene, const State& state) {
  scene.time = state.time.seconds();
  for (RenderItem& item : scene.items) {
    if (item.source == RenderItem::Source::dynamic_object) {
      const auto i = static_cast<std::size_t>(item.index);
      if (i >= state.dynamics.size()) {
        throw Error({"", 0, "update_render_scene"},
                    fmt::format("the State has {} rubble bodies but the scene needs body {}", state.dynamics.size(), i));
      }
      item.X_WI = state.dynamics[i].X_WB * item.X_PI;
    } else if (item.source == RenderItem::Source::robot_link) {
      const auto r = item.robot.slot(), l = static_cast<std::size_t>(item.index);
      if (r >= state.robots.size() || l >= state.robots[r].X_WL.size()) {
        throw Error({"", 0, "update_render_scene"}, fmt::format("the State has no pose for link {} of robot {} ({} robots in the State)",
                                                                l, r, state.robots.size()));
      }
      item.X_WI = state.robots[r].X_WL[l] * item.X_PI;
    }
  }
  scene.lights.resize(scene.world_lights);
  for (const RenderLamp& lamp : scene.lamps) {
    const auto r = lamp.robot.slot(), l = static_cast<std::size_t>(lamp.link);
    if (r >= state.robots.size() || !state.robots[r].lights_on || l >= state.robots[r].X_WL.size()) continue;
    const Pose3 X_WF = state.robots[r].X_WL[l] * lamp.X_LF;
    RenderLight light = lamp.light;
    light.position = X_WF.p;
    light.direction = X_WF.q.toRotationMatrix().col(0);
    scene.lights.push_back(light);
  }
}

}  // namespace rescuesim
