#include "bench/bench_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include <fmt/format.h>

#include "bench/scale_scenario.h"
#include "robots/rescue_robot.h"
#include "viz/canvas.h"

namespace rescuesim::bench {

namespace {

using json = nlohmann::ordered_json;

/// Real-time factor (log) and peak memory (linear) against robots (log), one point per run,
/// with the ideal RTF(first) x first / N in grey.
void plot(const json& runs, const std::filesystem::path& png) {
  constexpr int kW = 900, kH = 620, kLeft = 80, kRight = 30, kTop = 40, kGap = 70;
  const int panel_h = (kH - kTop - kGap - 50) / 2;
  Canvas c(kW, kH);
  std::vector<double> n, rtf, mem, ideal;
  for (const auto& r : runs) {
    if (!r.contains("real_time_factor")) continue;
    n.push_back(r["robots"].get<double>());
    rtf.push_back(std::max(r["real_time_factor"].get<double>(), 1e-3));
    mem.push_back(r.value("peak_memory_mb", 0.0));
    ideal.push_back(std::max(r.value("ideal_real_time_factor", 0.0), 1e-3));
  }
  if (n.empty()) {
    c.text(kLeft, kTop, "no run finished", {200, 0, 0}, 2);
    c.write_png(png);
    return;
  }
  const double x0 = std::log10(*std::min_element(n.begin(), n.end())),
               x1 = std::max(x0 + 1, std::log10(*std::max_element(n.begin(), n.end())));
  const int right = kW - kRight;
  const auto x_px = [&](double robots) { return kLeft + (std::log10(robots) - x0) / (x1 - x0) * (right - kLeft); };
  // a point's label right of it, or left of it near the right edge
  const auto label_at = [&](const Vec2& p, const std::string& label, Rgb8 colour) {
    const int x = p.x() + 6 + text_width(label) > kW - 2 ? static_cast<int>(p.x()) - 6 - text_width(label) : static_cast<int>(p.x()) + 6;
    c.text(x, static_cast<int>(p.y()) - 12, label, colour);
  };
  // one value per run: a line through the points, each dot labelled with its value
  const auto series = [&](const std::vector<double>& ys, const auto& y_px, Rgb8 colour, Rgb8 text, const auto& format) {
    std::vector<Vec2> pts;
    for (std::size_t i = 0; i < n.size(); ++i) pts.push_back({x_px(n[i]), y_px(ys[i])});
    if (pts.size() > 1) c.polyline(pts, colour, 2.0);
    for (std::size_t i = 0; i < n.size(); ++i) {
      c.fill_circle(pts[i], 4, colour);
      label_at(pts[i], format(ys[i]), text);
    }
  };
  const auto axes = [&](int top, const std::string& title) {
    const int bottom = top + panel_h;
    c.line({double(kLeft), double(bottom)}, {double(right), double(bottom)}, {0, 0, 0});
    c.line({double(kLeft), double(top)}, {double(kLeft), double(bottom)}, {0, 0, 0});
    c.text(kLeft, top - 22, title, {0, 0, 0}, 2);
    for (double v : n) {
      c.line({x_px(v), double(bottom)}, {x_px(v), double(bottom + 4)}, {0, 0, 0});
      const std::string label = fmt::format("{:.0f}", v);
      c.text(static_cast<int>(x_px(v)) - text_width(label) / 2, bottom + 8, label, {0, 0, 0});
    }
    c.text(right - text_width("robots"), bottom + 22, "robots", {0, 0, 0});
    return bottom;
  };
  // real-time factor, log scale from the decade below the least to the decade above the most
  {
    // (a little below the least, so that its point and label clear the axis)
    const double lo =
        std::floor(std::log10(std::min(*std::min_element(rtf.begin(), rtf.end()), *std::min_element(ideal.begin(), ideal.end()))) - 0.2);
    const double hi = std::ceil(std::log10(std::max(*std::max_element(rtf.begin(), rtf.end()), 1.0)) + 1e-9);
    const int bottom = axes(kTop, "real-time factor; grey: N robots costing N x one");
    const auto y_px = [&](double v) { return bottom - (std::log10(v) - lo) / (hi - lo) * panel_h; };
    for (double d = lo; d <= hi; d += 1) {
      const std::string label = d >= 0 ? fmt::format("{:.0f}x", std::pow(10, d)) : fmt::format("{:g}x", std::pow(10, d));
      c.text(4, static_cast<int>(y_px(std::pow(10, d))) - 4, label, {0, 0, 0});
      c.line({double(kLeft), y_px(std::pow(10, d))}, {double(right), y_px(std::pow(10, d))}, {225, 225, 225});
    }
    c.line({double(kLeft), y_px(1)}, {double(right), y_px(1)}, {200, 120, 120});  // real time
    for (std::size_t i = 1; i < n.size(); ++i) c.line({x_px(n[i - 1]), y_px(ideal[i - 1])}, {x_px(n[i]), y_px(ideal[i])}, {150, 150, 150});
    series(rtf, y_px, {30, 140, 60}, {30, 100, 40}, [](double v) { return fmt::format("{:.2f}x", v); });
  }
  // peak memory, linear
  {
    const double hi = std::max(*std::max_element(mem.begin(), mem.end()) * 1.15, 1.0);
    const int bottom = axes(kTop + panel_h + kGap, "peak memory MB");
    const auto y_px = [&](double v) { return bottom - v / hi * panel_h; };
    c.text(4, kTop + panel_h + kGap, fmt::format("{:.0f}", hi), {0, 0, 0});
    c.text(4, bottom - 8, "0", {0, 0, 0});
    series(mem, y_px, {40, 90, 200}, {30, 60, 150}, [](double v) { return fmt::format("{:.0f}", v); });
  }
  c.write_png(png);
}

}  // namespace

json bench_scale(const std::vector<int>& robots, double sim_seconds, const RunChild& run_child, const std::filesystem::path& png) {
  const ModelMap models = builtin_models();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  json out;
  out["scenario"] = "the scale scenario (session/scale_scenario.h): 20/12 m maze cells, 12 x 12 up to 144 robots; "
                    "a 1081-beam 270 deg 30 m lidar at 10 Hz each, odometry, IMU, sonars, wall following; no cameras";
  out["sim_seconds"] = sim_seconds;
  out["cores"] = cores;
  json runs = json::array();
  double first_rtf = 0;
  int first_n = 0;
  for (int n : robots) {
    std::fprintf(stderr, "bench: scale scenario, %d robot%s, %.0f s of sim time ...\n", n, n == 1 ? "" : "s", sim_seconds);
    json r = run_child(scale_scenario(n, sim_seconds, models), models);
    json row;
    row["robots"] = n;
    row["maze_cells"] = scale_maze_cells(n);
    if (r.contains("error")) {
      row["error"] = r["error"];
      runs.push_back(row);
      continue;
    }
    const double rtf = r.value("real_time_factor", 0.0), wall = r.value("wall_time_s", 0.0), sim = r.value("sim_time_s", 0.0);
    if (first_n == 0 && rtf > 0) {
      first_n = n;
      first_rtf = rtf;
    }
    row["real_time_factor"] = rtf;
    row["sim_time_s"] = sim;
    row["wall_time_s"] = wall;
    // every robot's laser: 1081 beams, 10 scans per sim second
    row["rays_per_s"] = wall > 0 ? static_cast<double>(n) * 1081 * 10 * sim / wall : 0.0;
    row["peak_memory_mb"] = r.value("peak_memory_mb", 0.0);
    row["peak_memory_per_robot_mb"] = r.value("peak_memory_mb", 0.0) / n;
    row["cpu_time_s"] = r.value("cpu_time_s", 0.0);
    row["cpu_per_core"] = wall > 0 ? r.value("cpu_time_s", 0.0) / wall / cores : 0.0;
    const double ideal = first_rtf * first_n / n;
    row["ideal_real_time_factor"] = ideal;
    row["scaling"] = ideal > 0 ? rtf / ideal : 0.0;
    runs.push_back(row);
  }
  out["baseline_is"] = "ideal_real_time_factor: the first count's real-time factor x its robots / N (N robots costing N times as much)";
  out["runs"] = runs;
  if (!png.empty()) {
    plot(runs, png);
    out["plot"] = png.string();
  }
  return out;
}

}  // namespace rescuesim::bench
