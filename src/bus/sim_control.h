#pragma once
/// SimControl: the control surface of a running simulation, the operations of the ROS 2
/// Simulation Interfaces standard (ros-simulation/simulation_interfaces) as plain C++: reset,
/// pause and play, stepping, entities (list, state, teleport, info, bounds), named poses,
/// spawnables and worlds, and the run's parameters. One implementation (session/run_control.h)
/// serves every front end: ROS 2 services and actions, ROS 1 services, Foxglove services and
/// the Python API. The types mirror the standard's messages field for field (same constants),
/// so a front end only translates bytes; docs/ros.md "Controlling a run" lists them.
///
/// Threads: every SimControl method runs on the simulation thread, between two steps. A front
/// end on another thread hands a closure to post(), which runs it there at the next step
/// boundary (or at once when the run is paused and waiting); the closure calls the methods and
/// sends its reply itself. Nothing here blocks the simulation on a client.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/pose.h"

namespace rescuesim::control {

/// simulation_interfaces/msg/Result codes shared by every service; service-specific ones are >= 101.
namespace code {
inline constexpr std::uint8_t kFeatureUnsupported = 0, kOk = 1, kNotFound = 2, kIncorrectState = 3, kOperationFailed = 4;
// SpawnEntity
inline constexpr std::uint8_t kNameNotUnique = 101, kNameInvalid = 102, kUnsupportedFormat = 103, kNoResource = 104,
                              kNamespaceInvalid = 105, kResourceParseError = 106, kMissingAssets = 107,
                              kUnsupportedAssets = 108, kSpawnInvalidPose = 109;
// SetEntityState
inline constexpr std::uint8_t kInvalidPose = 101;
// SetSimulationState
inline constexpr std::uint8_t kAlreadyInTargetState = 101, kStateTransitionError = 102, kIncorrectTransition = 103;
// GetAvailableWorlds / LoadWorld / UnloadWorld / GetCurrentWorld
inline constexpr std::uint8_t kDefaultSourcesFailed = 101, kNoWorldLoaded = 101;
}  // namespace code

/// simulation_interfaces/msg/Result: a code and, unless OK, why.
struct Result {
  std::uint8_t result = code::kOk;
  std::string error_message;

  static Result ok() { return {}; }
  static Result fail(std::uint8_t c, std::string why) { return {c, std::move(why)}; }
  bool is_ok() const { return result == code::kOk; }
};

/// simulation_interfaces/msg/SimulatorFeatures constants.
namespace feature {
inline constexpr std::uint16_t kSpawning = 0, kDeleting = 1, kNamedPoses = 2, kPoseBounds = 3, kEntityTags = 4,
                               kEntityBounds = 5, kEntityBoundsBox = 6, kEntityBoundsConvex = 7, kEntityCategories = 8,
                               kSpawningResourceString = 9, kEntityStateGetting = 10, kEntityStateSetting = 11,
                               kEntityInfoGetting = 12, kEntityInfoSetting = 13, kSpawnables = 14;
inline constexpr std::uint16_t kSimulationReset = 20, kSimulationResetTime = 21, kSimulationResetState = 22,
                               kSimulationResetSpawned = 23, kSimulationStateGetting = 24, kSimulationStateSetting = 25,
                               kSimulationStatePause = 26;
inline constexpr std::uint16_t kStepSimulationSingle = 31, kStepSimulationMultiple = 32, kStepSimulationAction = 33;
inline constexpr std::uint16_t kWorldLoading = 40, kWorldResourceString = 41, kWorldTags = 42, kWorldUnloading = 43,
                               kWorldInfoGetting = 44, kAvailableWorlds = 45;
inline constexpr std::uint16_t kSpawningEntities = 50;
}  // namespace feature

struct SimulatorFeatures {
  std::vector<std::uint16_t> features;
  std::vector<std::string> spawn_formats;
  std::string custom_info;
};

/// simulation_interfaces/msg/SimulationState.
enum class RunState : std::uint8_t { stopped = 0, playing = 1, paused = 2, quitting = 3, no_world = 4, loading_world = 5 };

/// ResetSimulation scope bits.
namespace scope {
inline constexpr std::uint8_t kDefault = 0, kTime = 1, kState = 2, kSpawned = 4, kAll = 255;
}

/// simulation_interfaces/msg/EntityCategory.
namespace category {
inline constexpr std::uint8_t kObject = 0, kRobot = 1, kHuman = 2, kDynamicObject = 4, kStaticObject = 5;
}

/// simulation_interfaces/msg/TagsFilter.
struct TagsFilter {
  std::vector<std::string> tags;
  std::uint8_t filter_mode = 0;  ///< 0 ANY, 1 ALL
};

/// simulation_interfaces/msg/Bounds.
struct Bounds {
  static constexpr std::uint8_t kEmpty = 0, kBox = 1, kConvexHull = 2, kSphere = 3;
  std::uint8_t type = kEmpty;
  std::vector<Vec3> points;  ///< box: two corners; sphere: centre, then (radius, 0, 0)
};

/// simulation_interfaces/msg/EntityFilters.
struct EntityFilters {
  std::string filter;                   ///< POSIX extended regular expression on names; empty: all
  std::vector<std::uint8_t> categories;  ///< empty: all
  TagsFilter tags;
  Bounds bounds;                        ///< EMPTY: everywhere
};

/// simulation_interfaces/msg/EntityState: pose, twist and acceleration, in `frame_id` (empty: the world).
struct EntityState {
  std::int64_t stamp_ns = 0;  ///< header stamp (sim time)
  std::string frame_id;
  Pose3 pose;
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();          ///< m/s, rad/s
  Vec3 linear_acc = Vec3::Zero(), angular_acc = Vec3::Zero();  ///< m/s^2, rad/s^2
};

/// simulation_interfaces/msg/EntityInfo.
struct EntityInfo {
  std::uint8_t category = category::kObject;
  std::string description;
  std::vector<std::string> tags;
};

/// simulation_interfaces/msg/NamedPose.
struct NamedPose {
  std::string name, description;
  std::vector<std::string> tags;
  Pose3 pose;
};

/// simulation_interfaces/msg/Spawnable.
struct Spawnable {
  std::string uri, resource_string;  ///< 2.x carries a Resource; 1.x only the uri
  std::string description;
  Bounds spawn_bounds;
};

/// simulation_interfaces/msg/WorldResource.
struct WorldResource {
  std::string name, uri, resource_string, description;
  std::vector<std::string> tags;
};

/// simulation_interfaces/srv/SpawnEntity's request.
struct SpawnRequest {
  std::string name;
  bool allow_renaming = false;
  std::string uri, resource_string;
  std::string entity_namespace;
  std::string frame_id;  ///< of initial_pose; empty: the world
  Pose3 pose;
};

/// A run parameter (rcl_interfaces ParameterValue kinds used here: bool, integer, double, string).
struct ParameterValue {
  static constexpr std::uint8_t kNotSet = 0, kBool = 1, kInteger = 2, kDouble = 3, kString = 4, kByteArray = 5,
                                kBoolArray = 6, kIntegerArray = 7, kDoubleArray = 8, kStringArray = 9;
  std::uint8_t type = kNotSet;
  bool bool_value = false;
  std::int64_t integer_value = 0;
  double double_value = 0;
  std::string string_value;
  std::vector<std::uint8_t> byte_array_value;
  std::vector<bool> bool_array_value;
  std::vector<std::int64_t> integer_array_value;
  std::vector<double> double_array_value;
  std::vector<std::string> string_array_value;
};

struct Parameter {
  std::string name;
  ParameterValue value;
};

/// rcl_interfaces/msg/ParameterDescriptor, as far as a run has them.
struct ParameterDescriptor {
  std::string name;
  std::uint8_t type = ParameterValue::kNotSet;
  std::string description;
  bool read_only = false;
  std::optional<std::pair<double, double>> range;  ///< a double or integer parameter's inclusive range
};

/// rcl_interfaces/msg/SetParametersResult.
struct SetParameterResult {
  bool successful = false;
  std::string reason;
};

/// A stepping job (StepSimulation, the SimulateSteps action): `steps` steps from PAUSED, with a
/// report after each `feedback_every` steps and one at the end; cancel() ends it early.
struct StepJob {
  std::uint64_t steps = 1;
  std::uint64_t feedback_every = 0;  ///< 0: no feedback
  /// (completed, remaining) on the simulation thread.
  std::function<void(std::uint64_t, std::uint64_t)> feedback;
  /// At the end: OK when every step ran; OPERATION_FAILED when cancelled, the run stopped, or a
  /// reset or state change ended it (the message says which). `completed` steps ran.
  std::function<void(const Result&, std::uint64_t completed)> done;
};

class SimControl {
 public:
  virtual ~SimControl() = default;

  /// Runs `task` on the simulation thread at the next step boundary (also while paused).
  /// Returns false, without running it, when the run has ended or kMaxPosted tasks wait already.
  virtual bool post(std::function<void(SimControl&)> task) = 0;
  static constexpr std::size_t kMaxPosted = 1024;

  // ---- everything below: on the simulation thread only (inside a posted task) ----

  /// What this run supports (GetSimulatorFeatures): exactly the operations below that work.
  virtual SimulatorFeatures features() const = 0;

  virtual RunState run_state() const = 0;
  /// SetSimulationState: PLAYING, PAUSED, STOPPED (stopped = paused at the start: a reset),
  /// QUITTING (ends the run). ALREADY_IN_TARGET_STATE, INCORRECT_TRANSITION as the standard says.
  virtual Result set_run_state(RunState target) = 0;
  /// StepSimulation / SimulateSteps: only while PAUSED (else INCORRECT_STATE for the action,
  /// OPERATION_FAILED for the service, as the standard says; `action` picks). On success the
  /// job's done() is called when its steps have run; on refusal it is not, and the Result says why.
  virtual Result start_steps(StepJob job, bool action) = 0;
  /// Ends the stepping job in progress (its done() reports OPERATION_FAILED, "cancelled").
  /// False when there is none.
  virtual bool cancel_steps() = 0;
  /// ResetSimulation with a scope of bits (scope::*).
  virtual Result reset(std::uint8_t scope) = 0;

  /// Names of the entities that pass `filters` (GetEntities), in a stable order.
  virtual Result entities(const EntityFilters& filters, std::vector<std::string>& names) const = 0;
  virtual Result entity_state(const std::string& name, EntityState& out) const = 0;
  /// Teleports an entity (SetEntityState); `set_pose`/`set_twist` as the 2.x flags (1.x: both).
  virtual Result set_entity_state(const std::string& name, const EntityState& state, bool set_pose, bool set_twist,
                                  bool set_acceleration) = 0;
  virtual Result entity_info(const std::string& name, EntityInfo& out) const = 0;
  virtual Result entity_bounds(const std::string& name, Bounds& out) const = 0;
  virtual Result named_poses(const TagsFilter& tags, std::vector<NamedPose>& out) const = 0;
  virtual Result named_pose_bounds(const std::string& name, Bounds& out) const = 0;
  virtual Result spawnables(const std::vector<std::string>& sources, std::vector<Spawnable>& out) const = 0;
  /// SpawnEntity: `entity_name` is the name given (renamed when allowed).
  virtual Result spawn(const SpawnRequest& request, std::string& entity_name) = 0;
  virtual Result remove(const std::string& name) = 0;

  virtual Result available_worlds(const std::vector<std::string>& sources, std::vector<WorldResource>& out) const = 0;
  virtual Result current_world(WorldResource& out) const = 0;
  virtual Result load_world(const WorldResource& world, WorldResource& loaded) = 0;
  virtual Result unload_world() = 0;

  /// The run's parameters (node /rescuesim), in name order.
  virtual std::vector<ParameterDescriptor> parameter_descriptors() const = 0;
  /// A parameter's value; type kNotSet when there is no such parameter.
  virtual ParameterValue parameter(const std::string& name) const = 0;
  virtual SetParameterResult set_parameter(const Parameter& p) = 0;

  /// The run's state hash now (world/state.h), for clients that check determinism.
  virtual std::uint64_t state_hash() const = 0;
  /// Simulation time now (ns) and steps taken.
  virtual std::int64_t time_ns() const = 0;
  virtual std::int64_t steps_taken() const = 0;
};

/// The sentence a front end puts in a refusal when a run offers no control (a replay).
inline constexpr const char* kNoControl = "this run cannot be controlled (a replay has no simulation to drive)";

}  // namespace rescuesim::control
