#include <cmath>
#include <cstdio>

#include "app/commands.h"

namespace rescuesim::app {

std::string world_summary(const WorldSpec& w) {
  const Vec2 size = w.floor_max - w.floor_min;
  double wall_length = 0;
  for (const auto& wall : w.walls) wall_length += (wall.b - wall.a).norm();
  int ramps = 0;
  for (const auto& r : w.raised_areas) ramps += static_cast<int>(r.ramp_edges.size());
  int lying = 0;
  for (const auto& v : w.victims) lying += v.posture == VictimSpec::Posture::lying;
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "  size          %.2f x %.2f m\n", size.x(), size.y());
  s += buf;
  std::snprintf(buf, sizeof buf, "  walls         %zu (%.1f m in all)\n", w.walls.size(), wall_length);
  s += buf;
  std::snprintf(buf, sizeof buf, "  obstacles     %zu\n", w.blocks.size());
  s += buf;
  std::snprintf(buf, sizeof buf, "  raised areas  %zu (%d ramps)\n", w.raised_areas.size(), ramps);
  s += buf;
  std::snprintf(buf, sizeof buf, "  victims       %zu (%d lying, %zu sitting)\n", w.victims.size(), lying, w.victims.size() - lying);
  s += buf;
  std::snprintf(buf, sizeof buf, "  rubble        %zu\n", w.rubble.size());
  s += buf;
  if (!w.solids.empty() || !w.bodies.empty()) {
    std::size_t meshes = 0, triangles = 0;
    for (const auto& so : w.solids) {
      if (so.geometry.type != Geometry::Type::mesh) continue;
      ++meshes;
      triangles += so.geometry.mesh.triangles.size();
    }
    std::snprintf(buf, sizeof buf, "  model solids  %zu (%zu exact meshes, %zu triangles)\n", w.solids.size(), meshes, triangles);
    s += buf;
    std::snprintf(buf, sizeof buf, "  model bodies  %zu\n", w.bodies.size());
    s += buf;
  }
  std::snprintf(buf, sizeof buf, "  robot starts  %zu\n", w.robots.size());
  s += buf;
  for (const auto& r : w.robots) {
    std::snprintf(buf, sizeof buf, "    %s (%s) at (%.2f, %.2f) m heading %.0f deg\n", r.name.c_str(), r.model.c_str(), r.start.x,
                  r.start.y, r.start.yaw * 180.0 / M_PI);
    s += buf;
  }
  if (w.seed != 0 || !w.metadata.empty()) {
    std::snprintf(buf, sizeof buf, "  seed          %llu\n", static_cast<unsigned long long>(w.seed));
    s += buf;
  }
  return s;
}

void print_diagnostics(const Diagnostics& d) {
  for (const auto& item : d.items()) std::fprintf(stderr, "  %s\n", item.str().c_str());
}

}  // namespace rescuesim::app
