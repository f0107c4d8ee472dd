// The Simulation Interfaces over Foxglove services in JSON: the catalogue with its JSON Schemas,
// strict request decoding (every field checked, unknown keys refused, paths in the errors),
// what each call does on the simulation thread, and the response text.
//
// Why `json` with `jsonschema` schemas, and not the ros2msg text of the .srv files: the Service
// Call panel writes the request its user typed with the request's own encoding, and the apps
// read a `json` message only with a JSON Schema (or none): Foxglove's and Lichtblick's
// parseChannel refuse `json` + `ros2msg` ("expected jsonschema or no schema"), and the service
// is then dropped as unparsable. The schemas are kept to the subset their schema reader takes:
// an object with "properties", each property one "type" of boolean, string, number, integer,
// object (with properties) or array (with typed "items"); no $ref, no type lists.

#include "bridges/foxglove/sim_services.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <tuple>
#include <type_traits>

#include "core/error.h"

namespace rescuesim::foxglove {

namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

// ---- JSON Schemas of the requests and responses ----

ojson typed(const char* type, const char* description = nullptr) {
  ojson j = {{"type", type}};
  if (description) j["description"] = description;
  return j;
}
ojson object(ojson properties, const char* description = nullptr) {
  ojson j = {{"type", "object"}, {"properties", std::move(properties)}};
  if (description) j["description"] = description;
  return j;
}
ojson array_of(ojson items, const char* description = nullptr) {
  ojson j = {{"type", "array"}, {"items", std::move(items)}};
  if (description) j["description"] = description;
  return j;
}
ojson vector3() { return object({{"x", typed("number")}, {"y", typed("number")}, {"z", typed("number")}}); }
ojson quaternion() {
  return object({{"x", typed("number")}, {"y", typed("number")}, {"z", typed("number")}, {"w", typed("number")}});
}
ojson pose() { return object({{"position", vector3()}, {"orientation", quaternion()}}); }
ojson twist() { return object({{"linear", vector3()}, {"angular", vector3()}}); }
ojson header() {
  return object({{"stamp", object({{"sec", typed("integer")}, {"nanosec", typed("integer")}})}, {"frame_id", typed("string")}});
}
ojson result() {
  return object({{"result", typed("integer", "1 OK, 0 FEATURE_UNSUPPORTED, 2 NOT_FOUND, 3 INCORRECT_STATE, 4 OPERATION_FAILED, "
                                              ">= 101 the service's own codes")},
                 {"error_message", typed("string")}});
}
ojson simulation_state() {
  return object({{"state", typed("integer", "0 STOPPED, 1 PLAYING, 2 PAUSED, 3 QUITTING, 4 NO_WORLD, 5 LOADING_WORLD")}});
}
ojson entity_state() {
  return object({{"header", header()}, {"pose", pose()}, {"twist", twist()}, {"acceleration", twist()}},
                "in header.frame_id; an empty frame is the world");
}
ojson entity_filters() {
  return object({{"filter", typed("string", "POSIX extended regular expression on entity names; empty: all")},
                 {"categories", array_of(object({{"category", typed("integer", "0 OBJECT, 1 ROBOT, 2 HUMAN, 4 DYNAMIC_OBJECT, "
                                                                                 "5 STATIC_OBJECT")}}))},
                 {"tags", object({{"tags", array_of(typed("string"))}, {"filter_mode", typed("integer", "0 ANY, 1 ALL")}})},
                 {"bounds", object({{"type", typed("integer", "0 EMPTY, 1 BOX, 2 CONVEX_HULL, 3 SPHERE")},
                                    {"points", array_of(vector3())}})}});
}

struct Definition {
  const char* name;
  const char* type;
  ojson request, response;
};

std::vector<Definition> definitions() {
  std::vector<Definition> d;
  d.push_back({"/reset_simulation", "simulation_interfaces/srv/ResetSimulation",
               object({{"scope", typed("integer", "bits: 0 DEFAULT (= ALL), 1 TIME, 2 STATE, 4 SPAWNED, 255 ALL")}}),
               object({{"result", result()}})});
  d.push_back({"/get_simulation_state", "simulation_interfaces/srv/GetSimulationState", object(ojson::object()),
               object({{"state", simulation_state()}, {"result", result()}})});
  d.push_back({"/set_simulation_state", "simulation_interfaces/srv/SetSimulationState", object({{"state", simulation_state()}}),
               object({{"result", result()}})});
  d.push_back({"/step_simulation", "simulation_interfaces/srv/StepSimulation",
               object({{"steps", typed("integer", "steps to run from PAUSED (default 1)")}}), object({{"result", result()}})});
  d.push_back({"/get_entities", "simulation_interfaces/srv/GetEntities", object({{"filters", entity_filters()}}),
               object({{"result", result()}, {"entities", array_of(typed("string"))}})});
  d.push_back({"/get_entity_state", "simulation_interfaces/srv/GetEntityState", object({{"entity", typed("string")}}),
               object({{"result", result()}, {"state", entity_state()}})});
  d.push_back({"/set_entity_state", "simulation_interfaces/srv/SetEntityState",
               object({{"entity", typed("string")},
                       {"state", entity_state()},
                       {"set_pose", typed("boolean")},
                       {"set_twist", typed("boolean")},
                       {"set_acceleration", typed("boolean")}},
                      "without set_* flags, the parts of state given are set"),
               object({{"result", result()}})});
  d.push_back({"/get_simulator_features", "simulation_interfaces/srv/GetSimulatorFeatures", object(ojson::object()),
               object({{"features", object({{"features", array_of(typed("integer"))},
                                            {"spawn_formats", array_of(typed("string"))},
                                            {"custom_info", typed("string")}})}})});
  d.push_back({"/spawn_entity", "simulation_interfaces/srv/SpawnEntity",
               object({{"name", typed("string", "unique; names its topics' namespace unless entity_namespace is given")},
                       {"allow_renaming", typed("boolean")},
                       {"uri", typed("string", "a built-in robot (rescue_robot, tracked_robot) or body (box, brick, cylinder, "
                                               "sphere), or a URDF, SDF or YAML robot file (path, file://, package://, model://)")},
                       {"resource_string", typed("string", "URDF or SDF text, or a robot entry in YAML, when uri is empty")},
                       {"entity_namespace", typed("string")},
                       {"initial_pose", object({{"header", header()}, {"pose", pose()}}, "frame_id: empty, world or map, or an entity")}}),
               object({{"result", result()}, {"entity_name", typed("string")}})});
  d.push_back({"/delete_entity", "simulation_interfaces/srv/DeleteEntity", object({{"entity", typed("string")}}),
               object({{"result", result()}})});
  return d;
}

// ---- decoding ----

/// A JSON value as an error message shows it: compact, at most 40 characters.
std::string shown(const json& v) {
  std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

/// `key` under `path` ("state" + "pose" = "state.pose").
std::string child(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }

/// A JSON object of a request whose keys must be among `fields`.
class Object {
 public:
  Object(const json& j, std::string path, std::initializer_list<const char*> fields) : j_(j), path_(std::move(path)) {
    if (!j.is_object()) throw Error((path_.empty() ? "request" : path_) + ": expected an object, got " + shown(j));
    for (const auto& item : j.items()) {
      bool known = false;
      for (const char* f : fields) known = known || item.key() == f;
      if (known) continue;
      std::string list;
      for (const char* f : fields) list += (list.empty() ? "" : ", ") + std::string(f);
      const std::string key = item.key().size() > 40 ? item.key().substr(0, 37) + "..." : item.key();
      throw Error((path_.empty() ? "request" : path_) + ": unknown field '" + key + "' (" +
                  (list.empty() ? "it has no fields" : "fields: " + list) + ")");
    }
  }
  /// The field, or null when absent.
  const json* find(const char* key) const {
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  std::string path(const char* key) const { return child(path_, key); }

 private:
  const json& j_;
  std::string path_;
};

std::uint64_t unsigned_value(const json& v, const std::string& path, std::uint64_t max, const std::string& what) {
  const std::string expected = "expected an integer 0.." + std::to_string(max) + (what.empty() ? "" : " (" + what + ")");
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u <= max) return u;
  } else if (v.is_number_float()) {
    // 5.0 from a hand-written request; exact integers only
    const double d = v.get<double>();
    if (std::isfinite(d) && d >= 0 && d == std::floor(d) && d <= 9007199254740992.0 && static_cast<std::uint64_t>(d) <= max) {
      return static_cast<std::uint64_t>(d);
    }
  }
  throw Error(path + ": " + expected + ", got " + shown(v));
}

std::uint64_t unsigned_field(const Object& o, const char* key, std::uint64_t max, std::uint64_t fallback, const std::string& what = "") {
  const json* v = o.find(key);
  return v ? unsigned_value(*v, o.path(key), max, what) : fallback;
}

double number_field(const Object& o, const char* key, double fallback) {
  const json* v = o.find(key);
  if (!v) return fallback;
  if (v->is_null()) return std::numeric_limits<double>::quiet_NaN();  // as msg::from_json reads null
  if (!v->is_number()) throw Error(o.path(key) + ": expected a number, got " + shown(*v));
  return v->get<double>();
}

std::string string_value(const json& v, const std::string& path) {
  if (!v.is_string()) throw Error(path + ": expected a string, got " + shown(v));
  return v.get<std::string>();
}

std::string string_field(const Object& o, const char* key, bool required) {
  const json* v = o.find(key);
  if (!v) {
    if (required) throw Error(o.path(key) + ": missing (a string)");
    return {};
  }
  return string_value(*v, o.path(key));
}

std::optional<bool> bool_field(const Object& o, const char* key) {
  const json* v = o.find(key);
  if (!v) return std::nullopt;
  if (!v->is_boolean()) throw Error(o.path(key) + ": expected true or false, got " + shown(*v));
  return v->get<bool>();
}

const json& array_value(const json& v, const std::string& path) {
  if (!v.is_array()) throw Error(path + ": expected an array, got " + shown(v));
  return v;
}

Vec3 vector3_value(const json& v, const std::string& path) {
  const Object o(v, path, {"x", "y", "z"});
  return {number_field(o, "x", 0), number_field(o, "y", 0), number_field(o, "z", 0)};
}

Vec3 vector3_field(const Object& o, const char* key) {
  const json* v = o.find(key);
  return v ? vector3_value(*v, o.path(key)) : Vec3::Zero();
}

/// (linear, angular) of a geometry_msgs/Twist or Accel.
std::pair<Vec3, Vec3> twist_value(const json& v, const std::string& path) {
  const Object o(v, path, {"linear", "angular"});
  return {vector3_field(o, "linear"), vector3_field(o, "angular")};
}

Pose3 pose_value(const json& v, const std::string& path) {
  const Object o(v, path, {"position", "orientation"});
  Pose3 X;
  X.p = vector3_field(o, "position");
  if (const json* q = o.find("orientation")) {
    // a field left out keeps its ROS 2 default: the identity (w = 1); normalising and
    // refusing a non-unit quaternion (INVALID_POSE) is SimControl's to do
    const Object oq(*q, o.path("orientation"), {"x", "y", "z", "w"});
    X.q = Quat(number_field(oq, "w", 1), number_field(oq, "x", 0), number_field(oq, "y", 0), number_field(oq, "z", 0));
  }
  return X;
}

/// std_msgs/Header into an EntityState: stamp {sec, nanosec} (nsec taken too), frame_id.
void header_value(const json& v, const std::string& path, control::EntityState& s) {
  const Object o(v, path, {"stamp", "frame_id"});
  s.frame_id = string_field(o, "frame_id", false);
  if (const json* t = o.find("stamp")) {
    const Object ot(*t, o.path("stamp"), {"sec", "nanosec", "nsec"});
    std::int64_t sec = 0;
    if (const json* js = ot.find("sec")) {
      constexpr std::int64_t lo = std::numeric_limits<std::int32_t>::min(), hi = std::numeric_limits<std::int32_t>::max();
      const bool fits = js->is_number_unsigned()
                            ? js->get<std::uint64_t>() <= static_cast<std::uint64_t>(hi)
                            : js->is_number_integer() && js->get<std::int64_t>() >= lo && js->get<std::int64_t>() <= hi;
      if (!fits) throw Error(ot.path("sec") + ": expected a 32-bit integer, got " + shown(*js));
      sec = js->get<std::int64_t>();
    }
    const bool ros2 = ot.find("nanosec") != nullptr;
    const std::uint64_t ns = unsigned_field(ot, ros2 ? "nanosec" : "nsec", 999'999'999, 0);
    s.stamp_ns = sec * 1'000'000'000 + static_cast<std::int64_t>(ns);
  }
}

/// Which parts of an EntityState a request gave.
struct StateParts {
  bool pose = false, twist = false, acceleration = false;
};

StateParts entity_state_value(const json& v, const std::string& path, control::EntityState& s) {
  const Object o(v, path, {"header", "pose", "twist", "acceleration"});
  StateParts given;
  if (const json* h = o.find("header")) header_value(*h, o.path("header"), s);
  if (const json* p = o.find("pose")) {
    s.pose = pose_value(*p, o.path("pose"));
    given.pose = true;
  }
  if (const json* t = o.find("twist")) {
    std::tie(s.linear, s.angular) = twist_value(*t, o.path("twist"));
    given.twist = true;
  }
  if (const json* a = o.find("acceleration")) {
    std::tie(s.linear_acc, s.angular_acc) = twist_value(*a, o.path("acceleration"));
    given.acceleration = true;
  }
  return given;
}

control::EntityFilters filters_value(const json& v, const std::string& path) {
  const Object o(v, path, {"filter", "categories", "tags", "bounds"});
  control::EntityFilters f;
  f.filter = string_field(o, "filter", false);
  if (const json* cats = o.find("categories")) {
    const json& a = array_value(*cats, o.path("categories"));
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Object c(a[i], o.path("categories") + "[" + std::to_string(i) + "]", {"category"});
      f.categories.push_back(static_cast<std::uint8_t>(unsigned_field(c, "category", 255, 0, "an EntityCategory")));
    }
  }
  if (const json* tags = o.find("tags")) {
    const Object t(*tags, o.path("tags"), {"tags", "filter_mode"});
    if (const json* list = t.find("tags")) {
      const json& a = array_value(*list, t.path("tags"));
      for (std::size_t i = 0; i < a.size(); ++i) f.tags.tags.push_back(string_value(a[i], t.path("tags") + "[" + std::to_string(i) + "]"));
    }
    f.tags.filter_mode = static_cast<std::uint8_t>(unsigned_field(t, "filter_mode", 1, 0, "0 ANY, 1 ALL"));
  }
  if (const json* bounds = o.find("bounds")) {
    const Object b(*bounds, o.path("bounds"), {"type", "points"});
    f.bounds.type =
        static_cast<std::uint8_t>(unsigned_field(b, "type", 3, control::Bounds::kEmpty, "0 EMPTY, 1 BOX, 2 CONVEX_HULL, 3 SPHERE"));
    if (const json* points = b.find("points")) {
      const json& a = array_value(*points, b.path("points"));
      for (std::size_t i = 0; i < a.size(); ++i) {
        f.bounds.points.push_back(vector3_value(a[i], b.path("points") + "[" + std::to_string(i) + "]"));
      }
    }
  }
  return f;
}

SimRequest decode(SimService s, const json& j) {
  switch (s) {
    case SimService::reset_simulation: {
      const Object o(j, "", {"scope"});
      return ResetRequest{static_cast<std::uint8_t>(unsigned_field(o, "scope", 255, control::scope::kDefault, "a bit field"))};
    }
    case SimService::get_simulation_state:
      Object(j, "", {});  // {} only
      return GetSimulationStateRequest{};
    case SimService::set_simulation_state: {
      const Object o(j, "", {"state"});
      const json* state = o.find("state");
      if (!state) throw Error("state: missing (a SimulationState: {\"state\": 2} pauses)");
      if (!state->is_object()) {
        throw Error("state: expected an object {\"state\": N} (a SimulationState), got " + shown(*state));
      }
      const Object os(*state, "state", {"state"});
      if (!os.find("state")) throw Error("state.state: missing (0 STOPPED, 1 PLAYING, 2 PAUSED, 3 QUITTING)");
      const auto v =
          unsigned_field(os, "state", 5, 0, "a SimulationState: 0 STOPPED, 1 PLAYING, 2 PAUSED, 3 QUITTING, 4 NO_WORLD, 5 LOADING_WORLD");
      return SetSimulationStateRequest{static_cast<control::RunState>(v)};
    }
    case SimService::step_simulation: {
      const Object o(j, "", {"steps"});
      return StepRequest{unsigned_field(o, "steps", std::numeric_limits<std::uint64_t>::max(), 1)};
    }
    case SimService::get_entities: {
      const Object o(j, "", {"filters"});
      const json* f = o.find("filters");
      return GetEntitiesRequest{f ? filters_value(*f, "filters") : control::EntityFilters{}};
    }
    case SimService::get_entity_state: {
      const Object o(j, "", {"entity"});
      return GetEntityStateRequest{string_field(o, "entity", true)};
    }
    case SimService::set_entity_state: {
      const Object o(j, "", {"entity", "state", "set_pose", "set_twist", "set_acceleration"});
      SetEntityStateRequest r;
      r.entity = string_field(o, "entity", true);
      const json* state = o.find("state");
      if (!state) throw Error("state: missing (an EntityState with pose, twist or acceleration)");
      const StateParts given = entity_state_value(*state, "state", r.state);
      const auto set_pose = bool_field(o, "set_pose"), set_twist = bool_field(o, "set_twist");
      const auto set_acceleration = bool_field(o, "set_acceleration");
      if (set_pose || set_twist || set_acceleration) {
        r.set_pose = set_pose.value_or(false);
        r.set_twist = set_twist.value_or(false);
        r.set_acceleration = set_acceleration.value_or(false);
      } else {
        r.set_pose = given.pose;
        r.set_twist = given.twist;
        r.set_acceleration = given.acceleration;
      }
      if (!r.set_pose && !r.set_twist && !r.set_acceleration) {
        throw Error("nothing to set: give state.pose, state.twist or state.acceleration (or set_pose, set_twist, set_acceleration)");
      }
      return r;
    }
    case SimService::get_simulator_features:
      Object(j, "", {});
      return GetSimulatorFeaturesRequest{};
    case SimService::spawn_entity: {
      const Object o(j, "", {"name", "allow_renaming", "uri", "resource_string", "resource", "entity_namespace", "initial_pose"});
      SpawnEntityRequest r;
      r.spawn.name = string_field(o, "name", false);
      r.spawn.allow_renaming = bool_field(o, "allow_renaming").value_or(false);
      r.spawn.uri = string_field(o, "uri", false);
      r.spawn.resource_string = string_field(o, "resource_string", false);
      if (const json* res = o.find("resource")) {
        const Object ores(*res, "resource", {"uri", "resource_string"});
        r.spawn.uri = string_field(ores, "uri", false);
        r.spawn.resource_string = string_field(ores, "resource_string", false);
      }
      r.spawn.entity_namespace = string_field(o, "entity_namespace", false);
      if (const json* ip = o.find("initial_pose")) {
        const Object op(*ip, "initial_pose", {"header", "pose"});
        if (const json* h = op.find("header")) {
          control::EntityState hs;
          header_value(*h, op.path("header"), hs);
          r.spawn.frame_id = hs.frame_id;
        }
        if (const json* p = op.find("pose")) r.spawn.pose = pose_value(*p, op.path("pose"));
      }
      return r;
    }
    case SimService::delete_entity: {
      const Object o(j, "", {"entity"});
      return DeleteEntityRequest{string_field(o, "entity", true)};
    }
  }
  throw Error("unknown service");
}

// ---- encoding ----

ojson result_json(const control::Result& r) { return {{"result", r.result}, {"error_message", r.error_message}}; }
ojson vector3_json(const Vec3& v) { return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; }

ojson entity_state_json(const control::EntityState& s) {
  // sim time ns -> builtin_interfaces/Time {sec, nanosec}, nanosec in [0, 1e9)
  std::int64_t sec = s.stamp_ns / 1'000'000'000;
  std::int64_t nanosec = s.stamp_ns % 1'000'000'000;
  if (nanosec < 0) {
    nanosec += 1'000'000'000;
    --sec;
  }
  const Quat& q = s.pose.q;
  return {{"header", {{"stamp", {{"sec", sec}, {"nanosec", nanosec}}}, {"frame_id", s.frame_id}}},
          {"pose", {{"position", vector3_json(s.pose.p)}, {"orientation", {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}}}}},
          {"twist", {{"linear", vector3_json(s.linear)}, {"angular", vector3_json(s.angular)}}},
          {"acceleration", {{"linear", vector3_json(s.linear_acc)}, {"angular", vector3_json(s.angular_acc)}}}};
}

}  // namespace

const std::vector<Service>& sim_services() {
  static const std::vector<Service> services = [] {
    std::vector<Service> all;
    std::uint32_t id = 1;
    for (const Definition& d : definitions()) {
      Service s;
      s.id = id++;
      s.name = d.name;
      s.type = d.type;
      s.request = {"json", s.type + "_Request", "jsonschema", d.request.dump()};
      s.response = {"json", s.type + "_Response", "jsonschema", d.response.dump()};
      all.push_back(std::move(s));
    }
    return all;
  }();
  return services;
}

std::optional<SimService> sim_service_of(std::uint32_t id) {
  if (id < 1 || id > kSimServiceCount) return std::nullopt;
  return static_cast<SimService>(id - 1);
}

const std::string& sim_service_name(SimService s) { return sim_services()[static_cast<std::size_t>(s)].name; }

SimRequest decode_sim_request(SimService s, std::span<const std::uint8_t> payload) {
  const std::string& name = sim_service_name(s);
  json j = json::object();
  if (!payload.empty()) {
    j = json::parse(payload.begin(), payload.end(), nullptr, false);
    if (j.is_discarded()) throw Error(name + ": the request is not valid JSON (" + std::to_string(payload.size()) + " bytes)");
  }
  try {
    return decode(s, j);
  } catch (const Error& e) {
    throw Error(name + ": " + e.message());
  }
}

std::string encode_sim_response(const SimResponse& r) {
  ojson j;
  switch (r.service) {
    case SimService::get_simulation_state:
      j["state"] = {{"state", static_cast<int>(r.state)}};
      j["result"] = result_json(r.result);
      break;
    case SimService::get_entities:
      j["result"] = result_json(r.result);
      j["entities"] = r.entities;
      break;
    case SimService::get_entity_state:
      j["result"] = result_json(r.result);
      j["state"] = entity_state_json(r.entity_state);
      break;
    case SimService::spawn_entity:
      j["result"] = result_json(r.result);
      j["entity_name"] = r.entity_name;
      break;
    case SimService::get_simulator_features:
      // GetSimulatorFeatures has no Result: only the features
      j["features"] = {
          {"features", r.features.features}, {"spawn_formats", r.features.spawn_formats}, {"custom_info", r.features.custom_info}};
      break;
    default:
      j["result"] = result_json(r.result);
      break;
  }
  // names and messages may echo a client's bytes: invalid UTF-8 is replaced, never thrown on
  return j.dump(-1, ' ', false, ojson::error_handler_t::replace);
}

void run_sim_request(const SimRequest& request, control::SimControl& c, std::function<void(SimResponse)> reply) {
  SimResponse r;
  r.service = static_cast<SimService>(request.index());
  std::visit(
      [&](const auto& q) {
        using T = std::decay_t<decltype(q)>;
        if constexpr (std::is_same_v<T, ResetRequest>) {
          r.result = c.reset(q.scope);
        } else if constexpr (std::is_same_v<T, GetSimulationStateRequest>) {
          r.state = c.run_state();
          r.result = control::Result::ok();
        } else if constexpr (std::is_same_v<T, SetSimulationStateRequest>) {
          r.result = c.set_run_state(q.state);
        } else if constexpr (std::is_same_v<T, StepRequest>) {
          // accepted: answered when the steps have run; refused: answered now with the reason
          control::StepJob job;
          job.steps = q.steps;
          job.done = [reply, r](const control::Result& result, std::uint64_t) mutable {
            r.result = result;
            reply(std::move(r));
          };
          r.result = c.start_steps(std::move(job), /*action=*/false);
          if (r.result.is_ok()) return;
        } else if constexpr (std::is_same_v<T, GetEntitiesRequest>) {
          r.result = c.entities(q.filters, r.entities);
        } else if constexpr (std::is_same_v<T, GetEntityStateRequest>) {
          r.result = c.entity_state(q.entity, r.entity_state);
        } else if constexpr (std::is_same_v<T, SetEntityStateRequest>) {
          r.result = c.set_entity_state(q.entity, q.state, q.set_pose, q.set_twist, q.set_acceleration);
        } else if constexpr (std::is_same_v<T, SpawnEntityRequest>) {
          r.result = c.spawn(q.spawn, r.entity_name);
        } else if constexpr (std::is_same_v<T, DeleteEntityRequest>) {
          r.result = c.remove(q.entity);
        } else {
          r.features = c.features();
        }
        reply(std::move(r));
      },
      request);
}

}  // namespace rescuesim::foxglove
