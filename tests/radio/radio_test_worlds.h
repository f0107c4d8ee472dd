#pragma once
// Small worlds for the radio tests: an open floor with thin walls across the x axis.

#include <vector>

#include "world/world.h"

namespace rescuesim::radio_test {

/// A floor from (x_min, −8) to (x_max, 8) with walls 0.1 m thick and 1 m high across the x
/// axis, centred at each x in `wall_x`, reaching from y = −5 to y = 5.
inline World walls_across_x(const std::vector<double>& wall_x, double x_min = -2, double x_max = 12) {
  WorldSpec s;
  s.name = "radio_test";
  s.materials = default_materials();
  s.floor_min = {x_min, -8};
  s.floor_max = {x_max, 8};
  for (double x : wall_x) s.walls.push_back(WallSpec{{x, -5}, {x, 5}, 0.1, 1.0, "wall", {}});
  return compile_world(s, {});
}

}  // namespace rescuesim::radio_test
