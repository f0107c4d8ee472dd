#include "bench/bench_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/bench_figures.h"
#include "import/scenario/scenario.h"
#include "radio/radio_network.h"
#include "raycast/ray_scene.h"
#include "robots/rescue_robot.h"

namespace rescuesim::bench {

using json = nlohmann::ordered_json;

json bench_mission(const std::filesystem::path& scenario_file, double sim_seconds, const RunChild& run_child) {
  if (!std::filesystem::exists(scenario_file)) {
    return {{"skipped", scenario_file.string() + " not found (run the bench from the source folder, or give --mission-scenario)"}};
  }
  const ModelMap models = builtin_models();
  Scenario with = load_scenario(scenario_file, models);
  if (!with.mission) return {{"skipped", scenario_file.string() + " has no mission: block"}};
  with.duration = sim_seconds;
  with.stop_when_all_found = false;
  Scenario without = with;
  without.mission.reset();
  json j;
  j["scenario"] = scenario_file.string();
  j["robots"] = with.robots.size();
  j["radio_model"] = std::string(radio_model_name(with.mission->radio.model.kind));
  j["link_rate_hz"] = with.mission->radio.link_rate_hz;

  // the whole run, alternating, median of 3: the mission's cost is what it takes off the RTF
  std::fprintf(stderr, "bench: mission scenario with and without its mission, %.0f s each, 3 times ...\n", sim_seconds);
  std::vector<double> rtf_with, rtf_without, cpu_with, cpu_without;
  json last;
  for (int i = 0; i < 3; ++i) {
    last = run_child(with, models);
    rtf_with.push_back(last.value("real_time_factor", 0.0));
    cpu_with.push_back(last.value("cpu_time_s", 0.0));
    const json other = run_child(without, models);
    rtf_without.push_back(other.value("real_time_factor", 0.0));
    cpu_without.push_back(other.value("cpu_time_s", 0.0));
  }
  j["real_time_factor"] = ratio_figure(median(rtf_with), "x real time", median(rtf_without),
                                       "the same scenario and seed without its mission (no referee, no radio), median of 3");
  j["real_time_factor"]["target_ratio"] = 0.9;
  j["real_time_factor"]["meets_target"] = j["real_time_factor"]["ratio"].get<double>() >= 0.9;
  j["real_time_factor"]["peak_memory_mb"] = last.value("peak_memory_mb", 0.0);
  // CPU seconds of the whole child: the cost where wall time is at the mercy of other load
  j["cpu_time"] = ratio_figure(median(cpu_with), "s", median(cpu_without), "the same run without its mission, median of 3");
  if (last.contains("mission")) j["score"] = last["mission"];

  // one link update: n(n−1)/2 links with walls counted, then the routes, for growing teams
  std::fprintf(stderr, "bench: radio link updates ...\n");
  const WorldSpec spec = build_world(with);
  const World world = compile_world(spec, models);
  const RayScene rays(world);
  const WallCounter walls(rays, world);
  json updates = json::array();
  const Vec2 lo = spec.floor_min, hi = spec.floor_max;
  for (int n : {4, 10, 30}) {
    RadioNetwork net(with.mission->radio.model, with.seed);
    // radios spread over the floor on a fixed pseudo-random pattern (the same each run)
    for (int k = 0; k < n; ++k) {
      const double fx = std::fmod(0.618034 * (k + 1), 1.0), fy = std::fmod(0.754878 * (k + 1), 1.0);
      std::string id = "r";
      id += std::to_string(k);
      net.add_node(id, k == 0 ? RadioNodeKind::base : RadioNodeKind::robot,
                   {lo.x() + fx * (hi.x() - lo.x()), lo.y() + fy * (hi.y() - lo.y()), 0.6});
    }
    const int repeats = std::max(20, 2000 / n);
    const double s = median_seconds(5, [&] {
      for (int r = 0; r < repeats; ++r) net.update(&walls);
    }) / repeats;
    int linked = 0;
    for (RadioNodeIndex a : net.node_indices()) {
      for (RadioNodeIndex b : net.node_indices()) linked += a < b && net.link(a, b).connected;
    }
    updates.push_back({{"radios", n}, {"links", n * (n - 1) / 2}, {"connected", linked}, {"us_per_update", s * 1e6},
                       {"share_of_real_time_at_link_rate", s * with.mission->radio.link_rate_hz}});
  }
  j["link_update"] = updates;
  return j;
}

}  // namespace rescuesim::bench
