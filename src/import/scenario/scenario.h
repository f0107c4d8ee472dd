#pragma once
/// A scenario: which world (an SVG drawing or a generated maze), which robots with which
/// sensors and controllers, the physics step, the run's seed, length and pace, and the
/// mission. Read from YAML (worlds/default.yaml is the built-in default); every key is
/// checked, and errors name the file, line and key path.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "import/maze/maze.h"
#include "import/sdf/sdf_import.h"
#include "import/svg/svg_world.h"
#include "world/mission_spec.h"
#include "world/robot_spec.h"
#include "world/world.h"
#include "world/world_spec.h"

namespace rescuesim {

/// One robot of a scenario.
struct RobotConfig {
  std::string name;                 ///< unique; topics are namespaced by it when there are several robots
  std::string model = "rescue_robot";
  std::optional<Pose2> start;       ///< overrides the world's start of the same index
  std::string controller = "explorer";  ///< explorer, wall_follower, none (driven from outside, e.g. ROS)
  RobotSpec spec;                   ///< the model with this scenario's sensor and head settings applied
  std::string urdf;                 ///< the URDF file it came from (resolved), "" for built-in models
  std::string sdf;                  ///< the SDF file it came from (resolved), "" otherwise
  Diagnostics diagnostics;          ///< warnings from importing its description
};

/// A scenario as authored.
struct Scenario {
  std::string name = "default";     ///< names the output folder runs/<name>
  std::string source_file;          ///< the YAML it came from ("<built-in>" for the default)
  std::uint64_t seed = 1;           ///< run seed: maze, noise streams
  double duration = 180.0;          ///< s of sim time
  bool realtime = false;            ///< paced to the wall clock (else lockstep, as fast as possible)
  double rate = 1.0;                ///< realtime pace: sim seconds per wall second
  double physics_dt = 0.005;        ///< s
  bool physics_dt_given = false;    ///< physics.dt was in the file (else an SDF world's step may set it)
  int solver_iterations = 10;
  int physics_groups = 0;           ///< independent Bullet worlds (PhysicsOptions::groups); 0 = automatic
  bool stop_when_all_found = false; ///< end the run once every victim has been seen
  std::string render_quality = "low";  ///< camera images: low, medium or high (see docs/rendering.md)
  double render_latency = -1;       ///< s from a camera's sample to its delivery; < 0: one camera period

  /// The world comes from exactly one of these.
  std::optional<std::filesystem::path> svg;  ///< resolved against the scenario file's folder
  std::optional<MazeOptions> maze;
  std::optional<std::filesystem::path> sdf;  ///< an SDF world, resolved like svg
  /// Models placed into the world (world.include), and an SDF world's own content: read when the
  /// scenario is parsed (so that `check` reports their errors), added to the world by build_world.
  std::vector<SdfInclude> includes;
  std::shared_ptr<const SdfWorld> models;    ///< null when the scenario has neither sdf nor include
  /// Smoke and dust added to the world (world.media; docs/environment.md), whatever its source.
  std::vector<MediumSpec> media;
  /// Daylight (world.ambient_light, world.sun; docs/environment.md): unset keeps the world's own.
  std::optional<double> ambient_light;
  std::optional<bool> sun;
  /// Floor patches of other materials added to the world (world.ground; docs/terrain.md), whatever its source.
  std::vector<GroundAreaSpec> ground;
  SvgLoadOptions svg_options;       ///< scale and per-kind defaults for SVG worlds

  /// Folders where package:// URIs are looked for first (relative entries are taken from the
  /// scenario file's folder), before ROS_PACKAGE_PATH and AMENT_PREFIX_PATH.
  std::vector<std::filesystem::path> resource_paths;

  /// Robots; empty means one robot per start in the world, with default settings.
  std::vector<RobotConfig> robots;

  /// The rescue mission (`mission:`): referee rules, radio model, base stations. None: a
  /// plain run, without referee or radio (docs/missions.md).
  std::optional<MissionSpec> mission;
};

/// The robot models a scenario may name, by model name.
using ModelMap = std::map<std::string, RobotSpec>;

/// Parses scenario YAML; `file` names it in messages and resolves relative paths; `models`
/// are the robot models it may use. Throws Error naming the key path for unknown keys, wrong
/// types and impossible values (fov 0, negative range, rate 0, ...).
Scenario parse_scenario(const std::string& yaml_text, const std::string& file, const ModelMap& models);

/// Reads the scenario's SDF world and includes (with its resource_paths) into `s.models`, or
/// clears it when there are none; takes the SDF's physics step unless physics_dt_given. Called
/// by parse_scenario, and again by whoever changes the world or the includes afterwards.
void load_scenario_models(Scenario& s);

/// One robot as an entry of a scenario's `robots:` describes it (model:, urdf: or sdf:, with
/// name, drive, sensors, head, lamps), from YAML text of its own: what SpawnEntity takes as a
/// rescuesim robot. `file` names the text in messages, and relative URIs resolve against its
/// folder; `resource_paths` are searched first, as a scenario's. Throws Error naming the key.
RobotConfig read_robot_yaml(const std::string& yaml_text, const std::string& file, const ModelMap& models,
                            const std::vector<std::filesystem::path>& resource_paths = {});

/// Reads a scenario file.
Scenario load_scenario(const std::filesystem::path& file, const ModelMap& models);

/// The built-in default scenario (worlds/default.yaml, compiled in).
Scenario default_scenario(const ModelMap& models);
/// The YAML text of the built-in default scenario.
std::string default_scenario_text();

/// Builds the scenario's world: loads the SVG or generates the maze (seeded from the scenario
/// seed unless the maze sets its own), places the scenario's robots, and adds diagnostics from
/// the import.
WorldSpec build_world(const Scenario& scenario, Diagnostics* diagnostics = nullptr);

/// Compiles a built world with the scenario's robots (their sensor settings applied).
World compile_scenario(const Scenario& scenario, const WorldSpec& spec, const ModelMap& models);

/// The robot configurations in force: the scenario's, or defaults for each start of `spec`.
std::vector<RobotConfig> robot_configs(const Scenario& scenario, const WorldSpec& spec, const ModelMap& models);

}  // namespace rescuesim
