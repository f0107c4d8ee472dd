#include "bench/bench_urdf.h"

#include <algorithm>
#include <cstdio>

#include "bench/bench_figures.h"
#include "import/mesh/mesh.h"
#include "import/urdf/urdf_import.h"
#include "robots/rescue_robot.h"

namespace rescuesim::bench {

using json = nlohmann::ordered_json;

json bench_urdf(const std::filesystem::path& scenario_file, double sim_seconds, const RunChild& run_child) {
  if (!std::filesystem::exists(scenario_file)) {
    return {{"skipped", scenario_file.string() + " not found (run the bench from the source folder, or give --urdf-scenario)"}};
  }
  const ModelMap models = builtin_models();
  const Scenario scenario = load_scenario(scenario_file, models);
  if (scenario.robots.empty() || scenario.robots[0].urdf.empty())
    return {{"skipped", scenario_file.string() + ": its first robot is not a URDF robot"}};
  const RobotConfig& rc = scenario.robots[0];
  UrdfOptions uo;
  uo.resolver = ResourceResolver(scenario.resource_paths);
  json j;
  j["robot"] = rc.urdf;

  // reading the robot, beside loading its mesh files alone (the importer's own cost on top)
  std::fprintf(stderr, "bench: URDF load ...\n");
  UrdfRobot robot;
  const double load = median_seconds(5, [&] { robot = load_urdf(rc.urdf, uo); });
  const double meshes = median_seconds(5, [&] {
    for (const auto& m : robot.meshes) load_mesh(m.file);
  });
  long triangles = 0;
  for (const auto& m : robot.meshes) triangles += m.triangles;
  j["load"] = ratio_figure(load * 1e3, "ms", meshes * 1e3, "loading the same mesh files alone (assimp), median of 5");
  j["load"]["mesh_files"] = robot.meshes.size();
  j["load"]["triangles"] = triangles;

  // convex hulls: the largest mesh with the 64-vertex budget, beside its exact hull
  std::fprintf(stderr, "bench: convex hulls ...\n");
  const auto biggest = std::max_element(robot.meshes.begin(), robot.meshes.end(),
                                        [](const UrdfMeshReport& a, const UrdfMeshReport& b) { return a.triangles < b.triangles; });
  if (biggest != robot.meshes.end()) {
    const LoadedMesh mesh = load_mesh(biggest->file, MeshLoadOptions{});
    std::size_t budget_vertices = 0, exact_vertices = 0;
    const double hull = median_seconds(5, [&] { budget_vertices = convex_hull(mesh.mesh.vertices, 64).vertices.size(); });
    const double exact = median_seconds(5, [&] { exact_vertices = convex_hull(mesh.mesh.vertices, 1 << 30).vertices.size(); });
    j["hull"] = ratio_figure(hull * 1e3, "ms", exact * 1e3, "the exact convex hull of the same points (no vertex budget), median of 5");
    j["hull"]["mesh"] = biggest->uri;
    j["hull"]["mesh_vertices"] = mesh.mesh.vertices.size();
    j["hull"]["hull_vertices"] = budget_vertices;
    j["hull"]["exact_hull_vertices"] = exact_vertices;
    std::size_t pieces = 0;
    const double decomposition = median_seconds(1, [&] { pieces = convex_decomposition(mesh.mesh).size(); });
    j["hull"]["decomposition_ms"] = decomposition * 1e3;
    j["hull"]["decomposition_pieces"] = pieces;
  }

  // the robot in its maze, beside the built-in rescue robot in the same maze from the same start
  std::fprintf(stderr, "bench: URDF robot vs built-in robot, %.0f s each ...\n", sim_seconds);
  Scenario mine = scenario;
  mine.duration = sim_seconds;
  Scenario builtin = mine;
  RobotConfig b;
  b.name = rc.name;
  b.start = rc.start;
  b.controller = rc.controller;
  b.spec = models.at("rescue_robot");
  builtin.robots = {b};
  const json ours = run_child(mine, models);
  const json theirs = run_child(builtin, models);
  j["real_time_factor"] = ratio_figure(ours.value("real_time_factor", 0.0), "x real time", theirs.value("real_time_factor", 0.0),
                                       "the built-in rescue robot in the same maze, same controller, no cameras");
  j["real_time_factor"]["peak_memory_mb"] = ours.value("peak_memory_mb", 0.0);
  j["real_time_factor"]["builtin_peak_memory_mb"] = theirs.value("peak_memory_mb", 0.0);
  return j;
}

}  // namespace rescuesim::bench
