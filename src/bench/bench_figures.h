#pragma once
// Small helpers of the bench parts: timing a call and a figure beside its baseline.

#include <algorithm>
#include <chrono>
#include <vector>

#include <nlohmann/json.hpp>

namespace rescuesim::bench {

/// Median wall seconds of `repeats` calls.
template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// The median of `v` (the upper one of an even count); 0 when empty.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// {value, unit, baseline, baseline_is, ratio = value / baseline}.
inline nlohmann::ordered_json ratio_figure(double value, const char* unit, double baseline, const char* baseline_is) {
  return {{"value", value},
          {"unit", unit},
          {"baseline", baseline},
          {"baseline_is", baseline_is},
          {"ratio", baseline > 0 ? value / baseline : 0.0}};
}

}  // namespace rescuesim::bench
