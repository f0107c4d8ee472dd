// The mission's outputs when a run ends (MissionSystem::write_outputs): score.png and the
// reports' pictures in reports/.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mission/mission_system.h"
#include "sim/run_outputs.h"
#include "viz/canvas.h"

namespace rescuesim {

namespace {

/// A report's picture (an encoding image_problem accepts) as a canvas.
Canvas picture_canvas(const msg::Image& m) {
  const std::size_t channels = m.encoding == "mono8" ? 1 : m.encoding.size() == 5 ? 4 : 3;  // rgba8/bgra8 : rgb8/bgr8
  const bool bgr = m.encoding[0] == 'b';
  Canvas img(static_cast<int>(m.width), static_cast<int>(m.height));
  for (std::uint32_t y = 0; y < m.height; ++y) {
    for (std::uint32_t x = 0; x < m.width; ++x) {
      const std::uint8_t* p = &m.data[static_cast<std::size_t>(y) * m.step + x * channels];
      const Rgb8 c = channels == 1 ? Rgb8{p[0], p[0], p[0]} : bgr ? Rgb8{p[2], p[1], p[0]} : Rgb8{p[0], p[1], p[2]};
      img.set(static_cast<int>(x), static_cast<int>(y), c);
    }
  }
  return img;
}

/// score.png: the score over the run as a step line, with each charged report marked (green:
/// a victim found, red: false, grey: duplicate) and the victims found as a second line.
Canvas score_plot(const MissionResult& m, double sim_time, const std::string& title) {
  const int w = 720, h = 360, left = 56, right = 20, top = 40, bottom = 44;
  Canvas img(w, h, {255, 255, 255});
  const double t_max = std::max(sim_time, 1.0);
  double lo = 0, hi = std::max(1.0, static_cast<double>(m.victims));
  for (const auto& e : m.timeline) lo = std::min(lo, e.score), hi = std::max(hi, e.score);
  const auto px = [&](double t, double y) {
    return Vec2(left + (w - left - right) * t / t_max, h - bottom - (h - top - bottom) * (y - lo) / (hi - lo));
  };
  // axes, a grid line per score unit (at most 20), and their labels
  const int step = std::max(1, static_cast<int>(std::ceil((hi - lo) / 20)));
  for (int k = static_cast<int>(std::floor(lo)); k <= static_cast<int>(std::ceil(hi)); k += step) {
    img.line(px(0, k), px(t_max, k), k == 0 ? Rgb8{120, 120, 120} : Rgb8{225, 225, 225});
    img.text(8, static_cast<int>(px(0, k).y()) - 4, std::to_string(k), {0, 0, 0});
  }
  for (int i = 0; i <= 6; ++i) {
    const double t = t_max * i / 6;
    img.text(static_cast<int>(px(t, lo).x()) - 12, h - bottom + 8, std::to_string(static_cast<int>(std::lround(t))) + " s", {0, 0, 0});
  }
  // victims found (blue) and score (black), as steps
  std::vector<Vec2> found{px(0, 0)}, score{px(0, 0)};
  int n = 0;
  double last = 0;
  for (const auto& e : m.timeline) {
    found.push_back(px(e.t, n));
    if (e.outcome == ReportOutcome::accepted) ++n;
    found.push_back(px(e.t, n));
    score.push_back(px(e.t, last));
    score.push_back(px(e.t, e.score));
    last = e.score;
  }
  found.push_back(px(t_max, n));
  score.push_back(px(t_max, last));
  img.polyline(found, {60, 110, 220}, 2.0);
  img.polyline(score, {0, 0, 0}, 2.0);
  for (const auto& e : m.timeline) {
    const Rgb8 c = e.outcome == ReportOutcome::accepted       ? Rgb8{20, 170, 40}
                   : e.outcome == ReportOutcome::false_report ? Rgb8{220, 30, 30}
                                                              : Rgb8{150, 150, 150};
    img.fill_circle(px(e.t, e.score), 4, c);
  }
  img.text(left, 8, title, {0, 0, 0});
  img.text(left, 22, "score (black; dots: green found, red false, grey duplicate), victims found (blue)", {90, 90, 90});
  return img;
}

}  // namespace

std::string report_picture_file(const ReportPicture& p, const std::vector<std::string>& robot_names) {
  return "reports/" + std::to_string(p.report) + "_" + robot_names.at(p.robot.slot()) + "_" + std::string(report_outcome_name(p.outcome)) +
         ".png";
}

void MissionSystem::write_outputs(const Simulation&, RunOutputs& out) const {
  const MissionResult m = mission_.result();
  char title[160];
  std::snprintf(title, sizeof title, "%s: score %g, %d/%d victims, %llu false (%s rules, %s radio)", out.run_name.c_str(), m.score,
                m.victims_found, m.victims, static_cast<unsigned long long>(m.counts[ReportOutcome::false_report]), m.rules.c_str(),
                m.radio_model.c_str());
  score_plot(m, out.sim_time, title).write_png(out.dir / "score.png");
  for (const ReportImage& p : mission_.report_images()) {
    picture_canvas(p.image).write_png(out.dir / report_picture_file(p.about, m.robot_names));
  }
}

}  // namespace rescuesim
