#include <cmath>
#include <set>
#include <string>

#include "world/terrain.h"
#include "world/world_spec.h"

namespace rescuesim {

namespace {

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool finite(const Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw); }
bool finite(const Polygon2& poly) {
  for (const auto& p : poly) {
    if (!finite(p)) return false;
  }
  return true;
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// Names the element for a message when the importer left no source reference.
SourceRef ref(const SourceRef& s, const std::string& fallback) {
  if (!s.element.empty() || s.line > 0) return s;
  SourceRef r = s;
  r.element = fallback;
  return r;
}

/// How far (m) geometry may overhang the floor before it is worth a warning.
constexpr double kFloorSlack = 0.25;

class Validator {
 public:
  Validator(const WorldSpec& w, const ValidateOptions& o) : w_(w), o_(o) {}

  Diagnostics run() {
    check_floor();
    check_materials();
    for (std::size_t i = 0; i < w_.walls.size(); ++i) check_wall(w_.walls[i], i);
    for (std::size_t i = 0; i < w_.blocks.size(); ++i) check_block(w_.blocks[i], i);
    for (std::size_t i = 0; i < w_.raised_areas.size(); ++i) check_raised(w_.raised_areas[i], i);
    for (std::size_t i = 0; i < w_.rubble.size(); ++i) check_rubble(w_.rubble[i], i);
    for (std::size_t i = 0; i < w_.victims.size(); ++i) check_victim(w_.victims[i], i);
    for (std::size_t i = 0; i < w_.lights.size(); ++i) check_light(w_.lights[i], i);
    for (std::size_t i = 0; i < w_.solids.size(); ++i) check_solid(w_.solids[i], i);
    for (std::size_t i = 0; i < w_.terrain.size(); ++i) check_terrain(i);
    for (std::size_t i = 0; i < w_.bodies.size(); ++i) check_body(w_.bodies[i], i);
    for (std::size_t i = 0; i < w_.media.size(); ++i) check_medium(w_.media[i], i);
    for (std::size_t i = 0; i < w_.ground.size(); ++i) check_ground(i);
    check_robots();
    if (w_.walls.empty() && w_.blocks.empty() && w_.raised_areas.empty() && w_.rubble.empty() && w_.victims.empty() &&
        w_.solids.empty() && w_.bodies.empty() && w_.terrain.empty()) {
      d_.error({w_.source_file, 0, ""},
               "the world is empty: no walls, obstacles, raised areas, rubble, victims or model geometry (expected at least one; "
               "in an SVG, walls are black, raised areas red, victims blue; in an SDF, a model with a <collision> other "
               "than the ground plane)");
    }
    return d_;
  }

 private:
  void check_material_ref(const std::string& name, const SourceRef& where) {
    if (!w_.find_material(name)) d_.error(where, "unknown material '" + name + "'");
  }

  void check_floor() {
    const SourceRef where{w_.source_file, 0, "floor"};
    if (!finite(w_.floor_min) || !finite(w_.floor_max)) {
      d_.error(where, "floor extent is not a finite number");
      return;
    }
    const Vec2 size = w_.floor_max - w_.floor_min;
    if (size.x() <= 0 || size.y() <= 0) {
      d_.error(where, "floor size " + num(size.x()) + " x " + num(size.y()) + " m is not positive");
    }
    if (size.x() > o_.max_extent || size.y() > o_.max_extent) {
      d_.error(where, "floor size " + num(size.x()) + " x " + num(size.y()) + " m exceeds the limit of " +
                          num(o_.max_extent) + " m (check the SVG's units or the scale setting)");
    }
    if (!(w_.ambient_temperature > 0) || !std::isfinite(w_.ambient_temperature)) {
      d_.error(where, "ambient temperature " + num(w_.ambient_temperature) + " K is not positive");
    }
    if (!std::isfinite(w_.gravity) || w_.gravity < 0) d_.error(where, "gravity " + num(w_.gravity) + " is not >= 0");
    check_material_ref(w_.floor_material, where);
  }

  void check_materials() {
    std::set<std::string> names;
    for (const auto& m : w_.materials) {
      const SourceRef where{w_.source_file, 0, "material '" + m.name + "'"};
      if (m.name.empty()) d_.error(where, "material has no name");
      if (!names.insert(m.name).second) d_.error(where, "material defined twice");
      if (!finite(m.color) || m.color.minCoeff() < 0 || m.color.maxCoeff() > 1) {
        d_.error(where, "colour components must be in [0, 1]");
      }
      if (!(m.emissivity > 0 && m.emissivity <= 1)) d_.error(where, "emissivity " + num(m.emissivity) + " is not in (0, 1]");
      if (!(m.friction >= 0) || !std::isfinite(m.friction)) d_.error(where, "friction " + num(m.friction) + " is not >= 0");
      if (!(m.restitution >= 0 && m.restitution <= 1)) d_.error(where, "restitution " + num(m.restitution) + " is not in [0, 1]");
      if (!(m.roughness >= 0 && m.roughness <= 1)) d_.error(where, "roughness " + num(m.roughness) + " is not in [0, 1]");
      if (!std::isfinite(m.temperature)) d_.error(where, "temperature is not a finite number");
    }
  }

  void check_extent(const Box2& b, const SourceRef& where) {
    if (b.empty()) return;
    // walls drawn along the page edge overhang it by half their width: that is fine
    const Vec2 slack(kFloorSlack, kFloorSlack);
    const Box2 floor{w_.floor_min - slack, w_.floor_max + slack};
    if (!floor.contains(b.min) || !floor.contains(b.max)) {
      d_.warn(where, "lies more than 0.25 m outside the floor, which spans (" + num(w_.floor_min.x()) + ", " + num(w_.floor_min.y()) +
                         ") to (" + num(w_.floor_max.x()) + ", " + num(w_.floor_max.y()) + ") m");
    }
  }

  void check_wall(const WallSpec& wall, std::size_t i) {
    const SourceRef where = ref(wall.source, "wall " + std::to_string(i));
    if (!finite(wall.a) || !finite(wall.b) || !std::isfinite(wall.thickness) || !std::isfinite(wall.height)) {
      d_.error(where, "wall has a coordinate or size that is not a finite number");
      return;
    }
    if ((wall.b - wall.a).norm() <= 1e-9) d_.error(where, "wall has zero length");
    if (wall.thickness <= 0) d_.error(where, "wall thickness " + num(wall.thickness) + " m is not positive");
    if (wall.height <= 0) d_.error(where, "wall height " + num(wall.height) + " m is not positive");
    check_material_ref(wall.material, where);
    check_extent(bounds(WorldSpec::wall_outline(wall)), where);
  }

  void check_polygon(const Polygon2& poly, const SourceRef& where, const char* what) {
    if (poly.size() < 3) {
      d_.error(where, std::string(what) + " outline has " + std::to_string(poly.size()) + " vertices, expected at least 3");
      return;
    }
    if (!finite(poly)) {
      d_.error(where, std::string(what) + " outline has a coordinate that is not a finite number");
      return;
    }
    if (std::abs(signed_area(poly)) <= 1e-9) d_.error(where, std::string(what) + " has zero area");
    if (!is_simple(poly)) d_.error(where, std::string(what) + " outline crosses itself");
  }

  void check_block(const BlockSpec& b, std::size_t i) {
    const SourceRef where = ref(b.source, "obstacle " + std::to_string(i));
    check_polygon(b.outline, where, "obstacle");
    if (!(b.height > 0) || !std::isfinite(b.height)) d_.error(where, "obstacle height " + num(b.height) + " m is not positive");
    check_material_ref(b.material, where);
    if (finite(b.outline)) check_extent(bounds(b.outline), where);
  }

  void check_raised(const RaisedAreaSpec& r, std::size_t i) {
    const SourceRef where = ref(r.source, "raised area " + std::to_string(i));
    check_polygon(r.outline, where, "raised area");
    if (!(r.height > 0) || !std::isfinite(r.height)) d_.error(where, "raised area height " + num(r.height) + " m is not positive");
    if (!r.ramp_edges.empty() && (!(r.ramp_length > 0) || !std::isfinite(r.ramp_length))) {
      d_.error(where, "ramp length " + num(r.ramp_length) + " m is not positive");
    }
    for (int e : r.ramp_edges) {
      if (e < 0 || e >= static_cast<int>(r.outline.size())) {
        d_.error(where, "ramp on edge " + std::to_string(e) + ", but the outline has " + std::to_string(r.outline.size()) + " edges");
      }
    }
    if (r.outline.size() >= 3 && signed_area(r.outline) < 0 && !r.ramp_edges.empty()) {
      d_.error(where, "raised area outline must be counter-clockwise for ramps to point outward");
    }
    check_material_ref(r.material, where);
    if (finite(r.outline)) check_extent(bounds(r.outline), where);
  }

  void check_rubble(const RubbleSpec& r, std::size_t i) {
    const SourceRef where = ref(r.source, "rubble " + std::to_string(i));
    if (!finite(r.pose) || !finite(r.size) || !std::isfinite(r.mass)) {
      d_.error(where, "rubble has a pose, size or mass that is not a finite number");
      return;
    }
    if (r.size.minCoeff() <= 0) d_.error(where, "rubble size has a component that is not positive");
    if (r.mass <= 0) d_.error(where, "rubble mass " + num(r.mass) + " kg is not positive");
    check_material_ref(r.material, where);
    check_extent(bounds(rectangle(r.pose, r.size.x(), r.size.y())), where);
  }

  /// The wall or obstacle whose footprint contains p, as a description, or "".
  std::string solid_at(const Vec2& p) const {
    for (std::size_t i = 0; i < w_.walls.size(); ++i) {
      if (contains(WorldSpec::wall_outline(w_.walls[i]), p, 0)) return describe(w_.walls[i].source, "wall " + std::to_string(i));
    }
    for (std::size_t i = 0; i < w_.blocks.size(); ++i) {
      if (contains(w_.blocks[i].outline, p, 0)) return describe(w_.blocks[i].source, "obstacle " + std::to_string(i));
    }
    return "";
  }

  /// Nearest wall or obstacle closer than `clearance` to p, as a description, or "".
  std::string solid_near(const Vec2& p, double clearance, double* dist) const {
    for (std::size_t i = 0; i < w_.walls.size(); ++i) {
      const double d = distance_to_polygon(WorldSpec::wall_outline(w_.walls[i]), p);
      if (d < clearance) {
        *dist = d;
        return describe(w_.walls[i].source, "wall " + std::to_string(i));
      }
    }
    for (std::size_t i = 0; i < w_.blocks.size(); ++i) {
      const double d = distance_to_polygon(w_.blocks[i].outline, p);
      if (d < clearance) {
        *dist = d;
        return describe(w_.blocks[i].source, "obstacle " + std::to_string(i));
      }
    }
    return "";
  }

  static std::string describe(const SourceRef& s, const std::string& fallback) {
    std::string out = s.element.empty() ? fallback : s.element;
    if (s.line > 0) out += " (line " + std::to_string(s.line) + ")";
    return out;
  }

  void check_victim(const VictimSpec& v, std::size_t i) {
    const SourceRef where = ref(v.source, "victim " + std::to_string(i));
    if (!finite(v.pose) || !std::isfinite(v.length) || !std::isfinite(v.width)) {
      d_.error(where, "victim has a pose or size that is not a finite number");
      return;
    }
    if (v.length <= 0 || v.width <= 0) d_.error(where, "victim size " + num(v.length) + " x " + num(v.width) + " m is not positive");
    if (!(v.skin_temperature > 0) || !(v.clothes_temperature > 0)) d_.error(where, "victim temperatures must be positive (K)");
    const std::string solid = solid_at(v.pose.position());
    if (!solid.empty()) d_.error(where, "victim lies inside " + solid);
    check_extent(bounds(WorldSpec::victim_outline(v)), where);
  }

  /// A 3-D shape: finite, positive and not absurdly large.
  void check_geometry(const Geometry& g, const Pose3& X, const SourceRef& where) {
    if (!finite(X.p) || !std::isfinite(X.q.norm())) {
      d_.error(where, "pose is not a finite number");
      return;
    }
    if (!finite(g.size) || g.size.minCoeff() < 0 || (g.type != Geometry::Type::mesh && g.size.minCoeff() <= 0)) {
      d_.error(where, "size " + num(g.size.x()) + " x " + num(g.size.y()) + " x " + num(g.size.z()) + " m is not positive");
    } else if (g.size.maxCoeff() > o_.max_extent) {
      d_.error(where, "size " + num(g.size.maxCoeff()) + " m exceeds the limit of " + num(o_.max_extent) + " m (check the scale)");
    }
    if ((g.type == Geometry::Type::mesh || g.type == Geometry::Type::convex) && g.mesh.triangles.empty()) {
      d_.error(where, "mesh has no triangles");
    }
  }

  void check_solid(const SolidSpec& so, std::size_t i) {
    const SourceRef where = ref(so.source, "solid '" + so.name + "' (" + std::to_string(i) + ")");
    check_geometry(so.geometry, so.X_WS, where);
    check_material_ref(so.material, where);
    if (!so.victim.empty()) {
      bool found = false;
      for (const auto& v : w_.victims) found = found || v.name == so.victim;
      if (!found) d_.error(where, "names victim '" + so.victim + "', which the world does not have");
    }
  }

  /// A terrain element must build (terrain_solids names what is wrong), use a known material and
  /// stay clear of the other elements' footprints: overlapping elements would stack solids.
  void check_terrain(std::size_t i) {
    const TerrainSpec& t = w_.terrain[i];
    const std::string what = std::string(TerrainSpec::kind_name(t.kind)) + " '" + t.name + "'";
    const SourceRef where = ref(t.source, what);
    if (!std::isfinite(t.pose.x) || !std::isfinite(t.pose.y) || !std::isfinite(t.pose.yaw)) d_.error(where, "pose is not a finite number");
    try {
      (void)terrain_solids(t);
    } catch (const Error& e) {
      d_.error(e.where(), e.message());
      return;
    }
    check_material_ref(t.material, where);
    // footprints 1 mm in from each edge: elements edge to edge, as an arena's lanes are, touch
    const auto inset = [](const TerrainSpec& e) { return rectangle(e.pose, e.length - 0.002, e.width - 0.002); };
    for (std::size_t k = 0; k < i; ++k) {
      const TerrainSpec& o = w_.terrain[k];
      if (polygons_overlap(inset(t), inset(o))) {
        d_.error(where, "overlaps " + std::string(TerrainSpec::kind_name(o.kind)) + " '" + o.name + "'" +
                            (o.source.line > 0 ? " (line " + std::to_string(o.source.line) + ")" : std::string()) +
                            "; terrain elements must not overlap (expected footprints side by side)");
      }
    }
  }

  /// A smoke or dust volume: a footprint with area, a density (visible extinction) that is a
  /// number 0 or more, a positive height, a growth 0 or more, finite drift.
  void check_medium(const MediumSpec& m, std::size_t i) {
    const std::string what = std::string(MediumSpec::kind_name(m.kind)) + " '" + m.name + "' (" + std::to_string(i) + ")";
    const SourceRef where = ref(m.source, what);
    if (m.outline.size() < 3) {
      d_.error(where, "footprint has " + std::to_string(m.outline.size()) + " points; expected a polygon of at least 3");
    } else if (!finite(m.outline)) {
      d_.error(where, "footprint has a point that is not a finite number");
    } else if (!(std::abs(signed_area(m.outline)) > 1e-12)) {
      d_.error(where, "footprint has no area; expected a polygon of at least 3 points not on one line");
    }
    if (!std::isfinite(m.density) || m.density < 0) {
      d_.error(where, "density " + num(m.density) + " is not an extinction coefficient: expected a finite number of 1/m, 0 or more");
    }
    if (!std::isfinite(m.bottom) || m.bottom < 0) d_.error(where, "bottom " + num(m.bottom) + " m is not a height of 0 or more");
    if (!std::isfinite(m.height) || !(m.height > 0)) d_.error(where, "height " + num(m.height) + " m is not positive");
    if (!std::isfinite(m.growth) || m.growth < 0)
      d_.error(where, "growth " + num(m.growth) + " m/s is not 0 or more (a footprint only grows)");
    if (!finite(m.drift)) d_.error(where, "drift is not a finite velocity");
  }

  /// A floor patch: a known material, a footprint with area, and no overlap with another patch
  /// (two materials at one point would be ambiguous). Patches edge to edge are fine.
  void check_ground(std::size_t i) {
    const GroundAreaSpec& g = w_.ground[i];
    const SourceRef where = ref(g.source, "ground area '" + g.name + "' (" + std::to_string(i) + ")");
    if (g.material.empty()) {
      d_.error(where, "ground area has no material; expected one such as concrete, wood, sand or wet_tiles");
    } else {
      check_material_ref(g.material, where);
    }
    if (g.outline.size() < 3) {
      d_.error(where, "footprint has " + std::to_string(g.outline.size()) + " points; expected a polygon of at least 3");
      return;
    }
    if (!finite(g.outline)) {
      d_.error(where, "footprint has a point that is not a finite number");
      return;
    }
    if (!(std::abs(signed_area(g.outline)) > 1e-12)) {
      d_.error(where, "footprint has no area; expected a polygon of at least 3 points not on one line");
      return;
    }
    if (!is_simple(g.outline)) {
      d_.error(where, "footprint crosses itself; expected a simple polygon");
      return;
    }
    // each vertex 1 mm towards the centroid: patches that only share an edge do not overlap
    const auto shrunk = [](const Polygon2& p) {
      const Vec2 c = centroid(p);
      Polygon2 out;
      for (const Vec2& v : p) {
        const double d = (v - c).norm();
        out.push_back(d > 2e-3 ? Vec2(c + (v - c) * (1 - 1e-3 / d)) : v);
      }
      return out;
    };
    for (std::size_t k = 0; k < i; ++k) {
      const GroundAreaSpec& o = w_.ground[k];
      if (o.outline.size() < 3 || !finite(o.outline)) continue;
      if (polygons_overlap(shrunk(g.outline), shrunk(o.outline))) {
        d_.error(where,
                 "overlaps ground area '" + o.name + "'" +
                     (o.source.line > 0 ? " (line " + std::to_string(o.source.line) + ")" : std::string()) +
                     "; ground areas must not overlap, so that every point of the floor has one material (expected patches side by side)");
      }
    }
  }

  void check_body(const BodySpec& b, std::size_t i) {
    const SourceRef where = ref(b.source, "body '" + b.name + "' (" + std::to_string(i) + ")");
    check_geometry(b.geometry, b.X_WB, where);
    check_material_ref(b.material, where);
    if (!(b.mass > 0) || !std::isfinite(b.mass)) d_.error(where, "mass " + num(b.mass) + " kg is not positive");
    if (!finite(b.inertia) || b.inertia.minCoeff() <= 0) d_.error(where, "inertia has a moment that is not positive");
  }

  void check_light(const LightSpec& l, std::size_t i) {
    const SourceRef where{w_.source_file, 0, "light " + std::to_string(i)};
    if (!finite(l.position) || !finite(l.direction) || !finite(l.color) || !std::isfinite(l.intensity)) {
      d_.error(where, "light has a value that is not a finite number");
      return;
    }
    if (l.intensity < 0) d_.error(where, "light intensity is negative");
    if (l.type == LightSpec::Type::directional && l.direction.norm() < 1e-9) d_.error(where, "light direction is zero");
  }

  void check_robots() {
    std::set<std::string> names;
    for (std::size_t i = 0; i < w_.robots.size(); ++i) {
      const auto& r = w_.robots[i];
      const SourceRef where = ref(r.source, "robot '" + r.name + "'");
      if (r.name.empty()) d_.error(where, "robot has no name");
      if (!names.insert(r.name).second) d_.error(where, "two robots are named '" + r.name + "'");
      if (!finite(r.start)) {
        d_.error(where, "start pose is not a finite number");
        continue;
      }
      const Box2 floor{w_.floor_min, w_.floor_max};
      if (!floor.contains(r.start.position())) d_.error(where, "start position is outside the floor");
      double d = 0;
      const std::string solid = solid_near(r.start.position(), o_.robot_radius, &d);
      if (!solid.empty()) {
        d_.error(where, "start pose (" + num(r.start.x) + ", " + num(r.start.y) + ") is " + num(d) + " m from " + solid +
                            "; the robot needs " + num(o_.robot_radius) + " m of clearance");
      }
      for (std::size_t j = 0; j < i; ++j) {
        if ((w_.robots[j].start.position() - r.start.position()).norm() < 2 * o_.robot_radius) {
          d_.error(where, "start pose overlaps robot '" + w_.robots[j].name + "'");
        }
      }
    }
  }

  const WorldSpec& w_;
  const ValidateOptions& o_;
  Diagnostics d_;
};

}  // namespace

Diagnostics validate(const WorldSpec& world, const ValidateOptions& options) { return Validator(world, options).run(); }

}  // namespace rescuesim
