#include "import/scenario/scenario.h"
#include "world/terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "core/atomic_file.h"
#include "import/scenario/scenario_mission.h"
#include "import/scenario/scenario_robots.h"
#include "import/scenario/yaml_reader.h"

namespace rescuesim {

extern const char* const kDefaultScenarioYaml;

namespace {

constexpr double kDeg = M_PI / 180.0;

MazeOptions read_maze(const YamlNode& m, std::uint64_t run_seed) {
  MazeOptions o;
  o.cols = static_cast<int>(m.integer("cols", o.cols, 1, 500));
  o.rows = static_cast<int>(m.integer("rows", o.rows, 1, 500));
  o.cell_size = m.number("cell_size", o.cell_size, 0.2, 100);
  o.wall_thickness = m.number("wall_thickness", o.wall_thickness, 0.001, 10);
  o.wall_height = m.number("wall_height", o.wall_height, 0.01, 100);
  o.loop_fraction = m.number("loop_fraction", o.loop_fraction, 0, 1);
  o.rubble = static_cast<int>(m.integer("rubble", o.rubble, 0, 10000));
  o.raised_fraction = m.number("raised_fraction", o.raised_fraction, 0, 1);
  o.raised_height = m.number("raised_height", o.raised_height, 0.001, 10);
  o.ramp_length = m.number("ramp_length", o.ramp_length, 0.01, 100);
  o.victims = static_cast<int>(m.integer("victims", o.victims, 0, 10000));
  o.terrain_fraction = m.number("terrain_fraction", o.terrain_fraction, 0, 1);
  if (m.has("terrain")) {
    o.terrain.clear();
    for (const auto& k : m.sequence("terrain")) {
      try {
        o.terrain.push_back(terrain_kind_from_name(k.scalar()));
      } catch (const Error& e) {
        throw Error(m.where("terrain"), e.message());
      }
    }
  }
  const auto start = m.numbers("start_cell", {0, 0}, 2);
  if (start[0] != std::floor(start[0]) || start[1] != std::floor(start[1]) || start[0] < 0 || start[1] < 0 ||
      start[0] >= o.cols || start[1] >= o.rows) {
    throw Error(m.where("start_cell"), "start cell [" + std::to_string(start[0]) + ", " + std::to_string(start[1]) +
                                           "] is not a cell of a " + std::to_string(o.cols) + " x " + std::to_string(o.rows) + " maze");
  }
  o.start_cell = {static_cast<int>(start[0]), static_cast<int>(start[1])};
  // start_cells: one robot per cell, the first taking start_cell's place
  if (m.has("start_cells")) {
    if (m.has("start_cell")) throw Error(m.where("start_cells"), "give start_cell or start_cells, not both");
    const auto cells = m.sequence("start_cells");
    if (cells.empty()) throw Error(m.where("start_cells"), "expected a list of [col, row] cells, one per robot");
    std::vector<std::array<int, 2>> read;
    for (const auto& c : cells) {
      const auto xy = c.items();
      const auto whole = [&](const YamlNode& n) {
        const std::string text = n.scalar();
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (xy.size() != 2 || end == text.c_str() || *end != '\0' || v != std::floor(v) || v < 0 || v > 100000) {
          throw Error(c.where(), "expected a cell as [col, row] with whole numbers >= 0, got '" + text + "'");
        }
        return static_cast<int>(v);
      };
      if (xy.size() != 2) throw Error(c.where(), "expected a cell as [col, row]");
      read.push_back({whole(xy[0]), whole(xy[1])});
      if (read.back()[0] >= o.cols || read.back()[1] >= o.rows) {
        throw Error(c.where(), "cell [" + std::to_string(read.back()[0]) + ", " + std::to_string(read.back()[1]) + "] is not a cell of a " +
                                   std::to_string(o.cols) + " x " + std::to_string(o.rows) + " maze");
      }
    }
    o.start_cell = read[0];
    o.more_start_cells.assign(read.begin() + 1, read.end());
  }
  o.seed = m.uint64("seed", run_seed);
  m.finish();
  return o;
}

void read_svg_defaults(const YamlNode& d, SvgLoadOptions& o) {
  o.wall_height = d.number("wall_height", o.wall_height, 0.001, 100);
  o.obstacle_height = d.number("obstacle_height", o.obstacle_height, 0.001, 100);
  o.raised_height = d.number("raised_height", o.raised_height, 0.001, 10);
  o.ramp_length = d.number("ramp_length", o.ramp_length, 0.01, 100);
  o.rubble_height = d.number("rubble_height", o.rubble_height, 0.001, 10);
  o.rubble_density = d.number("rubble_density", o.rubble_density, 1, 20000);
  o.victim_length = d.number("victim_length", o.victim_length, 0.1, 3);
  o.victim_width = d.number("victim_width", o.victim_width, 0.05, 2);
  o.curve_tolerance = d.number("curve_tolerance", o.curve_tolerance, 1e-4, 1);
  d.finish();
}

/// world.include: models placed by the scenario, each a URI or {uri, name, pose: {x, y, z,
/// roll, pitch, yaw}} (m and degrees, like a robot's start).
std::vector<SdfInclude> read_includes(const YamlNode& w, const std::string& file) {
  std::vector<SdfInclude> out;
  if (!w.has("include")) return out;
  if (!w.has_sequence("include")) throw Error(w.where("include"), "expected a list of model URIs or {uri, name, pose} maps");
  const auto items = w.sequence("include");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const YamlNode& n = items[i];
    SdfInclude inc;
    inc.source = n.where();
    if (inc.source.file.empty()) inc.source.file = file;
    if (!n.is_map()) {
      inc.uri = n.scalar();
    } else {
      inc.uri = n.string("uri", "");
      inc.name = n.string("name", "");
      if (n.has("pose")) {
        const YamlNode p = n.map("pose");
        inc.pose = Pose3::from_rpy(Vec3(p.required_number("x"), p.required_number("y"), p.number("z", 0)),
                                   p.number("roll", 0, -360, 360) * kDeg, p.number("pitch", 0, -360, 360) * kDeg,
                                   p.number("yaw", 0, -360, 360) * kDeg);
        inc.has_pose = true;
        p.finish();
      }
      n.finish();
    }
    if (inc.uri.empty()) throw Error(n.where(), "an include needs a model URI (model://name, a model folder or an .sdf file)");
    out.push_back(std::move(inc));
  }
  return out;
}

/// A map's `outline`: at least 3 [x, y] points (m), returned counter-clockwise.
Polygon2 read_outline(const YamlNode& n) {
  Polygon2 outline;
  if (!n.has_sequence("outline")) throw Error(n.where("outline"), "expected the footprint as a list of at least 3 [x, y] points (m)");
  for (const YamlNode& p : n.sequence("outline")) {
    const std::vector<YamlNode> xy = p.is_sequence() ? p.items() : std::vector<YamlNode>{};
    double v[2] = {0, 0};
    bool ok = xy.size() == 2;
    for (std::size_t k = 0; ok && k < 2; ++k) {
      const std::string text = xy[k].is_sequence() || xy[k].is_map() ? std::string() : xy[k].scalar();
      char* end = nullptr;
      v[k] = std::strtod(text.c_str(), &end);
      ok = !text.empty() && end && *end == 0 && std::isfinite(v[k]);
    }
    if (!ok) throw Error(p.where(), "expected a point [x, y] of two finite numbers (m)");
    outline.push_back({v[0], v[1]});
  }
  if (outline.size() < 3) {
    throw Error(n.where("outline"),
                "the footprint has " + std::to_string(outline.size()) + " points; expected at least 3 [x, y] points (m)");
  }
  if (signed_area(outline) < 0) std::reverse(outline.begin(), outline.end());
  return outline;
}

/// world.ground: floor patches of other materials, each {material (required), name, outline:
/// [[x, y], ...] (m)}. The material must be known (checked here, so the message has the line).
std::vector<GroundAreaSpec> read_ground(const YamlNode& w, const std::string& file) {
  std::vector<GroundAreaSpec> out;
  if (!w.has("ground")) return out;
  if (!w.has_sequence("ground"))
    throw Error(w.where("ground"), "expected a list of {material, outline} maps (docs/terrain.md, \"Ground materials\")");
  const auto items = w.sequence("ground");
  const std::vector<MaterialSpec> known = default_materials();
  for (std::size_t i = 0; i < items.size(); ++i) {
    const YamlNode& n = items[i];
    if (!n.is_map()) throw Error(n.where(), "expected a map {material, outline} (docs/terrain.md, \"Ground materials\")");
    GroundAreaSpec g;
    g.source = n.where();
    if (g.source.file.empty()) g.source.file = file;
    if (!n.has("material")) throw Error(n.where(), "a ground area needs a material, such as concrete, wood, sand or wet_tiles");
    g.material = n.string("material", "");
    const bool found = std::any_of(known.begin(), known.end(), [&](const MaterialSpec& m) { return m.name == g.material; });
    if (!found) {
      std::string names;
      for (const auto& m : known) names += (names.empty() ? "" : ", ") + m.name;
      throw Error(n.where("material"), "unknown material '" + g.material + "' (expected one of: " + names + ")");
    }
    g.name = n.string("name", g.material + "_" + std::to_string(i + 1));
    g.outline = read_outline(n);
    n.finish();
    out.push_back(std::move(g));
  }
  return out;
}

/// world.media: smoke and dust volumes, each {kind: smoke|dust, name, outline: [[x, y], ...] (m),
/// density (visible extinction, 1/m), bottom, height (m), growth (m/s), drift: [vx, vy] (m/s)}.
std::vector<MediumSpec> read_media(const YamlNode& w, const std::string& file) {
  std::vector<MediumSpec> out;
  if (!w.has("media")) return out;
  if (!w.has_sequence("media"))
    throw Error(w.where("media"), "expected a list of {kind, outline, density, ...} maps (docs/environment.md)");
  const auto items = w.sequence("media");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const YamlNode& n = items[i];
    if (!n.is_map()) throw Error(n.where(), "expected a map {kind, outline, density, ...} (docs/environment.md)");
    MediumSpec m;
    m.source = n.where();
    if (m.source.file.empty()) m.source.file = file;
    m.kind = n.choice("kind", "smoke", {"smoke", "dust"}) == "dust" ? MediumSpec::Kind::dust : MediumSpec::Kind::smoke;
    m.name = n.string("name", std::string(MediumSpec::kind_name(m.kind)) + "_" + std::to_string(i + 1));
    m.density = n.required_number("density", 0, 1e6);
    m.bottom = n.number("bottom", 0, 0, 1e4);
    m.height = n.number("height", m.height, 1e-6, 1e4);
    m.growth = n.number("growth", 0, 0, 1e3);
    const std::vector<double> drift = n.numbers("drift", {0, 0}, 2);
    m.drift = {drift[0], drift[1]};
    m.outline = read_outline(n);
    n.finish();
    out.push_back(std::move(m));
  }
  return out;
}

/// Adds what a scenario's SDF models bring (solids, bodies, their victims and robot starts,
/// materials) to a drawn or generated world, and grows the floor to cover them.
void add_models(WorldSpec& w, const WorldSpec& models) {
  for (const auto& m : models.materials) {
    if (!w.find_material(m.name)) w.set_material(m);
  }
  w.solids.insert(w.solids.end(), models.solids.begin(), models.solids.end());
  w.bodies.insert(w.bodies.end(), models.bodies.begin(), models.bodies.end());
  w.victims.insert(w.victims.end(), models.victims.begin(), models.victims.end());
  w.robots.insert(w.robots.end(), models.robots.begin(), models.robots.end());
  Box2 b{w.floor_min, w.floor_max};
  b.extend(models.content_bounds());
  w.floor_min = b.min;
  w.floor_max = b.max;
}

}  // namespace

Scenario parse_scenario(const std::string& yaml_text, const std::string& file, const ModelMap& models) {
  const YamlNode root = YamlNode::parse(yaml_text, file);
  Scenario s;
  s.source_file = file;
  s.name = root.string("name", s.name);
  if (s.name.empty() || s.name.find('/') != std::string::npos || s.name == "." || s.name == "..") {
    throw Error(root.where("name"), "name '" + s.name + "' cannot name an output folder; use letters, digits, '-' and '_'");
  }
  s.seed = root.uint64("seed", s.seed);
  s.duration = root.number("duration", s.duration, 1e-3, 1e7);
  s.realtime = root.choice("mode", "lockstep", {"lockstep", "realtime"}) == "realtime";
  s.rate = root.number("rate", s.rate, 1e-3, 1e4);
  s.stop_when_all_found = root.boolean("stop_when_all_found", s.stop_when_all_found);
  const YamlNode render = root.map("render");
  s.render_quality = render.choice("quality", s.render_quality, {"low", "medium", "high"});
  s.render_latency = render.number("latency", s.render_latency, -1, 10);
  render.finish();
  const YamlNode physics = root.map("physics");
  const bool dt_given = physics.has("dt");
  s.physics_dt = physics.number("dt", s.physics_dt, 1e-4, 0.05);
  s.solver_iterations = static_cast<int>(physics.integer("solver_iterations", s.solver_iterations, 1, 1000));
  s.physics_groups = static_cast<int>(physics.integer("groups", s.physics_groups, 0, 256));
  physics.finish();

  const YamlNode w = root.map("world");
  s.svg_options.units_per_metre = w.number("svg_scale", s.svg_options.units_per_metre, 1e-6, 1e9);
  s.svg_options.ambient_temperature = w.number("ambient_temperature", s.svg_options.ambient_temperature, 1, 2000);
  read_svg_defaults(w.map("defaults"), s.svg_options);
  const bool has_svg = w.has("svg"), has_maze = w.has("maze"), has_sdf = w.has("sdf");
  if (int(has_svg) + int(has_maze) + int(has_sdf) > 1) {
    throw Error(w.where(has_svg ? "svg" : "maze"), "give one of world.svg, world.maze or world.sdf, not several");
  }
  const bool on_disk = !file.empty() && file != "<built-in>";
  const auto beside_scenario = [&](std::filesystem::path p) {
    if (p.is_relative() && on_disk) p = std::filesystem::path(file).parent_path() / p;
    return p;
  };
  if (has_svg) {
    s.svg = beside_scenario(w.string("svg", ""));
  } else if (has_sdf) {
    s.sdf = beside_scenario(w.string("sdf", ""));
  } else {
    s.maze = read_maze(w.map("maze"), s.seed);
  }
  for (const auto& p : root.strings("resource_paths", {})) s.resource_paths.push_back(beside_scenario(p));
  s.includes = read_includes(w, on_disk ? file : "");
  s.media = read_media(w, on_disk ? file : "");
  if (w.has("ambient_light")) s.ambient_light = w.number("ambient_light", 1.0, 0.0, 10.0);
  if (w.has("sun")) s.sun = w.boolean("sun", true);
  s.ground = read_ground(w, on_disk ? file : "");
  w.finish();
  s.physics_dt_given = dt_given;
  // SDF content is read now, so that `rescuesim check` reports its errors with the scenario's
  load_scenario_models(s);
  RobotReadContext context{on_disk ? file : "", s.resource_paths};
  const auto robots = root.sequence("robots");
  for (std::size_t i = 0; i < robots.size(); ++i) {
    s.robots.push_back(read_robot(robots[i], static_cast<int>(i), models, context));
    for (std::size_t k = 0; k < i; ++k) {
      if (s.robots[k].name == s.robots[i].name) throw Error(robots[i].where("name"), "two robots are named '" + s.robots[i].name + "'");
    }
  }
  if (root.has("mission")) s.mission = read_mission(root.map("mission"));
  root.finish();
  return s;
}

void load_scenario_models(Scenario& s) {
  s.models.reset();
  if (!s.sdf && s.includes.empty()) return;
  SdfOptions o;
  o.resolver = ResourceResolver(s.resource_paths);
  auto models = std::make_shared<SdfWorld>(s.sdf ? load_sdf_world(*s.sdf, o) : SdfWorld{});
  add_sdf_includes(s.includes, o, *models);
  // an SDF world's <max_step_size> is the step unless the scenario gives physics.dt
  const double dt = models->spec.physics_dt;
  if (s.sdf && !s.physics_dt_given && dt >= 1e-4 && dt <= 0.05) s.physics_dt = dt;
  s.models = std::move(models);
}

Scenario load_scenario(const std::filesystem::path& file, const ModelMap& models) {
  return parse_scenario(read_file(file, std::size_t(4) << 20), file.string(), models);
}

Scenario default_scenario(const ModelMap& models) { return parse_scenario(kDefaultScenarioYaml, "<built-in>", models); }

std::string default_scenario_text() { return kDefaultScenarioYaml; }

WorldSpec build_world(const Scenario& scenario, Diagnostics* diagnostics) {
  WorldSpec w;
  if (scenario.sdf) {
    // the SDF world (with any includes) was read with the scenario
    w = scenario.models->spec;
    if (diagnostics) diagnostics->append(scenario.models->diagnostics);
  } else {
    if (scenario.svg) {
      SvgLoadResult r = load_svg_world(*scenario.svg, scenario.svg_options);
      if (diagnostics) diagnostics->append(r.diagnostics);
      w = std::move(r.world);
    } else {
      const MazeOptions opts = scenario.maze ? *scenario.maze : MazeOptions{};
      w = maze_to_world(generate_maze(opts));
    }
    if (scenario.models) {
      add_models(w, scenario.models->spec);
      if (diagnostics) diagnostics->append(scenario.models->diagnostics);
    }
  }
  w.ambient_temperature = scenario.svg_options.ambient_temperature;
  w.media.insert(w.media.end(), scenario.media.begin(), scenario.media.end());
  if (scenario.ambient_light) w.ambient_light = *scenario.ambient_light;
  if (scenario.sun) w.sun = *scenario.sun;
  w.ground.insert(w.ground.end(), scenario.ground.begin(), scenario.ground.end());
  // the scenario's robots take the world's starts in order, unless they bring their own
  if (!scenario.robots.empty()) {
    std::vector<RobotPlacement> placed;
    for (std::size_t i = 0; i < scenario.robots.size(); ++i) {
      const RobotConfig& c = scenario.robots[i];
      RobotPlacement p;
      p.name = c.name;
      p.model = c.model;
      if (c.start) {
        p.start = *c.start;
        p.source = {scenario.source_file, 0, "robots[" + std::to_string(i) + "].start"};
      } else if (i < w.robots.size()) {
        p.start = w.robots[i].start;
        p.height = w.robots[i].height;
        p.source = w.robots[i].source;
      } else {
        throw Error({scenario.source_file, 0, "robots[" + std::to_string(i) + "]"},
                    "robot '" + c.name + "' has no start: the world has " + std::to_string(w.robots.size()) +
                        " start(s); give robots[" + std::to_string(i) + "].start");
      }
      placed.push_back(std::move(p));
    }
    w.robots = std::move(placed);
  }
  return w;
}

namespace {

/// The built-in models plus the robots an SDF world or include describes.
ModelMap with_sdf_robots(const Scenario& scenario, const ModelMap& models) {
  ModelMap all = models;
  if (scenario.models) {
    for (const auto& [name, spec] : scenario.models->robots) all.emplace(name, spec);
  }
  return all;
}

}  // namespace

std::vector<RobotConfig> robot_configs(const Scenario& scenario, const WorldSpec& spec, const ModelMap& models) {
  if (!scenario.robots.empty()) return scenario.robots;
  const ModelMap all = with_sdf_robots(scenario, models);
  std::vector<RobotConfig> out;
  for (const auto& p : spec.robots) {
    RobotConfig c;
    c.name = p.name;
    c.model = p.model;
    const auto it = all.find(p.model);
    if (it == all.end()) throw Error(p.source, "unknown robot model '" + p.model + "'");
    c.spec = it->second;
    // a robot from the SDF world is driven from outside unless the scenario says otherwise
    if (scenario.models && scenario.models->robots.count(p.model)) c.controller = "none";
    out.push_back(std::move(c));
  }
  return out;
}

World compile_scenario(const Scenario& scenario, const WorldSpec& spec, const ModelMap& models) {
  // robots described by their own files (URDF, SDF) are models of this scenario only
  ModelMap all = with_sdf_robots(scenario, models);
  for (const auto& c : scenario.robots) all.emplace(c.model, c.spec);
  World world = compile_world(spec, all);
  const auto configs = robot_configs(scenario, spec, all);
  for (std::size_t i = 0; i < world.robots.size() && i < configs.size(); ++i) world.robots[i].spec = configs[i].spec;
  return world;
}

}  // namespace rescuesim
