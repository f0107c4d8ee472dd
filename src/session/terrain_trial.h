#pragma once
/// A test-method trial (docs/terrain.md, "Trials"): a robot driven across one lane of a
/// test-method arena by a simple scripted driver, and what happened counted as the standards
/// count it: repetitions completed, time per repetition, falls (rollovers) and stuck events.
/// Two patterns: `laps`, each lap from the lane's start line with a small seeded offset, and
/// `back-and-forth`, end-to-end repetitions without a reset (forward to the end line, reversing
/// back to the start line, each crossing one repetition) until the first failure; and
/// `figure-eight`, loops around two pylons on the element (stepfields and crossing ramps, the
/// test methods' figure-8 terrains) without a reset, each figure-eight one repetition. Runs
/// `rescuesim trial-terrain` and the batch's terrain trials.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "viz/canvas.h"
#include "world/robot_spec.h"
#include "world/world_spec.h"

namespace rescuesim {

/// How repetitions are driven.
enum class TerrainPattern {
  laps,            ///< every lap from the start line, forward to the end line; a failure costs one lap
  back_and_forth,  ///< no reset: forward to the end line, back (reversing) to the start line, ...; a failure ends the trial
  figure_eight,    ///< no reset: figure-eights around two pylons on the element; a failure ends the trial
};

/// The pattern's name in files and options ("laps", "back-and-forth", "figure-eight").
const char* terrain_pattern_name(TerrainPattern p);
/// The pattern by name; throws Error listing the names for anything else.
TerrainPattern parse_terrain_pattern(const std::string& name);
/// What one repetition is called, plural, for progress lines ("laps", "crossings back and
/// forth", "figure-eights").
const char* terrain_pattern_reps(TerrainPattern p);
/// The lane's element in `world`: by name, else the first of a kind by that name; nullptr when none.
const TerrainSpec* find_terrain_lane(const WorldSpec& world, const std::string& lane);
/// Throws Error (exit 2) when `p` cannot be driven on `lane`: figure-eights only on stepfields
/// and crossing ramps.
void check_terrain_pattern(const TerrainSpec& lane, TerrainPattern p);

struct TerrainTrialOptions {
  std::string lane;               ///< a terrain element's name, or a kind ("stairs": the first of that kind)
  std::string robot = "tracked_robot";  ///< a built-in model
  TerrainPattern pattern = TerrainPattern::laps;
  int laps = 10;                  ///< laps: attempts, each from the start line; back-and-forth: crossings; figure-eight: figure-eights
  std::uint64_t seed = 1;         ///< the laps' start offsets
  double speed = 0.3;             ///< m/s along the lane
  double approach = 0.8;          ///< m of floor between the element and the start and end lines
  double time_limit = 60;         ///< s a lap may take
  double stuck_time = 10;         ///< s without 5 cm of progress: stuck
  double fall_pitch = 75;         ///< degrees of pitch beyond which the robot has fallen over
  double fall_roll = 60;          ///< degrees of roll, likewise
  double start_offset = 0.05;     ///< m: laps start up to this far off the lane's centre line
  double start_yaw = 3;           ///< degrees: and turned up to this much
};

/// One lap.
struct TerrainLap {
  int lap = 0;
  bool reverse = false;           ///< back-and-forth: driven backwards, from the end line to the start line
  std::string outcome;            ///< "completed", "fell", "stuck" or "timeout"
  double time = 0;                ///< s from the lap's start to its goal line (or to the event)
  double progress = 0;            ///< m along the lane in the lap's direction from where it began, at most
                                  ///< (figure-eight: m along the figure-eight's path)
  double max_pitch = 0, max_roll = 0;  ///< degrees, largest magnitudes
  double max_height = 0;          ///< m, highest base above the floor
  std::vector<Vec2> path;         ///< the base's track in the world, every 0.1 s
};

struct TerrainTrialResult {
  TerrainSpec element;            ///< the lane's element
  std::string robot;
  TerrainTrialOptions options;
  std::vector<TerrainLap> laps;
  int repetitions = 0, falls = 0, stuck = 0, timeouts = 0;
  double mean_time = 0;           ///< s per completed repetition (0: none)
  double sim_time = 0;            ///< s simulated, all laps
  std::uint64_t state_hash = 0;   ///< the final State hash of each simulation of the trial (one per lap, or one), combined
  std::vector<Vec2> pylons;       ///< figure-eight: the two pylons (world, m)
  double loop_radius = 0;         ///< figure-eight: the loops' radius around each pylon (m)
  double eight_length = 0;        ///< figure-eight: one figure-eight's path (m)
};

/// Runs the trial on `world` (its robots are replaced by the trial's). Throws Error (exit 2) for
/// an unknown lane or robot, or a figure-eight on an element that is not a figure-8 terrain. `progress` hears each lap as it ends.
TerrainTrialResult run_terrain_trial(const WorldSpec& world, const std::map<std::string, RobotSpec>& models,
                                     const TerrainTrialOptions& options,
                                     const std::function<void(const TerrainLap&)>& progress = nullptr);

/// The result as JSON (summary and every lap, paths left out).
std::string terrain_trial_json(const TerrainTrialResult& result);

/// The lane from above with each lap's path, green completed, red fell, orange stuck or out of
/// time, and the counts in the title.
Canvas terrain_trial_figure(const WorldSpec& world, const TerrainTrialResult& result);

}  // namespace rescuesim
