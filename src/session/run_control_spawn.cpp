// RunControl's spawning (SpawnEntity, DeleteEntity, GetSpawnables): robots from URDF, SDF or
// rescuesim's own YAML, built-in robots and loose bodies, added to the running simulation
// (Simulation::add_robot, add_body) and removed again (see run_control.h).

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "import/scenario/scenario.h"
#include "import/sdf/sdf_import.h"
#include "import/urdf/urdf_import.h"
#include "robots/rescue_robot.h"
#include "session/run_control.h"
#include "session/session.h"
#include "world/resource_uri.h"

namespace rescuesim {

using namespace control;

namespace {

/// The loose bodies anyone may spawn by name: rubble of the sizes a rescue arena has.
struct BuiltinBody {
  const char* name;
  const char* description;
  Geometry geometry;
  double mass;
};

std::vector<BuiltinBody> builtin_bodies() {
  return {{"box", "a loose box of rubble, 0.3 m a side, 2 kg", Geometry::box(Vec3(0.3, 0.3, 0.3)), 2.0},
          {"brick", "a brick, 0.22 x 0.1 x 0.065 m, 2.5 kg", Geometry::box(Vec3(0.22, 0.1, 0.065)), 2.5},
          {"cylinder", "a loose cylinder (a pipe end), 0.15 m radius, 0.4 m long, 3 kg", Geometry::cylinder(0.15, 0.4), 3.0},
          {"sphere", "a loose ball, 0.1 m radius, 0.5 kg", Geometry::sphere(0.1), 0.5}};
}

/// A ROS name token: a letter, then letters, digits and underscores (what names topics).
bool is_token(const std::string& s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

/// "/a/b/" -> "a/b" when each part is a token; nullopt otherwise.
std::optional<std::string> clean_namespace(const std::string& ns) {
  std::string out;
  std::stringstream parts(ns);
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (part.empty()) continue;
    if (!is_token(part)) return std::nullopt;
    out += (out.empty() ? "" : "/") + part;
  }
  return out;
}

/// What a SpawnEntity request names: a robot, or a loose body.
struct Spawned {
  std::optional<RobotSpec> robot;
  std::optional<DynamicObject> body;
};

/// Why reading a description failed, as SpawnEntity's result code: a file the description
/// names (a mesh) that is not there is MISSING_ASSETS; anything else wrong in it RESOURCE_PARSE_ERROR.
std::uint8_t parse_failure_code(const std::string& what) {
  return what.find("cannot find") != std::string::npos || what.find("No such file") != std::string::npos ? code::kMissingAssets
                                                                                                           : code::kResourceParseError;
}

/// SDF text in a file of its own (sdformat reads files; the URIs in it resolve as for a file in
/// the working folder). Removed when it goes out of scope.
struct TempSdf {
  std::filesystem::path path;
  explicit TempSdf(const std::string& text) {
    path = std::filesystem::temp_directory_path() /
           ("rescuesim-spawn-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++) + ".sdf");
    std::ofstream(path) << text;
  }
  ~TempSdf() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
  static int& counter() {
    static int n = 0;
    return n;
  }
};

}  // namespace

Result RunControl::spawnables(const std::vector<std::string>& sources, std::vector<Spawnable>& out) const {
  out.clear();
  for (const auto& [name, spec] : builtin_models()) {
    Spawnable s;
    s.uri = name;
    s.description = "built-in robot '" + name + "' (rescuesim)";
    out.push_back(std::move(s));
  }
  for (const BuiltinBody& b : builtin_bodies()) {
    Spawnable s;
    s.uri = b.name;
    s.description = b.description;
    out.push_back(std::move(s));
  }
  // robot descriptions in the folders asked for, or else the scenario's resource paths
  std::vector<std::filesystem::path> dirs;
  for (const std::string& src : sources) {
    const std::string p = src.starts_with("file://") ? src.substr(7) : src;
    if (!std::filesystem::is_directory(p)) return Result::fail(code::kOperationFailed, "'" + src + "' is no folder");
    dirs.emplace_back(p);
  }
  if (sources.empty()) dirs = session_.scenario().resource_paths;
  constexpr int kMaxDepth = 4;         // package/urdf/robot.urdf, models/name/model.sdf
  constexpr std::size_t kMaxFound = 500;  // a spawnables list, not a file system index
  std::vector<std::filesystem::path> found;
  for (const auto& d : dirs) {
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(d, std::filesystem::directory_options::skip_permission_denied, ec);
         it != std::filesystem::recursive_directory_iterator() && found.size() < kMaxFound; it.increment(ec)) {
      if (ec) break;
      if (it.depth() >= kMaxDepth) it.disable_recursion_pending();
      const auto& p = it->path();
      if (it->is_regular_file(ec) && (p.extension() == ".urdf" || p.extension() == ".sdf")) found.push_back(std::filesystem::absolute(p));
    }
  }
  std::sort(found.begin(), found.end());
  for (const auto& p : found) {
    Spawnable s;
    s.uri = "file://" + p.string();
    s.description = (p.extension() == ".urdf" ? "URDF robot " : "SDF model ") + p.filename().string();
    out.push_back(std::move(s));
  }
  return Result::ok();
}

Result RunControl::spawn(const SpawnRequest& request, std::string& entity_name) {
  entity_name.clear();
  Simulation& sim = session_.sim();
  // the name: unique among entities, or made so when renaming is allowed
  std::string name = request.name;
  if (name.empty() && !request.allow_renaming) return Result::fail(code::kNameInvalid, "an entity needs a name (or allow_renaming)");
  if (!name.empty() && !is_token(name)) {
    return Result::fail(code::kNameInvalid,
                        "'" + name + "' is no valid name: a letter, then letters, digits and underscores (it names topics)");
  }
  if (name.empty()) name = "entity";
  if (find(name)) {
    if (!request.allow_renaming) return Result::fail(code::kNameNotUnique, "an entity named '" + name + "' exists already");
    const std::string base = name;
    for (int i = 1; find(name); ++i) name = base + "_" + std::to_string(i);
  }
  // the namespace of its topics and frames: the one asked for, else its name; one robot's own
  const std::optional<std::string> ns = clean_namespace(request.entity_namespace.empty() ? name : request.entity_namespace);
  if (!ns || ns->empty()) {
    return Result::fail(code::kNamespaceInvalid,
                        "'" + request.entity_namespace + "' is no valid namespace: tokens of letters, digits and underscores between '/'");
  }
  for (std::size_t r = 0; r < sim.world().robots.size(); ++r) {
    const std::string taken = sim.topic_name(RobotIndex::at(r), "x");  // "/<ns>/x" or "/x"
    if (taken == "/" + *ns + "/x") {
      return Result::fail(code::kNamespaceInvalid, "namespace '/" + *ns + "' is robot '" + sim.world().robots[r].name + "''s already");
    }
  }
  // the pose, in the world or relative to an entity
  Pose3 X_W = request.pose;
  if (const std::string why = pose_problem(X_W); !why.empty()) return Result::fail(code::kSpawnInvalidPose, "initial_pose: " + why);
  X_W.q.normalize();
  if (!request.frame_id.empty() && request.frame_id != "world" && request.frame_id != "map") {
    EntityState parent;
    if (!find(request.frame_id) || !entity_state(request.frame_id, parent).is_ok()) {
      return Result::fail(code::kSpawnInvalidPose,
                          "the pose's frame '" + request.frame_id + "' is neither the world ('world', 'map', '') nor an entity");
    }
    X_W = parent.pose * X_W;
  }

  // what to spawn
  Spawned what;
  const std::vector<std::filesystem::path>& paths = session_.scenario().resource_paths;
  const ModelMap models = builtin_models();
  const std::string& uri = request.uri;
  try {
    if (uri.empty() && request.resource_string.empty()) {
      return Result::fail(code::kNoResource, "give a uri (a built-in name, a URDF, SDF or YAML file) or a resource_string");
    }
    if (uri.empty()) {
      const std::string& text = request.resource_string;
      const auto first = text.find_first_not_of(" \t\r\n");
      if (first != std::string::npos && text[first] == '<') {
        if (text.find("<robot") != std::string::npos) {
          UrdfOptions o;
          o.resolver = ResourceResolver(paths);
          what.robot = parse_urdf(text, "<resource_string>", o).spec;
        } else if (text.find("<sdf") != std::string::npos) {
          SdfOptions o;
          o.resolver = ResourceResolver(paths);
          const TempSdf file(text);
          what.robot = load_sdf_robot(file.path.string(), o, {"<resource_string>", 0, "sdf"}).spec;
        } else {
          return Result::fail(code::kUnsupportedFormat, "the resource_string is XML but neither URDF (<robot>) nor SDF (<sdf>)");
        }
      } else {
        what.robot = read_robot_yaml(text, "<resource_string>", models, paths).spec;
      }
    } else if (models.count(uri)) {
      what.robot = models.at(uri);
    } else if (const std::vector<BuiltinBody> bodies = builtin_bodies();
               std::any_of(bodies.begin(), bodies.end(), [&](const BuiltinBody& x) { return x.name == uri; })) {
      const auto b = std::find_if(bodies.begin(), bodies.end(), [&](const BuiltinBody& x) { return x.name == uri; });
      DynamicObject o;
      o.geometry = b->geometry;
      o.mass = b->mass;
      o.inertia = solid_inertia(b->geometry, b->mass);
      what.body = std::move(o);
    } else {
      const ResourceResolver resolver(paths);
      std::filesystem::path file;
      if (!uri.starts_with("model://")) {
        try {
          file = resolver.resolve(uri, {"<spawn request>", 0, "uri"});
        } catch (const Error& e) {
          return Result::fail(code::kNoResource, e.what());
        }
      }
      if (uri.starts_with("model://") || is_sdf_path(file) || std::filesystem::is_directory(file)) {
        SdfOptions o;
        o.resolver = resolver;
        what.robot = load_sdf_robot(uri.starts_with("model://") ? uri : file.string(), o, {"<spawn request>", 0, "uri"}).spec;
      } else if (is_urdf_path(file)) {
        UrdfOptions o;
        o.resolver = resolver;
        what.robot = load_urdf(file, o).spec;
      } else if (file.extension() == ".yaml" || file.extension() == ".yml") {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        what.robot = read_robot_yaml(text.str(), file.string(), models, paths).spec;
      } else {
        return Result::fail(
            code::kUnsupportedFormat,
            "'" + uri + "': spawn takes URDF (.urdf), SDF (.sdf, model://, a model folder) or rescuesim YAML (.yaml) robots");
      }
    }
  } catch (const Error& e) {
    return Result::fail(parse_failure_code(e.what()), e.what());
  }

  try {
    if (what.body) {
      DynamicObject o = std::move(*what.body);
      o.name = name;
      o.X_WO = X_W;
      o.spawned = true;
      // a body that would start in the floor starts 2 mm above it (as place_robot does for robots)
      double lowest = 0;
      for (const Vec3& v : mesh_of(o.geometry, 24).vertices) lowest = std::min(lowest, (o.X_WO.q * v).z());
      o.X_WO.p.z() = std::max(o.X_WO.p.z(), 0.002 - lowest);
      sim.add_body(std::move(o));
    } else {
      // without a camera service (no cameras in the run, or --no-cameras) its cameras are off too
      if (!session_.renders_cameras()) {
        for (SensorSpec& sensor : what.robot->sensors) {
          if (sensor.is_camera()) sensor.enabled = false;
        }
      }
      RobotInstance r = place_robot(name, std::move(*what.robot), X_W);
      r.spawned = true;
      r.ns = *ns;
      sim.add_robot(std::move(r));
    }
  } catch (const Error& e) {
    return Result::fail(code::kOperationFailed, std::string("the simulation could not take '") + name + "': " + e.what());
  }
  rebuild_entities();
  entity_name = name;
  return Result::ok();
}

Result RunControl::remove(const std::string& name) {
  const Entity* e = find(name);
  if (!e) return Result::fail(code::kNotFound, "no entity named '" + name + "'");
  Simulation& sim = session_.sim();
  const bool spawned = (e->kind == Entity::Kind::robot && sim.world().robots[e->index].spawned) ||
                       (e->kind == Entity::Kind::rubble && sim.world().dynamics[e->index].spawned);
  if (!spawned) {
    return Result::fail(
        code::kOperationFailed,
        "'" + name + "' comes from the scenario: only spawned entities can be deleted (a reset brings the scenario's back)");
  }
  if (e->kind == Entity::Kind::robot) {
    sim.remove_robot(RobotIndex::at(e->index));
  } else {
    sim.remove_body(e->index);
  }
  rebuild_entities();
  return Result::ok();
}

}  // namespace rescuesim
