// rescuesim_nav_plot: the seed's Fig. 5 for one navigation run: left, the maze with the robot's
// true path and the victims found or missed; right, the navigation node's own map with its
// odometry path and the routes its A* planner chose (earlier ones faint, the last one bold), from
// the files the simulator and the node left.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "import/svg/svg_world.h"
#include "viz/world_plot.h"

namespace rescuesim::nav {

namespace {

const char* kUsage =
    "rescuesim_nav_plot: draw a navigation run like the seed's Fig. 5 (docs/demos.md)\n"
    "\n"
    "Usage: rescuesim_nav_plot --run DIR --nav FILE --out FILE.png [--title TEXT] [--px-per-m N]\n"
    "\n"
    "  --run DIR      the simulator's output folder (world.svg, trajectory.csv, summary.json)\n"
    "  --nav FILE     the record rescuesim_nav wrote with --out (its planned paths, odom frame)\n"
    "  --out FILE     the PNG to write (atomically)\n"
    "  --title TEXT   a line above the map\n"
    "  --px-per-m N   resolution (default 40; small worlds are drawn at least 420 px wide)\n"
    "\n"
    "Left, the truth: the maze, the robot's true path, the victims seen (ring) or missed (cross).\n"
    "Right, what the node knew: its occupancy map, the robot's odometry path and every A* route,\n"
    "in the odom frame at the same scale (odometry drifts, so the two pictures differ; when it ran\n"
    "far off, the right side is drawn smaller and says so).\n"
    "Exit codes: 0 written, 2 bad arguments or unreadable input files.\n";

const Rgb8 kPathColour{20, 150, 60};
const Rgb8 kRouteColour{230, 110, 0};
const Rgb8 kEndColour{20, 80, 200};

/// One row of trajectory.csv (first robot only).
struct Sample {
  double t;
  Pose2 truth, odom;
};

std::vector<Sample> read_trajectory(const std::filesystem::path& file) {
  std::istringstream in(read_file(file));
  std::string line;
  std::getline(in, line);  // header
  std::vector<Sample> out;
  std::string first_robot;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) f.push_back(cell);
    if (f.size() < 8) throw Error({file.string(), n, "trajectory row"}, "expected t,robot,x,y,yaw,odom_x,odom_y,odom_yaw,...");
    if (first_robot.empty()) first_robot = f[1];
    if (f[1] != first_robot) continue;
    out.push_back(
        {std::stod(f[0]), {std::stod(f[2]), std::stod(f[3]), std::stod(f[4])}, {std::stod(f[5]), std::stod(f[6]), std::stod(f[7])}});
  }
  if (out.empty()) throw Error({file.string(), 0, ""}, "no trajectory samples");
  return out;
}

int run(int argc, char** argv) {
  std::string run_dir, nav_file, out, title;
  double px_per_m = 40;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "rescuesim_nav_plot: unknown argument or missing value: '%s' (see --help)\n", a.c_str());
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--run") {
      run_dir = v;
    } else if (a == "--nav") {
      nav_file = v;
    } else if (a == "--out") {
      out = v;
    } else if (a == "--title") {
      title = v;
    } else if (a == "--px-per-m") {
      px_per_m = std::atof(v.c_str());
      if (!(px_per_m >= 5 && px_per_m <= 200)) {
        std::fprintf(stderr, "rescuesim_nav_plot: --px-per-m wants 5 .. 200, not '%s'\n", v.c_str());
        return 2;
      }
    } else {
      std::fprintf(stderr, "rescuesim_nav_plot: unknown argument '%s' (see --help)\n", a.c_str());
      return 2;
    }
  }
  if (run_dir.empty() || nav_file.empty() || out.empty()) {
    std::fprintf(stderr, "rescuesim_nav_plot: --run, --nav and --out are required (see --help)\n");
    return 2;
  }
  const std::filesystem::path dir(run_dir);
  const WorldSpec world = load_svg_world(dir / "world.svg").world;
  const std::vector<Sample> traj = read_trajectory(dir / "trajectory.csv");
  const auto summary = nlohmann::json::parse(read_file(dir / "summary.json"));
  const auto nav = nlohmann::json::parse(read_file(nav_file));

  WorldPlotOptions po;
  // small mazes are drawn larger, so that the title and the key fit
  const Vec2 size = world.floor_max - world.floor_min;
  po.px_per_m = std::max(px_per_m, 420.0 / std::max(1.0, size.x()));
  po.title = title;
  Canvas left = plot_world(world, po);
  const PlotFrame frame = plot_frame_for(world, po);

  // left, the truth: the robot's path through the maze, start and end, victims found or missed
  std::vector<Vec2> path;
  for (const Sample& s : traj) path.push_back(frame.to_px(s.truth.position()));
  left.polyline(path, kPathColour, 2.0);
  left.fill_circle(path.front(), 5, {20, 120, 40});
  left.fill_circle(path.back(), 6, kEndColour);
  for (const auto& v : world.victims) {
    bool found = false;
    for (const auto& r : summary.at("victims")) {
      if (r.value("name", "") == v.name) found = r.value("found", false);
    }
    const Vec2 p = frame.to_px(v.pose.position());
    if (found) {
      left.circle(p, 12, {20, 170, 40}, 3.0);
    } else {
      left.line(p + Vec2(-9, -9), p + Vec2(9, 9), {220, 30, 30}, 3.0);
      left.line(p + Vec2(-9, 9), p + Vec2(9, -9), {220, 30, 30}, 3.0);
    }
  }

  // right, what the node knew: its map, its odometry path and the routes A* chose, all in the
  // odom frame (x along the robot's start heading), at the same scale as the maze
  std::vector<std::vector<Vec2>> routes;
  for (const auto& p : nav.at("paths")) {
    std::vector<Vec2> r;
    for (const auto& q : p.at("points")) r.emplace_back(q[0].get<double>(), q[1].get<double>());
    if (r.size() >= 2) routes.push_back(std::move(r));
  }
  std::vector<Vec2> odom_path;
  for (const Sample& s : traj) odom_path.push_back(s.odom.position());
  Box2 box{odom_path.front(), odom_path.front()};
  const auto grow = [&box](const Vec2& p) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  };
  for (const Vec2& p : odom_path) grow(p);
  for (const auto& r : routes) {
    for (const Vec2& p : r) grow(p);
  }
  const auto map = nav.find("map");
  double res = 0;
  Pose2 X_OM;
  std::vector<std::string> rows;
  if (map != nav.end()) {
    res = map->at("resolution").get<double>();
    const auto& o = map->at("origin");
    X_OM = Pose2{o[0].get<double>(), o[1].get<double>(), o[2].get<double>()};
    rows = map->at("rows").get<std::vector<std::string>>();
    for (std::size_t y = 0; y < rows.size(); ++y) {
      for (std::size_t x = 0; x < rows[y].size(); ++x) {
        if (rows[y][x] != '?') grow(X_OM.transform({(x + 0.5) * res, (y + 0.5) * res}));
      }
    }
  }
  PlotFrame odom_frame;
  const Vec2 pad(0.3, 0.3);  // m around what is drawn
  odom_frame.world.min = box.min - pad;
  odom_frame.world.max = box.max + pad;
  // the maze's scale, unless odometry ran far off (wheels spinning on the spot): then smaller,
  // so that the panel stays within 1.5 times the maze picture
  const Vec2 extent = odom_frame.world.size();
  odom_frame.px_per_m = std::min({frame.px_per_m, 1.5 * left.width() / extent.x(), 1.5 * left.height() / extent.y()});
  odom_frame.margin = frame.margin;
  const double shrink = frame.px_per_m / odom_frame.px_per_m;
  const int title_h = frame.margin + 16;
  Canvas right(odom_frame.width(), odom_frame.height() + title_h, {255, 255, 255});
  const auto to_px = [&](const Vec2& p_O) -> Vec2 { return odom_frame.to_px(p_O) + Vec2(0, title_h); };
  right.fill_rect(static_cast<int>(to_px(odom_frame.world.min).x()), static_cast<int>(to_px(odom_frame.world.max).y()),
                  static_cast<int>(to_px(odom_frame.world.max).x()), static_cast<int>(to_px(odom_frame.world.min).y()), {205, 205, 205});
  const double cell_px = std::max(1.0, res * odom_frame.px_per_m);
  for (std::size_t y = 0; y < rows.size(); ++y) {
    for (std::size_t x = 0; x < rows[y].size(); ++x) {
      const char c = rows[y][x];
      if (c == '?') continue;
      const Vec2 p = to_px(X_OM.transform({(x + 0.5) * res, (y + 0.5) * res}));
      const Rgb8 colour = c == '#' ? Rgb8{30, 30, 30} : c == '+' ? Rgb8{150, 150, 150} : Rgb8{255, 255, 255};
      const int x0 = static_cast<int>(std::floor(p.x() - cell_px / 2)), y0 = static_cast<int>(std::floor(p.y() - cell_px / 2));
      const int n = static_cast<int>(std::ceil(cell_px));
      right.fill_rect(x0, y0, x0 + n, y0 + n, colour);
    }
  }
  for (std::size_t i = 0; i + 1 < routes.size(); ++i) {
    std::vector<Vec2> px;
    for (const Vec2& p : routes[i]) px.push_back(to_px(p));
    right.polyline(px, kRouteColour, 1.5, false, 0.45);
  }
  std::vector<Vec2> odom_px;
  for (const Vec2& p : odom_path) odom_px.push_back(to_px(p));
  right.polyline(odom_px, kPathColour, 2.0);
  right.fill_circle(odom_px.front(), 5, {20, 120, 40});
  right.fill_circle(odom_px.back(), 6, kEndColour);
  if (!routes.empty()) {
    std::vector<Vec2> px;
    for (const Vec2& p : routes.back()) px.push_back(to_px(p));
    right.polyline(px, kRouteColour, 4.0);
    right.fill_circle(px.front(), 5, kRouteColour);
    right.circle(px.back(), 8, kRouteColour, 3.0);
  }
  char scale[64] = "";
  if (shrink > 1.01) std::snprintf(scale, sizeof scale, ", 1/%.1f of the maze's scale", shrink);
  right.text(frame.margin, frame.margin, std::string("the node's map and A* routes (odom frame") + scale + ")", {0, 0, 0});


  // side by side, tops aligned
  constexpr int kGap = 16;
  Canvas img(left.width() + kGap + right.width(), std::max(left.height(), right.height()));
  img.paste(left, 0, 0);
  img.paste(right, left.width() + kGap, 0);

  // a key under the map, wrapped to its width
  struct KeyItem {
    const char* label;
    Rgb8 colour;
    double width, alpha;
    bool ring;
  };
  const KeyItem key[] = {{"path (left: true, right: odometry)", kPathColour, 2.0, 1.0, false},
                         {"end", kEndColour, 6.0, 1.0, false},
                         {"last A* route (dot: from, ring: to)", kRouteColour, 4.0, 1.0, false},
                         {"earlier A* routes", kRouteColour, 1.5, 0.45, false},
                         {"victim seen", {20, 170, 40}, 2.0, 1.0, true}};
  constexpr int kRow = 16, kSwatch = 24, kPad = 10;
  std::vector<std::pair<int, int>> at;  // (x, row) of each item
  int x = kPad, row = 0;
  for (const KeyItem& k : key) {
    const int w = kSwatch + 6 + 6 * static_cast<int>(std::string(k.label).size()) + 18;
    if (x + w > img.width() - kPad && x > kPad) {
      x = kPad;
      ++row;
    }
    at.emplace_back(x, row);
    x += w;
  }
  Canvas fig(img.width(), img.height() + (row + 1) * kRow + 4);
  fig.paste(img, 0, 0);
  for (std::size_t i = 0; i < at.size(); ++i) {
    const KeyItem& k = key[i];
    const double kx = at[i].first, ky = img.height() + at[i].second * kRow + 4;
    if (k.ring) {
      fig.circle({kx + kSwatch / 2.0, ky + 3}, 6, k.colour, k.width);
    } else {
      fig.line({kx, ky + 3}, {kx + kSwatch, ky + 3}, k.colour, k.width, k.alpha);
    }
    fig.text(static_cast<int>(kx) + kSwatch + 6, static_cast<int>(ky), k.label, {40, 40, 40});
  }
  img = std::move(fig);
  img.write_png(out);
  return 0;
}

}  // namespace

}  // namespace rescuesim::nav

int main(int argc, char** argv) {
  try {
    return rescuesim::nav::run(argc, argv);
  } catch (const std::exception& e) {
    // unreadable or malformed input files
    std::fprintf(stderr, "rescuesim_nav_plot: %s\n", e.what());
    return 2;
  }
}
