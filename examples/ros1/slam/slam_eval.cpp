// slam_eval: scores a SLAM run of the office demonstration against the world's ground truth
// (mission/map_metrics.h) and draws it. Reads the scenario (for the world and the robot's laser) and a
// run folder holding map.yaml + map.pgm and trajectory.csv (slam_recorder writes them); writes
// map.png, slam.png (floor plan | SLAM map | trajectories) and slam_metrics.json into --out.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "import/scenario/scenario.h"
#include "mission/map_metrics.h"
#include "robots/rescue_robot.h"
#include "viz/canvas.h"
#include "viz/world_plot.h"

namespace fs = std::filesystem;
using namespace rescuesim;
using namespace rescuesim::map_eval;
using json = nlohmann::json;

namespace {

struct Trajectory {
  std::vector<double> t;
  std::vector<Pose2> truth, odom, slam;  // slam: only the rows where SLAM had a pose (paired with truth_s)
  std::vector<Pose2> truth_s;
};

Trajectory read_trajectory(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read the trajectory " + file.string());
  Trajectory tr;
  std::string line;
  std::getline(in, line);
  if (line.rfind("t,gt_x,gt_y,gt_yaw,odom_x", 0) != 0) {
    throw Error(file.string() + ":1: not a slam_recorder trajectory (header '" + line + "')");
  }
  for (int n = 2; std::getline(in, line); ++n) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) f.push_back(cell);
    if (line.back() == ',') f.emplace_back();
    if (f.size() != 10) throw Error(file.string() + ":" + std::to_string(n) + ": expected 10 comma-separated fields");
    auto num = [&](int k) {
      try {
        return std::stod(f[k]);
      } catch (const std::exception&) {
        throw Error(file.string() + ":" + std::to_string(n) + ": field " + std::to_string(k + 1) + " is not a number");
      }
    };
    tr.t.push_back(num(0));
    tr.truth.push_back({num(1), num(2), num(3)});
    tr.odom.push_back({num(4), num(5), num(6)});
    if (!f[7].empty()) {
      tr.slam.push_back({num(7), num(8), num(9)});
      tr.truth_s.push_back(tr.truth.back());
    }
  }
  if (tr.slam.size() < 2) throw Error(file.string() + ": fewer than two rows with a SLAM pose: did slam_node run?");
  return tr;
}

// the map grid as an image, one pixel per cell, north up (white free, black occupied, grey unknown)
Canvas draw_map_raw(const SlamMap& m) {
  Canvas c(m.grid.width, m.grid.height, {200, 200, 200});
  for (int j = 0; j < m.grid.height; ++j)
    for (int i = 0; i < m.grid.width; ++i) {
      const auto v = m.grid.at(i, j);
      if (v != kUnknown) c.set(i, m.grid.height - 1 - j, v == kOccupied ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255});
    }
  return c;
}

// the map resampled into the world frame through X_WM, on the same plot frame as the floor plan
void draw_map_in_world(Canvas& c, const PlotFrame& f, const SlamMap& m, const Pose2& X_WM) {
  const Pose2 X_MW = X_WM.inverse();
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const Vec2 p_W((x + 0.5 - f.margin) / f.px_per_m + f.world.min.x(), f.world.max.y() - (y + 0.5 - f.margin) / f.px_per_m);
      int i, j;
      m.grid.cell_of(X_MW.transform(p_W), i, j);
      if (!m.grid.inside(i, j) || m.grid.at(i, j) == kUnknown) continue;
      c.set(x, y, m.grid.at(i, j) == kOccupied ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255});
    }
}

std::vector<Vec2> to_px(const PlotFrame& f, const std::vector<Pose2>& poses, const Pose2& X_WM = {}) {
  std::vector<Vec2> pts;
  for (const auto& p : poses) pts.push_back(f.to_px(X_WM.transform(p.position())));
  return pts;
}

std::string fmt(const char* format, double v) {
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Score a SLAM run against the world's ground truth: occupied-cell precision and recall, and the\n"
               "absolute trajectory error (ATE); draw the floor plan, the SLAM map and both trajectories."};
  fs::path scenario_file, run_dir, out_dir;
  double laser_height = -1, ignore_margin = 0.3, wall_time = -1, rate = -1;
  int tolerance = 1;
  app.add_option("--scenario", scenario_file, "scenario YAML of the run (its world and robot)")->required()->check(CLI::ExistingFile);
  app.add_option("--run", run_dir, "folder with map.yaml, map.pgm and trajectory.csv (from slam_recorder)")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("-o,--out", out_dir, "where to write map.png, slam.png and slam_metrics.json (default: --run)");
  app.add_option("--tolerance-cells", tolerance, "a map cell matches a true one this many cells away (Chebyshev)")
      ->check(CLI::Range(0, 10));
  app.add_option("--laser-height", laser_height, "height of the laser plane above the floor (m; default: from the robot model)");
  app.add_option("--ignore-margin", ignore_margin, "cells this close to a victim count neither way (m)")->check(CLI::Range(0.0, 5.0));
  app.add_option("--wall-time", wall_time, "wall-clock seconds the run took, recorded in slam_metrics.json")->check(CLI::NonNegativeNumber);
  app.add_option("--rate", rate, "the run's pace (sim seconds per wall second), recorded in slam_metrics.json")->check(CLI::PositiveNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (out_dir.empty()) out_dir = run_dir;

  try {
    // the world and the robot's laser, as the simulator built them
    const ModelMap models = builtin_models();
    const Scenario scenario = load_scenario(scenario_file, models);
    const WorldSpec world = build_world(scenario);
    const auto robots = robot_configs(scenario, world, models);
    if (robots.empty()) throw Error(scenario_file.string() + ": the scenario has no robot");
    const RobotSpec& robot = robots.front().spec;
    LaserModel laser;
    bool have_laser = false;
    for (const auto& s : robot.sensors)
      if (s.type == SensorSpec::Type::lidar && s.link == "base_link") {
        laser.X_BL = {s.X_LS.p.x(), s.X_LS.p.y(), s.X_LS.yaw()};
        laser.min_angle = s.lidar.min_angle;
        laser.max_angle = s.lidar.max_angle;
        laser.beams = s.lidar.samples;
        laser.max_range = s.lidar.max_range;
        // base_link rides 0.15 m above the floor at rest (robots/rescue_robot.cpp)
        if (laser_height < 0) laser_height = 0.15 + s.X_LS.p.z();
        have_laser = true;
        break;
      }
    if (!have_laser) throw Error(scenario_file.string() + ": the robot has no laser on base_link");

    const SlamMap map = read_map(run_dir / "map.yaml");
    const Trajectory tr = read_trajectory(run_dir / "trajectory.csv");

    // alignment: the SLAM map frame is placed in the world by the first SLAM pose (no fitting);
    // the least-squares fit is reported beside it
    const TrajectoryError ate = trajectory_error(tr.truth_s, tr.slam, Alignment::start);
    const TrajectoryError ate_fit = trajectory_error(tr.truth_s, tr.slam, Alignment::least_squares);
    const TrajectoryError ate_odom = trajectory_error(tr.truth, tr.odom, Alignment::start);

    const Grid truth = true_occupancy(world, map.grid.resolution, laser_height);
    const Grid ignore = ignore_mask(world, truth, ignore_margin);
    std::vector<Pose2> scan_poses;  // the true poses every 0.1 s: the laser's rate
    double next_t = -1;
    for (std::size_t k = 0; k < tr.t.size(); ++k)
      if (tr.t[k] >= next_t) {
        scan_poses.push_back(tr.truth[k]);
        next_t = tr.t[k] + 0.1;
      }
    const Grid visible = visible_surface(truth, scan_poses, laser);
    const MapScore score = score_map(map, ate.X_WM, truth, visible, ignore, tolerance);

    // metrics
    double distance = 0;
    for (std::size_t k = 1; k < tr.truth.size(); ++k) distance += (tr.truth[k].position() - tr.truth[k - 1].position()).norm();
    json m;
    m["scenario"] = scenario_file.string();
    m["map"] = {{"resolution_m", map.grid.resolution}, {"width", map.grid.width}, {"height", map.grid.height}};
    m["sim_time_s"] = tr.t.back();
    if (wall_time >= 0) m["wall_time_s"] = wall_time;
    if (rate > 0) m["rate"] = rate;
    m["distance_m"] = distance;
    m["occupancy"] = {
        {"precision", score.precision},
        {"recall", score.recall},
        {"tolerance_cells", tolerance},
        {"map_occupied_cells", score.map_occupied},
        {"map_occupied_matched", score.map_matched},
        {"map_occupied_ignored_near_victims", score.map_ignored},
        {"visible_true_cells", score.visible},
        {"visible_true_matched", score.visible_matched},
        {"laser_height_m", laser_height},
        {"definition",
         "precision: occupied SLAM cells (map_server occupied_thresh), placed in the world by the start alignment, with a "
         "true occupied cell (walls, and obstacles taller than the laser plane) within tolerance_cells; cells within "
         "ignore_margin of a victim are not counted. recall: true occupied cells that a beam of the robot's laser from "
         "the true trajectory (every 0.1 s) hits first, with an occupied SLAM cell within tolerance_cells."}};
    auto pose_json = [](const Pose2& p) { return json{{"x", p.x}, {"y", p.y}, {"yaw", p.yaw}}; };
    m["ate"] = {{"rmse_m", ate.rmse},
                {"max_m", ate.max},
                {"pairs", ate.pairs},
                {"alignment", "start: the first SLAM pose (map -> base_link) placed on the first ground-truth pose; no fitting"},
                {"X_world_map", pose_json(ate.X_WM)},
                {"least_squares",
                 {{"rmse_m", ate_fit.rmse},
                  {"max_m", ate_fit.max},
                  {"alignment", "rigid 2-D least-squares fit (Umeyama, no scale) of the SLAM positions to the true ones"},
                  {"X_world_map", pose_json(ate_fit.X_WM)}}},
                {"odometry_only", {{"rmse_m", ate_odom.rmse}, {"max_m", ate_odom.max}, {"alignment", "start"}}}};
    fs::create_directories(out_dir);
    write_file_atomic(out_dir / "slam_metrics.json", m.dump(2) + "\n");

    // pictures: the raw map, and the three panels on one plot frame
    draw_map_raw(map).write_png(out_dir / "map.png");
    WorldPlotOptions po;
    po.px_per_m = 25;
    po.grid = false;
    po.legend = false;
    const PlotFrame f = plot_frame_for(world, po);
    const int title_h = 28, gap = 10;
    Canvas plan = plot_world(world, po);
    Canvas mapc(f.width(), f.height(), {200, 200, 200});
    draw_map_in_world(mapc, f, map, ate.X_WM);
    Canvas trc(f.width(), f.height(), {255, 255, 255});
    // faint floor plan under the trajectories
    {
      Canvas faint = plot_world(world, po);
      for (int y = 0; y < faint.height(); ++y)
        for (int x = 0; x < faint.width(); ++x) {
          const Rgb8 p = faint.at(x, y);
          trc.set(x, y, {static_cast<std::uint8_t>(255 - (255 - p.r) / 4), static_cast<std::uint8_t>(255 - (255 - p.g) / 4),
                         static_cast<std::uint8_t>(255 - (255 - p.b) / 4)});
        }
    }
    trc.polyline(to_px(f, tr.odom, ate_odom.X_WM), {150, 150, 150}, 1.5);
    trc.polyline(to_px(f, tr.truth), {40, 160, 40}, 3.0);
    trc.polyline(to_px(f, tr.slam, ate.X_WM), {214, 39, 40}, 1.5);
    const int W = 3 * f.width() + 2 * gap, H = f.height() + title_h + 22;
    Canvas fig(W, H, {255, 255, 255});
    const std::string titles[3] = {"ground truth: " + world.name,
                                   "SLAM map: P " + fmt("%.2f", score.precision) + ", R " + fmt("%.2f", score.recall),
                                   "trajectory: ATE " + fmt("%.3f m", ate.rmse)};
    const Canvas* panels[3] = {&plan, &mapc, &trc};
    for (int k = 0; k < 3; ++k) {
      const int x0 = k * (f.width() + gap);
      fig.paste(*panels[k], x0, title_h);
      fig.text(x0 + f.margin, 8, titles[k], {0, 0, 0}, 2);
    }
    const int ly = title_h + f.height() + 4;
    int lx = 2 * (f.width() + gap) + f.margin;
    const std::pair<Rgb8, const char*> legend[3] = {{{40, 160, 40}, "truth"}, {{214, 39, 40}, "SLAM"}, {{150, 150, 150}, "odometry"}};
    for (const auto& [colour, label] : legend) {
      fig.fill_rect(lx, ly + 4, lx + 16, ly + 8, colour);
      lx += 20 + fig.text(lx + 20, ly, label, {0, 0, 0}, 2) + 12;
    }
    fig.text(f.margin, ly, fmt("%.0f s sim time", tr.t.back()) + ", " + fmt("%.0f m driven", distance), {0, 0, 0}, 2);
    fig.write_png(out_dir / "slam.png");

    std::printf("slam_eval: precision %.3f, recall %.3f (within %d cell of %.3f m), ATE %.3f m (start-aligned; "
                "least-squares %.3f m; odometry alone %.3f m) over %.0f s and %.0f m\n",
                score.precision, score.recall, tolerance, map.grid.resolution, ate.rmse, ate_fit.rmse, ate_odom.rmse,
                tr.t.back(), distance);
    std::printf("slam_eval: wrote %s/{slam_metrics.json, map.png, slam.png}\n", out_dir.string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "slam_eval: %s\n", e.what());
    return 2;
  }
  return 0;
}
