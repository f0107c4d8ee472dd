// summary.png: a batch at a glance. Top left, the share of trials that have found every victim
// by each moment of sim time (and the mean share of victims found); then histograms of victims
// found, coverage, collisions and real-time factor. A batch of terrain trials instead shows
// histograms of repetitions, falls and stuck events per trial, time per repetition and
// real-time factor.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "batch/batch_summary.h"

namespace rescuesim {

namespace {

constexpr Rgb8 kInk{40, 40, 40};
constexpr Rgb8 kGrid{225, 225, 225};
constexpr Rgb8 kBlue{50, 110, 190};
constexpr Rgb8 kOrange{230, 130, 30};

std::string format(double v) {
  char buf[32];
  if (std::abs(v) >= 100 || v == std::floor(v)) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else if (std::abs(v) >= 10) {
    std::snprintf(buf, sizeof buf, "%.1f", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.2g", v);
  }
  return buf;
}

/// Round tick values (1, 2 or 5 times a power of ten apart) from lo to hi, about six of them.
std::vector<double> nice_ticks(double lo, double hi) {
  const double step = nice_step(hi - lo, 6);
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) ticks.push_back(std::abs(v) < 1e-12 ? 0.0 : v);
  return ticks;
}

/// A plot area: data range mapped onto a pixel rectangle.
struct Axes {
  int x = 0, y = 0, w = 0, h = 0;  // plot rectangle (px)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  Vec2 px(double vx, double vy) const {
    return {x + (vx - x0) / (x1 - x0) * w, y + h - (vy - y0) / (y1 - y0) * h};
  }
};

/// A panel's frame, title, grid and tick labels; returns the axes inside it.
Axes panel(Canvas& img, int px, int py, int pw, int ph, const std::string& title, const std::string& xlabel, double x0, double x1,
           double y0, double y1, std::vector<double> xticks = {}, int yticks = 5) {
  Axes a;
  a.x = px + 56;
  a.y = py + 34;
  a.w = pw - 56 - 16;
  a.h = ph - 34 - 44;
  a.x0 = x0;
  a.x1 = x1 > x0 ? x1 : x0 + 1;
  a.y0 = y0;
  a.y1 = y1 > y0 ? y1 : y0 + 1;
  img.text(px + (pw - text_width(title, 2)) / 2, py + 8, title, kInk, 2);
  for (int k = 0; k <= yticks; ++k) {
    const double v = a.y0 + (a.y1 - a.y0) * k / yticks;
    const Vec2 p = a.px(a.x0, v);
    img.line({double(a.x), p.y()}, {double(a.x + a.w), p.y()}, kGrid);
    const std::string s = format(v);
    img.text(a.x - 6 - text_width(s, 1), static_cast<int>(p.y()) - 3, s, kInk, 1);
  }
  if (xticks.empty()) xticks = nice_ticks(a.x0, a.x1);
  for (double v : xticks) {
    const Vec2 p = a.px(v, a.y0);
    img.line({p.x(), double(a.y + a.h)}, {p.x(), double(a.y + a.h + 4)}, kInk);
    const std::string s = format(v);
    img.text(static_cast<int>(p.x()) - text_width(s, 1) / 2, a.y + a.h + 8, s, kInk, 1);
  }
  img.text(a.x + (a.w - text_width(xlabel, 1)) / 2, a.y + a.h + 24, xlabel, kInk, 1);
  img.polyline({{double(a.x), double(a.y)},
                {double(a.x + a.w), double(a.y)},
                {double(a.x + a.w), double(a.y + a.h)},
                {double(a.x), double(a.y + a.h)}},
               kInk, 1.0, true);
  return a;
}

/// A histogram panel: `values` counted into `bins` equal bins over [lo, hi].
void histogram(Canvas& img, int px, int py, int pw, int ph, const std::string& title, const std::string& xlabel,
               const std::vector<double>& values, double lo, double hi, int bins, const std::vector<double>& xticks = {}) {
  if (!(hi > lo)) hi = lo + 1;
  std::vector<int> counts(static_cast<std::size_t>(bins), 0);
  for (double v : values) {
    const int b = std::clamp(static_cast<int>(std::floor((v - lo) / (hi - lo) * bins)), 0, bins - 1);
    ++counts[static_cast<std::size_t>(b)];
  }
  const int top = std::max(1, *std::max_element(counts.begin(), counts.end()));
  const int yticks = std::min(top, 5);
  const double ymax = std::ceil(static_cast<double>(top) / yticks) * yticks;
  const Axes a = panel(img, px, py, pw, ph, title, xlabel, lo, hi, 0, ymax, xticks, yticks);
  for (int b = 0; b < bins; ++b) {
    if (counts[static_cast<std::size_t>(b)] == 0) continue;
    const Vec2 p0 = a.px(lo + (hi - lo) * b / bins, 0);
    const Vec2 p1 = a.px(lo + (hi - lo) * (b + 1) / bins, counts[static_cast<std::size_t>(b)]);
    img.fill_rect(static_cast<int>(std::lround(p0.x())) + 1, static_cast<int>(std::lround(p1.y())),
                  static_cast<int>(std::lround(p1.x())) - 1, static_cast<int>(std::lround(p0.y())), kBlue);
  }
  if (values.empty()) img.text(a.x + 10, a.y + 10, "no trials", kInk, 1);
}

/// Integer-valued data: one bin per value up to 20 bins, wider bins beyond.
void integer_histogram(Canvas& img, int px, int py, int pw, int ph, const std::string& title, const std::string& xlabel,
                       const std::vector<double>& values, int max_value) {
  const int width = std::max(1, (max_value + 20) / 20);
  const int bins = max_value / width + 1;
  // bins centred on their first value; at most about eight labels
  const int label_step = width * std::max(1, (bins + 7) / 8);
  std::vector<double> ticks;
  for (int v = 0; v < bins * width; v += label_step) ticks.push_back(v);
  histogram(img, px, py, pw, ph, title, xlabel, values, -0.5 * width, (bins - 0.5) * width, bins, ticks);
}

/// The real-time factors' histogram over their own range.
void rtf_histogram(Canvas& img, int px, int py, int pw, int ph, const std::vector<double>& rtf) {
  double lo = rtf.empty() ? 0 : *std::min_element(rtf.begin(), rtf.end());
  double hi = rtf.empty() ? 1 : *std::max_element(rtf.begin(), rtf.end());
  lo = std::floor(lo * 0.95);
  hi = std::ceil(hi * 1.05 + 1e-9);
  histogram(img, px, py, pw, ph, "real-time factor", "sim s per wall s (whole trial)", rtf, lo, hi, 10);
}

/// A batch of terrain trials (every record has `terrain`).
Canvas terrain_figure(const std::map<int, TrialRecord>& records) {
  const int pw = 400, ph = 330, top = 50;
  Canvas img(3 * pw, top + 2 * ph);
  int ok = 0, successes = 0, laps = 0, max_falls = 0, max_stuck = 0;
  std::vector<double> reps, falls, stuck, mean_time, rtf;
  const TrialTerrain* any = nullptr;
  for (const auto& [trial, r] : records) {
    successes += r.success;
    if (r.status != "ok" || !r.terrain) continue;
    ++ok;
    any = &*r.terrain;
    laps = std::max(laps, r.terrain->laps);
    max_falls = std::max(max_falls, r.terrain->falls);
    max_stuck = std::max(max_stuck, r.terrain->stuck);
    reps.push_back(r.terrain->repetitions);
    falls.push_back(r.terrain->falls);
    stuck.push_back(r.terrain->stuck);
    if (r.terrain->repetitions > 0) mean_time.push_back(r.terrain->mean_time);
    rtf.push_back(r.real_time_factor);
  }
  const int n = static_cast<int>(records.size());
  std::string what = "terrain trials";
  if (any) what += ": " + any->lane + (any->lane == any->kind ? "" : " (" + any->kind + ")") + ", " + any->robot + ", " + any->pattern;
  char counts[160];
  std::snprintf(counts, sizeof counts, "%d trials, %d failed, %d completed every repetition (%.0f%%)", n, n - ok, successes,
                n > 0 ? 100.0 * successes / n : 0.0);
  img.text((img.width() - text_width(what, 2)) / 2, 8, what, kInk, 2);
  img.text((img.width() - text_width(counts, 1)) / 2, 32, counts, kInk, 1);
  integer_histogram(img, 0, top, 2 * pw, ph, "repetitions completed", "repetitions per trial", reps, laps);
  integer_histogram(img, 2 * pw, top, pw, ph, "falls", "falls per trial", falls, max_falls);
  integer_histogram(img, 0, top + ph, pw, ph, "stuck", "stuck events per trial", stuck, max_stuck);
  double t_hi = mean_time.empty() ? 1 : *std::max_element(mean_time.begin(), mean_time.end());
  histogram(img, pw, top + ph, pw, ph, "time per repetition", "s, mean over a trial's completed ones", mean_time, 0,
            std::ceil(t_hi * 1.1 + 1e-9), 10);
  rtf_histogram(img, 2 * pw, top + ph, pw, ph, rtf);
  return img;
}

}  // namespace

Canvas batch_figure(const std::map<int, TrialRecord>& records) {
  const auto terrain_or_failed = [](const auto& kv) { return kv.second.terrain.has_value() || kv.second.status != "ok"; };
  const auto has_terrain = [](const auto& kv) { return kv.second.terrain.has_value(); };
  const bool terrain = !records.empty() && std::all_of(records.begin(), records.end(), terrain_or_failed) &&
                       std::any_of(records.begin(), records.end(), has_terrain);
  if (terrain) return terrain_figure(records);
  const int pw = 400, ph = 330, top = 50;
  Canvas img(3 * pw, top + 2 * ph);
  int ok = 0, successes = 0, max_victims = 0, max_collisions = 0;
  double t_end = 0;
  std::vector<double> found, coverage, collisions, rtf;
  std::string scenario;
  for (const auto& [trial, r] : records) {
    scenario = r.scenario;
    successes += r.success;
    if (r.status != "ok") continue;
    ++ok;
    t_end = std::max(t_end, r.sim_time);
    max_victims = std::max(max_victims, r.victims_total);
    max_collisions = std::max(max_collisions, r.collisions);
    found.push_back(r.victims_found);
    coverage.push_back(r.coverage);
    collisions.push_back(r.collisions);
    rtf.push_back(r.real_time_factor);
  }
  const int n = static_cast<int>(records.size());
  char title[256];
  std::snprintf(title, sizeof title, "batch %s: %d trials, %d failed, %d found every victim (%.0f%%)", scenario.c_str(), n, n - ok,
                successes, n > 0 ? 100.0 * successes / n : 0.0);
  img.text((img.width() - text_width(title, 2)) / 2, 16, title, kInk, 2);

  // success against time, over two panel widths
  if (t_end <= 0) t_end = 1;
  const Axes a = panel(img, 0, top, 2 * pw, ph, "share of trials done (all victims found) by sim time", "sim time (s)", 0, t_end, 0, 1);
  const int samples = 200;
  std::vector<Vec2> done_curve, victims_curve;
  for (int k = 0; k <= samples; ++k) {
    const double t = t_end * k / samples;
    int done = 0, with_victims = 0;
    double share = 0;
    for (const auto& [trial, r] : records) {
      done += r.success && r.success_time <= t;
      if (r.status != "ok" || r.victims_total == 0) continue;
      ++with_victims;
      int seen = 0;
      for (const auto& v : r.victims) seen += v.found && v.time <= t;
      share += static_cast<double>(seen) / r.victims_total;
    }
    done_curve.push_back(a.px(t, n > 0 ? static_cast<double>(done) / n : 0.0));
    victims_curve.push_back(a.px(t, with_victims > 0 ? share / with_victims : 0.0));
  }
  img.polyline(victims_curve, kOrange, 2.0);
  img.polyline(done_curve, kBlue, 2.5);
  img.fill_rect(a.x + 12, a.y + 12, a.x + 32, a.y + 16, kBlue);
  img.text(a.x + 38, a.y + 11, "trials with every victim found", kInk, 1);
  img.fill_rect(a.x + 12, a.y + 28, a.x + 32, a.y + 32, kOrange);
  img.text(a.x + 38, a.y + 27, "mean share of victims found", kInk, 1);

  integer_histogram(img, 2 * pw, top, pw, ph, "victims found", "victims per trial", found, max_victims);
  histogram(img, 0, top + ph, pw, ph, "coverage", "share of free floor", coverage, 0, 1, 10);
  integer_histogram(img, pw, top + ph, pw, ph, "collisions", "collisions per trial", collisions, max_collisions);
  rtf_histogram(img, 2 * pw, top + ph, pw, ph, rtf);
  return img;
}

}  // namespace rescuesim
