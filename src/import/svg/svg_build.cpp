#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "import/svg/svg_shapes.h"

namespace rescuesim::svg {

namespace {

std::string hex(const Vec3& c) {
  char b[16];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", static_cast<int>(std::lround(c.x() * 255)),
                static_cast<int>(std::lround(c.y() * 255)), static_cast<int>(std::lround(c.z() * 255)));
  return b;
}

SourceRef attr_ref(const Shape& s, const std::string& key) {
  SourceRef r = s.source;
  r.element += " attribute data-" + key;
  return r;
}

const std::string* data(const Shape& s, const std::string& key) {
  const auto it = s.style.data.find(key);
  return it == s.style.data.end() ? nullptr : &it->second;
}

/// What an element is meant to be, and whether its fill (rather than its stroke) defines it.
struct Meaning {
  Semantic kind = Semantic::background;
  bool filled = false;
  Vec3 color = Vec3::Zero();
  bool forced_block = false;  ///< data-kind="obstacle"
};

Meaning meaning_of(const Shape& s) {
  Meaning m;
  const bool has_fill = s.style.fill.kind == Paint::Kind::color && s.tag != Shape::Tag::line;
  const bool has_stroke = s.style.stroke.kind == Paint::Kind::color && s.stroke_width > 0;
  m.filled = has_fill;
  if (const std::string* k = data(s, "kind")) {
    static const std::pair<const char*, Semantic> kinds[] = {
        {"wall", Semantic::wall},     {"obstacle", Semantic::wall}, {"raised", Semantic::raised},
        {"victim", Semantic::victim}, {"start", Semantic::start},   {"rubble", Semantic::rubble},
        {"ignore", Semantic::background}};
    for (const auto& [name, sem] : kinds) {
      if (*k == name) {
        m.kind = sem;
        m.forced_block = *k == std::string("obstacle");
        if (m.forced_block) m.filled = true;
        if (*k == std::string("wall")) m.filled = has_fill && !has_stroke;
        return m;
      }
    }
    throw Error(attr_ref(s, "kind"),
                "unknown kind '" + *k +
                    "'; expected wall, obstacle, raised, victim, start, rubble, ignore, terrain: stepfield, stairs, crossing-ramps, curb, "
                    "hurdle or gap, a medium: smoke or dust, or ground (a floor patch of another material)");
  }
  if (has_fill) {
    m.color = s.style.fill.rgb;
  } else if (has_stroke) {
    m.color = s.style.stroke.rgb;
  } else {
    return m;  // nothing visible
  }
  m.kind = classify_color(m.color);
  return m;
}

/// Points of all subpaths.
std::vector<Vec2> all_points(const Shape& s) {
  std::vector<Vec2> pts;
  for (const auto& sp : s.subpaths) pts.insert(pts.end(), sp.points.begin(), sp.points.end());
  return pts;
}

/// A material for a shape: data-material, else the kind's default, with data-temperature applied.
std::string material_for(const Shape& s, const std::string& fallback, WorldSpec& world) {
  std::string name = fallback;
  if (const std::string* m = data(s, "material")) name = *m;
  if (data(s, "temperature")) {
    const double t = data_kelvin(s, "temperature", 0);
    const MaterialSpec* base = world.find_material(name);
    if (!base) throw Error(attr_ref(s, "material"), "unknown material '" + name + "'");
    MaterialSpec hot = *base;
    char b[64];
    std::snprintf(b, sizeof b, "%s@%.2fK", name.c_str(), t);
    hot.name = b;
    hot.temperature = t;
    world.set_material(hot);
    name = hot.name;
  }
  return name;
}

/// Closed outlines of a filled shape, counter-clockwise; inner outlines (holes) are dropped
/// with a warning, since solids are extruded from simple polygons.
std::vector<Polygon2> outlines(const Shape& s, Diagnostics& diag) {
  std::vector<Polygon2> polys;
  for (const auto& sp : s.subpaths) {
    Polygon2 p = normalized(sp.points, 1e-9);
    if (p.size() < 3 || std::abs(signed_area(p)) < 1e-12) continue;
    polys.push_back(std::move(p));
  }
  std::vector<Polygon2> out;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    bool hole = false;
    for (std::size_t j = 0; j < polys.size() && !hole; ++j) {
      if (i != j && std::abs(signed_area(polys[j])) > std::abs(signed_area(polys[i])) && contains(polys[j], polys[i][0])) hole = true;
    }
    if (hole) {
      diag.warn(s.source, "an inner outline (a hole) is not supported; the shape is filled solid");
      continue;
    }
    out.push_back(polys[i]);
  }
  if (out.empty()) diag.warn(s.source, "shape has no area; ignored");
  return out;
}

void add_walls(const Shape& s, const SvgLoadOptions& o, WorldSpec& world, Diagnostics& diag) {
  const double height = data_metres(s, "height", o.wall_height);
  const double w = s.stroke_width;
  if (!(w > 0)) {
    diag.warn(s.source, "stroke width is zero; no wall made");
    return;
  }
  const std::string material = material_for(s, "wall", world);
  const bool capped = s.style.linecap == "square" || s.style.linecap == "round";
  int made = 0;
  for (const auto& sp : s.subpaths) {
    std::vector<Vec2> pts = sp.points;
    if (sp.closed && pts.size() > 2) pts.push_back(pts.front());
    const std::size_t n = pts.size();
    for (std::size_t i = 0; i + 1 < n; ++i) {
      Vec2 a = pts[i], b = pts[i + 1];
      const double len = (b - a).norm();
      if (len < 1e-9) continue;
      const Vec2 d = (b - a) / len;
      // interior joints overlap by half the width so corners close; ends follow the line cap
      const bool a_joint = i > 0 || sp.closed;
      const bool b_joint = i + 2 < n || sp.closed;
      if (a_joint || capped) a -= d * (w / 2);
      if (b_joint || capped) b += d * (w / 2);
      WallSpec wall;
      wall.a = a;
      wall.b = b;
      wall.thickness = w;
      wall.height = height;
      wall.material = material;
      wall.source = s.source;
      world.walls.push_back(std::move(wall));
      ++made;
    }
  }
  if (made == 0) diag.warn(s.source, "stroked shape has no length; no wall made");
}

void add_blocks(const Shape& s, const SvgLoadOptions& o, WorldSpec& world, Diagnostics& diag) {
  const double height = data_metres(s, "height", o.obstacle_height);
  const std::string material = material_for(s, "obstacle", world);
  for (auto& p : outlines(s, diag)) world.blocks.push_back({std::move(p), height, material, s.source});
}

/// Edges of a counter-clockwise polygon whose outward normal points to one of the named sides.
std::vector<int> ramp_edges(const Shape& s, const Polygon2& poly) {
  std::vector<int> edges;
  const int n = static_cast<int>(poly.size());
  if (const std::string* list = data(s, "ramp-edges")) {
    std::size_t pos = 0;
    try {
      while (!at_end(*list, pos)) {
        const double e = read_number(*list, pos);
        if (e != std::floor(e) || e < 0 || e >= n) {
          throw Error(attr_ref(s, "ramp-edges"),
                      "edge " + message_number(e) + " does not exist; the outline has " + std::to_string(n) + " edges");
        }
        edges.push_back(static_cast<int>(e));
      }
    } catch (const ParseError& e) {
      throw Error(attr_ref(s, "ramp-edges"), std::string(e.what()) + " (expected edge indices like '0,2')");
    }
    return edges;
  }
  const std::string spec = data(s, "ramps") ? *data(s, "ramps") : std::string("all");
  if (spec == "none") return edges;
  bool want[4] = {false, false, false, false};  // east, north, west, south
  if (spec == "all") {
    for (int e = 0; e < n; ++e) edges.push_back(e);
    return edges;
  }
  std::size_t i = 0;
  while (i <= spec.size()) {
    std::size_t j = spec.find(',', i);
    if (j == std::string::npos) j = spec.size();
    std::string side = spec.substr(i, j - i);
    side.erase(std::remove_if(side.begin(), side.end(), [](unsigned char c) { return std::isspace(c); }), side.end());
    i = j + 1;
    if (side.empty()) continue;
    if (side == "east" || side == "e") want[0] = true;
    else if (side == "north" || side == "n") want[1] = true;
    else if (side == "west" || side == "w") want[2] = true;
    else if (side == "south" || side == "s") want[3] = true;
    else throw Error(attr_ref(s, "ramps"), "unknown side '" + side + "'; expected all, none, or a list of north, east, south, west");
  }
  const Vec2 dirs[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  for (int e = 0; e < n; ++e) {
    const Vec2 d = (poly[static_cast<std::size_t>((e + 1) % n)] - poly[static_cast<std::size_t>(e)]).normalized();
    const Vec2 out(d.y(), -d.x());
    for (int k = 0; k < 4; ++k) {
      if (want[k] && out.dot(dirs[k]) > std::cos(M_PI / 4) - 1e-9) {
        edges.push_back(e);
        break;
      }
    }
  }
  return edges;
}

void add_raised(const Shape& s, const SvgLoadOptions& o, WorldSpec& world, Diagnostics& diag) {
  const double height = data_metres(s, "height", o.raised_height);
  const double ramp = data_metres(s, "ramp-length", o.ramp_length);
  const std::string material = material_for(s, "raised", world);
  for (auto& p : outlines(s, diag)) {
    RaisedAreaSpec r;
    r.ramp_edges = ramp_edges(s, p);
    r.outline = std::move(p);
    r.height = height;
    r.ramp_length = ramp;
    r.material = material;
    r.source = s.source;
    world.raised_areas.push_back(std::move(r));
  }
}

void add_victim(const Shape& s, const SvgLoadOptions& o, WorldSpec& world) {
  const auto pts = all_points(s);
  const OrientedExtent ext = oriented_extent(pts);
  VictimSpec v;
  v.source = s.source;
  const bool has_yaw = data(s, "yaw") != nullptr;
  // a round marker has no direction of its own: east unless data-yaw says otherwise
  const double yaw = has_yaw ? data_number(s, "yaw", 0) * M_PI / 180.0 : (s.is_round ? 0.0 : ext.angle);
  const AxisExtent along = extent_along(pts, yaw);
  Vec2 centre = s.is_round ? s.centre : along.centre;
  // an elongated shape is the body itself; a square or round one only marks the place
  const bool body_shape = !s.is_round && along.along >= 1.5 * along.across;
  v.length = data_metres(s, "length", body_shape ? along.along : o.victim_length);
  v.width = data_metres(s, "width", body_shape ? along.across : o.victim_width);
  v.pose = {centre.x(), centre.y(), wrap_angle(yaw)};
  if (const std::string* p = data(s, "posture")) {
    if (*p == "lying") v.posture = VictimSpec::Posture::lying;
    else if (*p == "sitting") v.posture = VictimSpec::Posture::sitting;
    else throw Error(attr_ref(s, "posture"), "unknown posture '" + *p + "'; expected lying or sitting");
  }
  v.skin_temperature = data_kelvin(s, "temperature", v.skin_temperature);
  v.clothes_temperature = data_kelvin(s, "clothes-temperature", v.clothes_temperature);
  if (const std::string* n = data(s, "name")) v.name = *n;
  else if (!s.id.empty()) v.name = s.id;
  else v.name = "victim_" + std::to_string(world.victims.size() + 1);
  world.victims.push_back(std::move(v));
}

void add_rubble(const Shape& s, const SvgLoadOptions& o, WorldSpec& world) {
  RubbleSpec r;
  r.source = s.source;
  bool cylinder = s.is_round;
  if (const std::string* shape = data(s, "shape")) {
    if (*shape == "box") cylinder = false;
    else if (*shape == "cylinder") cylinder = true;
    else throw Error(attr_ref(s, "shape"), "unknown shape '" + *shape + "'; expected box or cylinder");
  }
  const auto pts = all_points(s);
  const double height = data_metres(s, "height", o.rubble_height);
  const bool has_yaw = data(s, "yaw") != nullptr;
  const double yaw = has_yaw ? data_number(s, "yaw", 0) * M_PI / 180.0 : oriented_extent(pts).angle;
  const AxisExtent e = extent_along(pts, yaw);
  if (cylinder) {
    const double d = s.is_round ? 2 * s.radius : 0.5 * (e.along + e.across);
    const Vec2 c = s.is_round ? s.centre : e.centre;
    r.shape = RubbleSpec::Shape::cylinder;
    r.pose = {c.x(), c.y(), has_yaw ? wrap_angle(yaw) : 0.0};
    r.size = {d, d, height};
  } else {
    r.shape = RubbleSpec::Shape::box;
    r.pose = {e.centre.x(), e.centre.y(), wrap_angle(yaw)};
    r.size = {e.along, e.across, height};
  }
  const double volume = r.shape == RubbleSpec::Shape::box ? r.size.x() * r.size.y() * r.size.z()
                                                          : M_PI * 0.25 * r.size.x() * r.size.x() * r.size.z();
  r.mass = data_number(s, "mass", volume * o.rubble_density);
  if (!(r.mass > 0) || !std::isfinite(r.mass)) throw Error(attr_ref(s, "mass"), "mass " + message_number(r.mass) + " kg is not positive");
  r.material = material_for(s, "rubble", world);
  world.rubble.push_back(std::move(r));
}

/// The terrain kind an element's data-kind names, if it names one.
std::optional<TerrainSpec::Kind> terrain_kind(const Shape& s) {
  const std::string* k = data(s, "kind");
  if (!k) return std::nullopt;
  using K = TerrainSpec::Kind;
  for (K kind : {K::stepfield, K::stairs, K::crossing_ramps, K::curb, K::hurdle, K::gap}) {
    if (*k == TerrainSpec::kind_name(kind)) return kind;
  }
  return std::nullopt;
}

/// A terrain element drawn as its footprint: the shape's extent along the direction of travel
/// (data-yaw in degrees, else the footprint's long side) and across it; its parameters from
/// data-* attributes, the kind's defaults otherwise (docs/terrain.md).
void add_terrain(const Shape& s, TerrainSpec::Kind kind, WorldSpec& world) {
  TerrainSpec t = TerrainSpec::defaults(kind);
  t.source = s.source;
  const auto pts = all_points(s);
  const double yaw = data(s, "yaw") ? data_number(s, "yaw", 0) * M_PI / 180.0 : oriented_extent(pts).angle;
  const AxisExtent e = extent_along(pts, yaw);
  t.pose = {e.centre.x(), e.centre.y(), wrap_angle(yaw)};
  t.length = e.along;
  t.width = e.across;
  t.height = data_metres(s, "height", t.height);
  t.post = data_metres(s, "post", t.post);
  t.riser = data_metres(s, "riser", t.riser);
  t.gap = data_metres(s, "gap", t.gap);
  t.thickness = data_metres(s, "thickness", t.thickness);
  t.angle = data_number(s, "angle", t.angle);
  if (const std::string* p = data(s, "pattern")) {
    if (*p == "half-cubic") t.half_cubic = true;
    else if (*p == "full-cubic") t.half_cubic = false;
    else throw Error(attr_ref(s, "pattern"), "unknown pattern '" + *p + "'; expected half-cubic or full-cubic");
  }
  if (data(s, "seed")) {
    const double seed = data_number(s, "seed", 1);
    if (!(seed >= 0) || seed != std::floor(seed) || seed > 9.007199254740992e15) {
      throw Error(attr_ref(s, "seed"), "seed " + message_number(seed) + " is not a whole number from 0 to 2^53");
    }
    t.seed = static_cast<std::uint64_t>(seed);
  }
  t.material = material_for(s, "raised", world);
  if (const std::string* n = data(s, "name")) t.name = *n;
  else if (!s.id.empty()) t.name = s.id;
  else t.name = (kind == TerrainSpec::Kind::crossing_ramps ? std::string("crossing_ramps") : TerrainSpec::kind_name(kind)) + "_" +
                std::to_string(world.terrain.size() + 1);
  world.terrain.push_back(std::move(t));
}

/// The medium kind an element's data-kind names, if it names one.
std::optional<MediumSpec::Kind> medium_kind(const Shape& s) {
  const std::string* k = data(s, "kind");
  if (!k) return std::nullopt;
  for (MediumSpec::Kind kind : {MediumSpec::Kind::smoke, MediumSpec::Kind::dust}) {
    if (*k == MediumSpec::kind_name(kind)) return kind;
  }
  return std::nullopt;
}

/// A finite number from a data-* attribute that must not be negative.
double data_not_negative(const Shape& s, const std::string& key, double fallback, const char* expected) {
  const double x = data_number(s, key, fallback);
  if (!std::isfinite(x) || x < 0) {
    throw Error(attr_ref(s, key), "'" + *data(s, key) + "' is not " + expected);
  }
  return x;
}

/// A smoke or dust volume drawn as its footprint (docs/environment.md): one medium per closed
/// outline, with data-density (visible extinction, 1/m), data-bottom and data-height (m),
/// data-growth (m/s outward) and data-drift-x, data-drift-y (m/s).
void add_medium(const Shape& s, MediumSpec::Kind kind, const SvgLoadOptions& o, WorldSpec& world, Diagnostics& diag) {
  const char* what = MediumSpec::kind_name(kind);
  MediumSpec m;
  m.kind = kind;
  m.source = s.source;
  if (!data(s, "density")) {
    throw Error(s.source,
                std::string("a ") + what +
                    " volume needs data-density: its extinction coefficient for visible light in 1/m (about 3 / the visibility in m)");
  }
  m.density =
      data_not_negative(s, "density", 0, "an extinction coefficient: a finite number of 1/m, 0 or more (about 3 / the visibility in m)");
  m.bottom = data_metres(s, "bottom", 0.0, true);
  m.height = data_metres(s, "height", o.wall_height);
  m.growth = data_not_negative(s, "growth", 0, "a growth rate: a finite number of m/s, 0 or more");
  m.drift = {data_number(s, "drift-x", 0), data_number(s, "drift-y", 0)};
  for (const char* key : {"drift-x", "drift-y"}) {
    if (!std::isfinite(data_number(s, key, 0))) throw Error(attr_ref(s, key), "'" + *data(s, key) + "' is not a finite speed in m/s");
  }
  std::size_t points = 0;
  for (const auto& sp : s.subpaths) points = std::max(points, sp.points.size());
  std::vector<Polygon2> polys;
  if (points >= 3) polys = outlines(s, diag);
  if (polys.empty()) {
    throw Error(s.source,
                std::string("a ") + what +
                    " footprint needs an area: a rect, or a polygon or closed path of at least 3 points not on one line (it has " +
                    std::to_string(points) + (points == 1 ? " point)" : " points)"));
  }
  std::string base;
  if (const std::string* n = data(s, "name")) base = *n;
  else if (!s.id.empty()) base = s.id;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    MediumSpec piece = m;
    piece.outline = std::move(polys[i]);
    piece.name = base.empty() ? std::string(what) + "_" + std::to_string(world.media.size() + 1)
                              : (polys.size() > 1 ? base + "_" + std::to_string(i + 1) : base);
    world.media.push_back(std::move(piece));
  }
}

/// The ground material a fill pattern names (docs/terrain.md, "Ground materials"):
/// `fill="url(#sand)"` for the four ground materials by name, `url(#ground-NAME)` (or
/// `ground_NAME`) for any material; nullopt for any other fill. Throws Error for
/// `ground-NAME` with a material the world does not have.
std::optional<std::string> ground_pattern(const Shape& s, const WorldSpec& world) {
  const std::string& id = s.style.fill.url;
  if (id.empty()) return std::nullopt;
  for (const char* m : {"concrete", "wood", "sand", "wet_tiles"}) {
    if (id == m) return id;
  }
  if (id.rfind("ground-", 0) != 0 && id.rfind("ground_", 0) != 0) return std::nullopt;
  const std::string name = id.substr(7);
  if (!world.find_material(name)) {
    std::string known;
    for (const auto& m : world.materials) known += (known.empty() ? "" : ", ") + m.name;
    SourceRef at = s.source;
    at.element += " attribute fill";
    throw Error(at, "fill pattern '#" + id + "' names unknown material '" + name + "' (expected one of: " + known + ")");
  }
  return name;
}

/// A floor patch of another material drawn as its footprint (docs/terrain.md, "Ground
/// materials"): one ground area per closed outline, its material from data-material (required
/// unless its fill pattern names one, `pattern`; data-temperature applies as for any element),
/// its name from data-name or the id.
void add_ground(const Shape& s, WorldSpec& world, Diagnostics& diag, const std::optional<std::string>& pattern = std::nullopt) {
  const std::string* named = data(s, "material");
  if (!named && pattern) named = &*pattern;
  if (!named) {
    throw Error(s.source, "a ground area needs data-material (or a fill pattern named after one, fill=\"url(#sand)\"): the material of its "
                          "floor, such as concrete, wood, sand or wet_tiles");
  }
  if (!world.find_material(*named)) {
    std::string known;
    for (const auto& m : world.materials) known += (known.empty() ? "" : ", ") + m.name;
    throw Error(attr_ref(s, "material"), "unknown material '" + *named + "' (expected one of: " + known + ")");
  }
  const std::string material = material_for(s, *named, world);
  std::size_t points = 0;
  for (const auto& sp : s.subpaths) points = std::max(points, sp.points.size());
  std::vector<Polygon2> polys;
  if (points >= 3) polys = outlines(s, diag);
  if (polys.empty()) {
    throw Error(
        s.source,
        "a ground area needs a footprint with an area: a rect, or a polygon or closed path of at least 3 points not on one line (it has " +
            std::to_string(points) + (points == 1 ? " point)" : " points)"));
  }
  std::string base;
  if (const std::string* n = data(s, "name")) base = *n;
  else if (!s.id.empty()) base = s.id;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    GroundAreaSpec g;
    g.outline = std::move(polys[i]);
    g.material = material;
    g.source = s.source;
    g.name = base.empty() ? *named + "_" + std::to_string(world.ground.size() + 1)
                          : (polys.size() > 1 ? base + "_" + std::to_string(i + 1) : base);
    world.ground.push_back(std::move(g));
  }
}

struct Start {
  RobotPlacement placement;
  double radius = 0;
  bool has_heading = false;
};

Start make_start(const Shape& s, int index) {
  Start st;
  const auto pts = all_points(s);
  const OrientedExtent ext = oriented_extent(pts);
  const Vec2 c = s.is_round ? s.centre : centroid(normalized(pts));
  st.radius = s.is_round ? s.radius : 0.5 * ext.length;
  st.placement.start = {c.x(), c.y(), 0.0};
  st.placement.source = s.source;
  if (data(s, "yaw")) {
    st.placement.start.yaw = wrap_angle(data_number(s, "yaw", 0) * M_PI / 180.0);
    st.has_heading = true;
  }
  if (const std::string* n = data(s, "name")) st.placement.name = *n;
  else if (!s.id.empty()) st.placement.name = s.id;
  else st.placement.name = index == 0 ? "robot" : "robot_" + std::to_string(index + 1);
  if (const std::string* m = data(s, "model")) st.placement.model = *m;
  return st;
}

}  // namespace

double data_metres(const Shape& s, const std::string& key, double fallback, bool allow_zero) {
  const std::string* v = data(s, key);
  if (!v) return fallback;
  double m = 0;
  try {
    const Length l = parse_length(*v);
    if (l.unit == Unit::none) m = l.value;
    else if (l.physical()) m = l.metres();
    else throw ParseError("expected metres, or a length in m, cm or mm", 0);
  } catch (const ParseError& e) {
    throw Error(attr_ref(s, key), "'" + *v + "': " + e.what());
  }
  if (!std::isfinite(m) || m < 0 || (!allow_zero && m == 0)) {
    throw Error(attr_ref(s, key), "'" + *v + "' is not a positive length in metres");
  }
  return m;
}

double data_kelvin(const Shape& s, const std::string& key, double fallback) {
  const std::string* v = data(s, key);
  if (!v) return fallback;
  std::string text = *v;
  double offset = 0;
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  if (!text.empty() && (text.back() == 'C' || text.back() == 'c')) {
    offset = 273.15;
    text.pop_back();
  } else if (!text.empty() && (text.back() == 'K' || text.back() == 'k')) {
    text.pop_back();
  }
  double t = 0;
  try {
    std::size_t pos = 0;
    t = read_number(text, pos) + offset;
    if (!at_end(text, pos)) throw ParseError("unexpected text after the number", pos);
  } catch (const ParseError& e) {
    throw Error(attr_ref(s, key), "'" + *v + "': " + e.what() + " (expected a temperature like 310, 310K or 37C)");
  }
  if (!(t > 0)) throw Error(attr_ref(s, key), "'" + *v + "' is not above absolute zero");
  return t;
}

double data_number(const Shape& s, const std::string& key, double fallback) {
  const std::string* v = data(s, key);
  if (!v) return fallback;
  try {
    std::size_t pos = 0;
    const double x = read_number(*v, pos);
    if (!at_end(*v, pos)) throw ParseError("unexpected text after the number", pos);
    return x;
  } catch (const ParseError& e) {
    throw Error(attr_ref(s, key), "'" + *v + "': " + e.what());
  }
}

void build_world(const std::vector<Shape>& shapes, const SvgLoadOptions& o, WorldSpec& world, Diagnostics& diag) {
  std::vector<Start> starts;
  std::vector<const Shape*> heading_lines;
  for (const Shape& s : shapes) {
    if (const auto kind = terrain_kind(s)) {
      add_terrain(s, *kind, world);
      continue;
    }
    if (const auto kind = medium_kind(s)) {
      add_medium(s, *kind, o, world, diag);
      continue;
    }
    if (const std::string* k = data(s, "kind"); k && *k == "ground") {
      add_ground(s, world, diag, ground_pattern(s, world));
      continue;
    }
    // a fill pattern makes a ground area only of a shape with no other data-kind (which is not
    // then looked up, so a wall painted with any pattern stays a wall)
    if (const auto pattern = data(s, "kind") ? std::nullopt : ground_pattern(s, world)) {
      add_ground(s, world, diag, *pattern);
      continue;
    }
    const Meaning m = meaning_of(s);
    switch (m.kind) {
      case Semantic::wall:
        if (m.filled) add_blocks(s, o, world, diag);
        else add_walls(s, o, world, diag);
        break;
      case Semantic::raised: add_raised(s, o, world, diag); break;
      case Semantic::victim: add_victim(s, o, world); break;
      case Semantic::rubble: add_rubble(s, o, world); break;
      case Semantic::start:
        if (s.tag == Shape::Tag::line || (!m.filled && s.tag == Shape::Tag::polyline)) {
          heading_lines.push_back(&s);
        } else {
          starts.push_back(make_start(s, static_cast<int>(starts.size())));
        }
        break;
      case Semantic::background: break;
      case Semantic::unknown:
        diag.warn(s.source, std::string(m.filled ? "fill" : "stroke") + " colour " + hex(m.color) +
                                " has no meaning in a world drawing; ignored (expected black walls, red raised areas, "
                                "blue victims, green starts or orange rubble; see docs/worlds.md)");
        break;
    }
  }

  // heading lines: the end inside a start circle is the tail, the other end the head
  for (const Shape* line : heading_lines) {
    const auto& pts = line->subpaths.front().points;
    if (pts.size() < 2) continue;
    const Vec2 p0 = pts.front(), p1 = pts.back();
    Start* best = nullptr;
    double best_d = 1e300;
    bool tail_is_p0 = true;
    for (auto& st : starts) {
      const Vec2 c = st.placement.start.position();
      const double d0 = (p0 - c).norm(), d1 = (p1 - c).norm();
      const double d = std::min(d0, d1);
      if (d <= 1.1 * st.radius + 1e-9 && d < best_d) {
        best = &st;
        best_d = d;
        tail_is_p0 = d0 <= d1;
      }
    }
    if (!best) {
      diag.warn(line->source, "green line does not start inside a green start circle; ignored");
      continue;
    }
    if (best->has_heading) continue;
    const Vec2 dir = tail_is_p0 ? Vec2(p1 - p0) : Vec2(p0 - p1);
    best->placement.start.yaw = std::atan2(dir.y(), dir.x());
    best->has_heading = true;
  }
  for (auto& st : starts) world.robots.push_back(std::move(st.placement));
}

}  // namespace rescuesim::svg
