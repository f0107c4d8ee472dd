#include <cmath>
#include <cstdio>

#include <fmt/format.h>

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
  if (!w.terrain.empty()) {
    s += "  terrain       " + std::to_string(w.terrain.size()) + ":";
    for (const auto& t : w.terrain) s += std::string(" ") + TerrainSpec::kind_name(t.kind) + " '" + t.name + "'";
    s += "\n";
  }
  if (!w.ground.empty()) {
    s += "  ground areas  " + std::to_string(w.ground.size()) + ":";
    for (const auto& g : w.ground) s += " " + g.material + " '" + g.name + "'";
    s += "\n";
  }
  if (!w.media.empty()) {
    s += "  smoke, dust   " + std::to_string(w.media.size()) + "\n";
    for (const auto& m : w.media) {
      std::snprintf(buf, sizeof buf, "    %s '%s': %.3g /m (visibility %.3g m), %.3g-%.3g m up%s\n", MediumSpec::kind_name(m.kind),
                    m.name.c_str(), m.density, m.density > 0 ? 3.0 / m.density : INFINITY, m.bottom, m.bottom + m.height,
                    m.growth != 0 || m.drift != Vec2::Zero() ? ", growing or drifting" : "");
      s += buf;
    }
  }
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

std::string mission_summary(const MissionSpec& m, const WorldSpec& w) {
  const MissionRules& r = m.rules;
  std::string s =
      fmt::format("  mission       {} rules: victims within {:g} m, {:g} point(s) each, -{:g} per false report, {}, {:g} reports/s per "
                  "robot{}{}\n",
                  r.preset, r.report_radius_m, r.victim_points, r.false_report_penalty,
                  r.report_limit > 0 ? fmt::format("{} reports", r.report_limit) : std::string("no report limit"), r.report_rate_hz,
                  r.require_contact ? ", only in radio contact with a base" : "",
                  r.time_limit_s > 0 ? fmt::format(", until {:g} s", r.time_limit_s) : std::string());
  const RadioModel& radio = m.radio.model;
  std::string model;
  switch (radio.kind) {
    case RadioModelKind::ideal: model = "ideal (always connected)"; break;
    case RadioModelKind::wss:
      model = fmt::format("wss: {:g} dBm at {:g} m, exponent {:g}, {:g} dB per wall (at most {}), cut-off {:g} dBm", radio.wss.p0_dbm,
                          radio.wss.d0_m, radio.wss.n, radio.wss.wall_loss_db, radio.wss.max_walls, radio.wss.cutoff_dbm);
      break;
    case RadioModelKind::subt:
      model =
          fmt::format("subt: {:g} dBm out, loss {:g} dB + 10 x {:g} x log10(d), shadowing {:g} dB, floor {:g} dBm, {:g} bit/s per radio",
                      radio.subt.tx_power_dbm, radio.subt.l0_db, radio.subt.n, radio.subt.sigma_db, radio.subt.noise_floor_dbm,
                      radio.subt.capacity_bps);
      break;
  }
  s += fmt::format("  radio         {}; links at {:g} Hz, {} relays per robot\n", model, m.radio.link_rate_hz, m.radio.relays_per_robot);
  if (m.bases.empty()) {
    if (!w.robots.empty()) {
      s += fmt::format("  base          base, 1 m above {}'s start ({:.2f}, {:.2f}) m\n", w.robots[0].name, w.robots[0].start.x,
                       w.robots[0].start.y);
    }
  } else {
    for (const auto& b : m.bases)
      s += fmt::format("  base          {} at ({:.2f}, {:.2f}, {:.2f}) m\n", b.name, b.p_W.x(), b.p_W.y(), b.p_W.z());
  }
  return s;
}

void print_diagnostics(const Diagnostics& d) {
  for (const auto& item : d.items()) std::fprintf(stderr, "  %s\n", item.str().c_str());
}

}  // namespace rescuesim::app
