#include "world/world_spec.h"

#include <cmath>

namespace rescuesim {

const MaterialSpec* WorldSpec::find_material(const std::string& name) const {
  for (const auto& m : materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

void WorldSpec::set_material(const MaterialSpec& m) {
  for (auto& existing : materials) {
    if (existing.name == m.name) {
      existing = m;
      return;
    }
  }
  materials.push_back(m);
}

Polygon2 WorldSpec::wall_outline(const WallSpec& w) {
  const Vec2 d = w.b - w.a;
  const double len = d.norm();
  const double yaw = len > 0 ? std::atan2(d.y(), d.x()) : 0.0;
  const Vec2 c = 0.5 * (w.a + w.b);
  return rectangle({c.x(), c.y(), yaw}, len, w.thickness);
}

Polygon2 WorldSpec::ramp_outline(const RaisedAreaSpec& r, int edge) {
  const auto n = static_cast<int>(r.outline.size());
  const Vec2 a = r.outline[static_cast<std::size_t>(edge)];
  const Vec2 b = r.outline[static_cast<std::size_t>((edge + 1) % n)];
  const Vec2 d = (b - a).normalized();
  // counter-clockwise outline: the outward normal of edge a->b points to its right
  const Vec2 out(d.y(), -d.x());
  return {a + out * r.ramp_length, b + out * r.ramp_length, b, a};
}

Polygon2 WorldSpec::victim_outline(const VictimSpec& v) {
  if (v.posture == VictimSpec::Posture::sitting) {
    // seated: legs forward, about half the standing length by shoulder width plus arms
    return rectangle(v.pose, 0.55 * v.length, v.width + 0.1);
  }
  return rectangle(v.pose, v.length, v.width);
}

Box2 WorldSpec::content_bounds() const {
  Box2 b;
  for (const auto& w : walls) b.extend(bounds(wall_outline(w)));
  for (const auto& k : blocks) b.extend(bounds(k.outline));
  for (const auto& r : raised_areas) {
    b.extend(bounds(r.outline));
    for (int e : r.ramp_edges) {
      if (e >= 0 && e < static_cast<int>(r.outline.size())) b.extend(bounds(ramp_outline(r, e)));
    }
  }
  for (const auto& t : terrain) b.extend(bounds(t.outline()));
  for (const auto& g : ground) b.extend(bounds(g.outline));
  for (const auto& r : rubble) b.extend(r.pose.position());
  for (const auto& v : victims) b.extend(bounds(victim_outline(v)));
  for (const auto& r : robots) b.extend(r.start.position());
  // 3-D solids and bodies: the footprint of every vertex (a mesh's, or the shape's triangles)
  const auto extend_3d = [&b](const Geometry& g, const Pose3& X) {
    const TriangleMesh m = g.type == Geometry::Type::mesh || g.type == Geometry::Type::convex ? g.mesh : mesh_of(g, 8);
    for (const Vec3& v : m.vertices) {
      const Vec3 p = X * v;
      b.extend(Vec2(p.x(), p.y()));
    }
  };
  for (const auto& s : solids) extend_3d(s.geometry, s.X_WS);
  for (const auto& d : bodies) extend_3d(d.geometry, d.X_WB);
  return b;
}

std::vector<MaterialSpec> default_materials() {
  std::vector<MaterialSpec> m;
  // name, colour (sRGB), roughness, texture, temperature (K, <0 ambient), emissivity, friction, restitution
  m.push_back({"floor", {0.62, 0.60, 0.56}, 0.85, "tiles", -1, 0.94, 0.9, 0.05});
  m.push_back({"wall", {0.78, 0.76, 0.72}, 0.9, "concrete", -1, 0.92, 0.6, 0.05});
  m.push_back({"obstacle", {0.35, 0.33, 0.32}, 0.8, "concrete", -1, 0.92, 0.7, 0.05});
  m.push_back({"raised", {0.70, 0.52, 0.32}, 0.7, "wood", -1, 0.90, 1.0, 0.05});
  m.push_back({"rubble", {0.55, 0.45, 0.38}, 0.9, "concrete", -1, 0.93, 0.7, 0.1});
  m.push_back({"victim_skin", {0.87, 0.68, 0.55}, 0.6, "skin", 307.15, 0.98, 0.8, 0.0});
  m.push_back({"victim_clothes", {0.20, 0.30, 0.55}, 0.9, "fabric", 301.15, 0.95, 0.8, 0.0});
  m.push_back({"robot_body", {0.95, 0.55, 0.10}, 0.5, "none", -1, 0.90, 0.5, 0.05});
  m.push_back({"robot_wheel", {0.08, 0.08, 0.08}, 0.9, "none", -1, 0.95, 1.0, 0.0});
  m.push_back({"robot_sensor", {0.15, 0.15, 0.17}, 0.4, "none", -1, 0.90, 0.5, 0.05});
  // ground materials for floor patches (GroundAreaSpec; docs/terrain.md, "Ground materials").
  // Bullet multiplies the frictions of the two bodies in a contact, and the robots' rubber
  // (robot_wheel, the tracks' belts) has 1.0, so each value here is the Coulomb coefficient of
  // rubber on that ground, as handbooks tabulate it: dry concrete 0.6-0.85 (0.8); planed wood
  // about 0.6; loose dry sand gives a tyre a traction coefficient of 0.3-0.5, since the sand
  // shears before the rubber slips (0.4); wet glazed tiles 0.2-0.3 (0.25). Sand is drawn with
  // the concrete pattern in a sand colour, wet tiles with the tile pattern and a low roughness
  // (a wet sheen).
  m.push_back({"concrete", {0.62, 0.62, 0.60}, 0.9, "concrete", -1, 0.92, 0.8, 0.05});
  m.push_back({"wood", {0.64, 0.47, 0.30}, 0.7, "wood", -1, 0.90, 0.6, 0.05});
  m.push_back({"sand", {0.82, 0.72, 0.52}, 1.0, "concrete", -1, 0.90, 0.4, 0.0});
  m.push_back({"wet_tiles", {0.52, 0.58, 0.62}, 0.2, "tiles", -1, 0.95, 0.25, 0.05});
  return m;
}

}  // namespace rescuesim
