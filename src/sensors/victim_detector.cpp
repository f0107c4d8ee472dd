#include "sensors/victim_detector.h"

#include <cmath>

namespace rescuesim {

void LineOfSightDetector::check(const World& world, State& state, const RayScene& rays) const {
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    if (!robots_.empty() && (r >= robots_.size() || !robots_[r])) continue;
    const RobotSpec& spec = world.robots[r].spec;
    // a victim is seen when it is in the thermal camera's view, in range, and not hidden
    const SensorSpec* cam = nullptr;
    for (const auto& s : spec.sensors) {
      if (s.type == SensorSpec::Type::thermal_camera) cam = &s;
    }
    if (!cam) continue;
    const int link = spec.link_index(cam->link);
    const Pose3 X_WC = state.robots[r].X_WL[static_cast<std::size_t>(link)] * cam->X_LS;
    const double tan_h = std::tan(cam->camera.hfov / 2);
    const double tan_v = tan_h * cam->camera.height / cam->camera.width;
    for (std::size_t v = 0; v < world.victims.size(); ++v) {
      VictimState& vs = state.victims[v];
      if (vs.seen_by_robot(r)) continue;
      for (int part : world.victims[v].parts) {
        const Vec3 p_W = world.statics[static_cast<std::size_t>(part)].X_WO.p;
        const Vec3 p_C = X_WC.inverse() * p_W;
        if (p_C.x() <= cam->camera.min_range || p_C.x() > cam->camera.max_range) continue;
        if (std::abs(p_C.y()) > tan_h * p_C.x() || std::abs(p_C.z()) > tan_v * p_C.x()) continue;
        const Vec3 d = p_W - X_WC.p;
        Ray ray{X_WC.p, d.normalized(), static_cast<float>(d.norm() + 0.05)};
        RayHit hit;
        rays.cast({&ray, 1}, {&hit, 1}, RobotIndex::at(r));
        if (hit.source == RayHit::Source::static_object &&
            world.statics[static_cast<std::size_t>(hit.index)].victim == VictimIndex::at(v)) {
          vs.saw(r, world.robots.size(), world.robots[r].name, state.time);
          break;
        }
      }
    }
  }
}

// the robots left to line of sight are those whose thermal camera is not rendered
static std::vector<bool> not_rendered(const std::vector<bool>& rendered) {
  std::vector<bool> out(rendered.size());
  for (std::size_t r = 0; r < rendered.size(); ++r) out[r] = !rendered[r];
  return out;
}

ThermalImageDetector::ThermalImageDetector(const std::vector<bool>& rendered) : fallback_(not_rendered(rendered)) {}

void ThermalImageDetector::check(const World& world, State& state, const RayScene& rays) const {
  fallback_.check(world, state, rays);
}

}  // namespace rescuesim
