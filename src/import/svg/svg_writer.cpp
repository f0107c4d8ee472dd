#include <cmath>
#include <cstdio>
#include <string>

#include "import/svg/svg_world.h"

namespace rescuesim {

namespace {

/// Fixed-format numbers so the same world always gives the same bytes, trailing zeros
/// dropped: coordinates in centimetres keep four decimals (a micrometre), values in metres,
/// kilograms, kelvin and degrees keep six.
std::string num(double v, int decimals = 4) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  std::string s = b;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// Maps world metres to the file's centimetre user units (y down).
struct Map {
  Vec2 origin;  // world floor_min
  double top;   // world floor_max.y
  Vec2 operator()(const Vec2& p) const { return {(p.x() - origin.x()) * 100.0, (top - p.y()) * 100.0}; }
  static std::string len(double metres) { return num(metres * 100.0); }
};

std::string points(const Map& map, const Polygon2& poly) {
  std::string s;
  for (const auto& p : poly) {
    const Vec2 q = map(p);
    if (!s.empty()) s += ' ';
    s += num(q.x()) + "," + num(q.y());
  }
  return s;
}

std::string material_attr(const std::string& material, const std::string& fallback) {
  return material == fallback ? "" : " data-material=\"" + escape(material) + "\"";
}

/// A rectangle of size (length x width) around a world pose, written as a rotated rect.
std::string rotated_rect(const Map& map, const Pose2& pose, double length, double width) {
  const Vec2 c = map(pose.position());
  const double deg = -pose.yaw * 180.0 / M_PI;  // y down: world counter-clockwise is SVG clockwise
  return "x=\"" + num(c.x() - length * 50.0) + "\" y=\"" + num(c.y() - width * 50.0) + "\" width=\"" + Map::len(length) +
         "\" height=\"" + Map::len(width) + "\" transform=\"rotate(" + num(deg, 6) + " " + num(c.x()) + " " + num(c.y()) + ")\"";
}

}  // namespace

std::string world_to_svg(const WorldSpec& w) {
  const Map map{w.floor_min, w.floor_max.y()};
  const Vec2 size = w.floor_max - w.floor_min;
  std::string o;
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<!-- rescuesim world: black = walls/obstacles, red = raised areas, blue = victims, green = robot starts,\n"
       "     orange = rubble, grey = smoke and dust (data-kind); 1 user unit = 1 cm. See docs/worlds.md. -->\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + Map::len(size.x()) + "cm\" height=\"" + Map::len(size.y()) +
       "cm\" viewBox=\"0 0 " + Map::len(size.x()) + " " + Map::len(size.y()) + "\"";
  if (w.floor_min != Vec2::Zero()) o += " data-origin=\"" + num(w.floor_min.x(), 6) + " " + num(w.floor_min.y(), 6) + "\"";
  o += ">\n";

  // the generator record: seed and options, readable back into WorldSpec::metadata
  o += "  <metadata>\n    <rs:generator xmlns:rs=\"https://rescuesim.dev/ns/world\" name=\"" + escape(w.name) + "\" seed=\"" +
       std::to_string(w.seed) + "\">\n";
  for (const auto& [k, v] : w.metadata) o += "      <rs:param key=\"" + escape(k) + "\" value=\"" + escape(v) + "\"/>\n";
  o += "    </rs:generator>\n  </metadata>\n";
  o += "  <rect x=\"0\" y=\"0\" width=\"" + Map::len(size.x()) + "\" height=\"" + Map::len(size.y()) +
       "\" fill=\"#ffffff\" data-kind=\"ignore\"/>\n";

  o += "  <g id=\"raised\" fill=\"#d62728\" stroke=\"none\">\n";
  for (const auto& r : w.raised_areas) {
    std::string edges;
    for (int e : r.ramp_edges) {
      if (!edges.empty()) edges += ',';
      edges += std::to_string(e);
    }
    o += "    <polygon points=\"" + points(map, r.outline) + "\" data-height=\"" + num(r.height, 6) + "\" data-ramp-length=\"" +
         num(r.ramp_length, 6) + "\" data-ramp-edges=\"" + edges + "\"" + material_attr(r.material, "raised") + "/>\n";
  }
  o += "  </g>\n";

  // floor patches of other materials (only when there are some, so other worlds write as before)
  if (!w.ground.empty()) {
    o += "  <g id=\"ground\" fill=\"#d8c8a0\" stroke=\"none\">\n";
    for (const auto& g : w.ground) {
      o += "    <polygon points=\"" + points(map, g.outline) + "\" data-kind=\"ground\" data-name=\"" + escape(g.name) +
           "\" data-material=\"" + escape(g.material) + "\"/>\n";
    }
    o += "  </g>\n";
  }

  // terrain: the footprint, its kind and every parameter, so it reads back the same
  o += "  <g id=\"terrain\" fill=\"#8c564b\" stroke=\"none\">\n";
  for (const auto& t : w.terrain) {
    o += "    <rect " + rotated_rect(map, t.pose, t.length, t.width) + " data-kind=\"" + TerrainSpec::kind_name(t.kind) +
         "\" data-name=\"" + escape(t.name) + "\" data-yaw=\"" + num(t.pose.yaw * 180.0 / M_PI, 9) + "\" data-height=\"" +
         num(t.height, 9) + "\" data-post=\"" + num(t.post, 9) + "\" data-pattern=\"" + (t.half_cubic ? "half-cubic" : "full-cubic") +
         "\" data-riser=\"" + num(t.riser, 9) + "\" data-angle=\"" + num(t.angle, 9) + "\" data-gap=\"" + num(t.gap, 9) +
         "\" data-thickness=\"" + num(t.thickness, 9) + "\" data-seed=\"" + std::to_string(t.seed) + "\"" +
         material_attr(t.material, "raised") + "/>\n";
  }
  o += "  </g>\n";

  // smoke and dust: the footprint at t = 0 and every parameter, translucent grey
  o += "  <g id=\"media\" fill=\"#808080\" fill-opacity=\"0.35\" stroke=\"none\">\n";
  for (const auto& m : w.media) {
    o += "    <polygon points=\"" + points(map, m.outline) + "\" data-kind=\"" + MediumSpec::kind_name(m.kind) + "\" data-name=\"" +
         escape(m.name) + "\" data-density=\"" + num(m.density, 9) + "\" data-bottom=\"" + num(m.bottom, 9) + "\" data-height=\"" +
         num(m.height, 9) + "\"";
    if (m.growth != 0) o += " data-growth=\"" + num(m.growth, 9) + "\"";
    if (m.drift != Vec2::Zero()) o += " data-drift-x=\"" + num(m.drift.x(), 9) + "\" data-drift-y=\"" + num(m.drift.y(), 9) + "\"";
    o += "/>\n";
  }
  o += "  </g>\n";

  o += "  <g id=\"walls\" stroke=\"#000000\" fill=\"none\">\n";
  for (const auto& wall : w.walls) {
    const Vec2 a = map(wall.a), b = map(wall.b);
    o += "    <line x1=\"" + num(a.x()) + "\" y1=\"" + num(a.y()) + "\" x2=\"" + num(b.x()) + "\" y2=\"" + num(b.y()) +
         "\" stroke-width=\"" + Map::len(wall.thickness) + "\" data-height=\"" + num(wall.height, 6) + "\"" +
         material_attr(wall.material, "wall") + "/>\n";
  }
  o += "  </g>\n";

  o += "  <g id=\"obstacles\" fill=\"#000000\" stroke=\"none\">\n";
  for (const auto& b : w.blocks) {
    o += "    <polygon points=\"" + points(map, b.outline) + "\" data-height=\"" + num(b.height, 6) + "\"" +
         material_attr(b.material, "obstacle") + "/>\n";
  }
  o += "  </g>\n";

  o += "  <g id=\"rubble\" fill=\"#ff8c00\" stroke=\"none\">\n";
  for (const auto& r : w.rubble) {
    const std::string common = " data-height=\"" + num(r.size.z(), 6) + "\" data-mass=\"" + num(r.mass, 6) + "\" data-yaw=\"" +
                               num(r.pose.yaw * 180.0 / M_PI, 6) + "\"" + material_attr(r.material, "rubble");
    if (r.shape == RubbleSpec::Shape::cylinder) {
      const Vec2 c = map(r.pose.position());
      o += "    <circle cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"" + Map::len(0.5 * r.size.x()) + "\"" + common + "/>\n";
    } else {
      o += "    <rect " + rotated_rect(map, r.pose, r.size.x(), r.size.y()) + common + "/>\n";
    }
  }
  o += "  </g>\n";

  o += "  <g id=\"victims\" fill=\"#1f77b4\" stroke=\"none\">\n";
  for (const auto& v : w.victims) {
    o += "    <rect " + rotated_rect(map, v.pose, v.length, v.width) + " data-name=\"" + escape(v.name) + "\" data-posture=\"" +
         (v.posture == VictimSpec::Posture::lying ? "lying" : "sitting") + "\" data-yaw=\"" + num(v.pose.yaw * 180.0 / M_PI, 6) +
         "\" data-length=\"" + num(v.length, 6) + "\" data-width=\"" + num(v.width, 6) + "\" data-temperature=\"" +
         num(v.skin_temperature, 6) + "K\" data-clothes-temperature=\"" + num(v.clothes_temperature, 6) + "K\"/>\n";
  }
  o += "  </g>\n";

  o += "  <g id=\"starts\" fill=\"#2ca02c\" stroke=\"#2ca02c\">\n";
  for (const auto& r : w.robots) {
    const Vec2 c = map(r.start.position());
    const Vec2 tip = map(r.start.transform({0.5, 0.0}));
    o += "    <circle cx=\"" + num(c.x()) + "\" cy=\"" + num(c.y()) + "\" r=\"30\" stroke=\"none\" data-name=\"" + escape(r.name) +
         "\" data-model=\"" + escape(r.model) + "\" data-yaw=\"" + num(r.start.yaw * 180.0 / M_PI, 6) + "\"/>\n";
    o += "    <line x1=\"" + num(c.x()) + "\" y1=\"" + num(c.y()) + "\" x2=\"" + num(tip.x()) + "\" y2=\"" + num(tip.y()) +
         "\" stroke-width=\"6\"/>\n";
  }
  o += "  </g>\n</svg>\n";
  return o;
}

}  // namespace rescuesim
