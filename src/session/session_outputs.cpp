// The files a run leaves behind: summary.json, world.svg, overview.png and the camera frames
// here; the run systems add theirs (trajectory.csv, sensors/laser.png, score.png, reports/:
// sim/run_outputs.h). Each is written atomically.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "import/svg/svg_world.h"
#include "mission/mission_system.h"
#include "sensors/camera/render_camera_service.h"
#include "session/session.h"
#include "sim/run_outputs.h"
#include "viz/world_plot.h"

namespace rescuesim {

namespace {

/// A thermal pixel (mono16, centikelvin) as grey through the sensor's mono8 window.
std::uint8_t thermal_grey(std::uint16_t v, const CameraSpec& camera) {
  const double t = (v * 0.01 - camera.mono8_min) / (camera.mono8_max - camera.mono8_min);
  return static_cast<std::uint8_t>(std::clamp(std::lround(255 * t), 0L, 255L));
}

/// The mission's part of summary.json: score, reports by outcome, victims as the referee saw
/// them, the reports' pictures, and the radio's figures (see docs/missions.md).
nlohmann::ordered_json mission_json(const MissionResult& m) {
  nlohmann::ordered_json j;
  j["rules"] = m.rules;
  j["radio_model"] = m.radio_model;
  j["score"] = m.score;
  j["victims_found"] = m.victims_found;
  j["victims"] = m.victims;
  auto& reports = j["reports"] = nlohmann::ordered_json::object();
  reports["charged"] = m.counts.charged;
  for (int o = 0; o <= static_cast<int>(ReportOutcome::invalid); ++o) {
    reports[std::string(report_outcome_name(static_cast<ReportOutcome>(o)))] = m.counts.by_outcome[o];
  }
  auto& victims = j["victim_reports"] = nlohmann::ordered_json::array();
  for (std::size_t v = 0; v < m.victim_states.size(); ++v) {
    const RefereeVictimState& s = m.victim_states[v];
    const auto or_null = [&](auto x) { return s.found ? nlohmann::ordered_json(x) : nlohmann::ordered_json(); };
    victims.push_back({{"name", m.victim_names[v]},
                       {"found", s.found},
                       {"time_s", or_null(s.time)},
                       {"by", s.found ? nlohmann::ordered_json(m.robot_names[s.by.slot()]) : nlohmann::ordered_json()},
                       {"error_m", or_null(s.error_m)}});
  }
  auto& pictures = j["report_pictures"] = nlohmann::ordered_json::array();
  for (const ReportPicture& p : m.pictures) {
    pictures.push_back(
        {{"report", p.report},
         {"robot", m.robot_names.at(p.robot.slot())},
         {"time_s", p.t},
         {"outcome", report_outcome_name(p.outcome)},
         {"victim", p.victim.valid() ? nlohmann::ordered_json(m.victim_names.at(p.victim.slot())) : nlohmann::ordered_json()},
         {"file", report_picture_file(p, m.robot_names)}});
  }
  auto& robots = j["robots"] = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < m.robot_names.size(); ++r) {
    robots.push_back({{"name", m.robot_names[r]}, {"contact_fraction", m.contact_fraction[r]}, {"relays_dropped", m.relays_dropped[r]}});
  }
  j["link_updates"] = m.link_updates;
  j["datagrams"] = {{"sent", m.datagrams_sent}, {"delivered", m.datagrams_delivered}, {"dropped", m.datagrams_dropped}};
  if (m.map) {
    j["map"] = {{"precision", m.map->precision}, {"recall", m.map->recall}, {"map_occupied", m.map->map_occupied},
                {"visible", m.map->visible}, {"stamp", m.map->stamp}, {"maps", m.map->maps}};
    if (!m.map->error.empty()) j["map"]["error"] = m.map->error;
  }
  return j;
}

nlohmann::ordered_json summary_json(const RunResult& r, const Scenario& s, const WorldSpec& w) {
  nlohmann::ordered_json j;
  j["scenario"] = r.scenario;
  j["seed"] = r.seed;
  j["world"] = w.name;
  j["world_seed"] = w.seed;
  j["sim_time_s"] = r.sim_time;
  j["wall_time_s"] = r.wall_time;
  j["real_time_factor"] = r.real_time_factor;
  j["mode"] = s.realtime ? "realtime" : "lockstep";
  j["stop_reason"] = r.stop_reason;
  j["trouble"] = r.trouble;
  j["victims_total"] = r.victims.size();
  j["victims_found"] = r.victims_found;
  j["victim_detection"] = r.victim_detection;
  auto& victims = j["victims"] = nlohmann::ordered_json::array();
  for (const auto& v : r.victims) {
    victims.push_back({{"name", v.name},
                       {"found", v.found},
                       {"time_s", v.found ? nlohmann::ordered_json(v.time) : nlohmann::ordered_json()},
                       {"by", v.by}});
  }
  j["coverage"] = r.coverage;
  j["collisions"] = r.collisions;
  j["distance_m"] = r.distance;
  auto& counts = j["message_counts"] = nlohmann::ordered_json::object();
  for (const auto& [topic, n] : r.message_counts) counts[topic] = n;
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.state_hash));
  j["state_hash"] = hash;
  if (r.mission) j["mission"] = mission_json(*r.mission);
  if (!r.explorers.empty()) {
    auto& ex = j["explorers"] = nlohmann::ordered_json::object();
    for (const auto& [name, st] : r.explorers) {
      ex[name] = {{"scans", st.scans},
                  {"plans", st.plans},
                  {"frontier_trips", st.frontier_trips},
                  {"frontiers_reached", st.frontiers_reached},
                  {"look_trips", st.look_trips},
                  {"team_frontier_trips", st.team_frontier_trips},
                  {"team_mapped_cells", st.team_mapped_cells},
                  {"stuck_no_progress", st.stuck_no_progress},
                  {"stuck_blocked", st.stuck_blocked},
                  {"stuck_looping", st.stuck_looping},
                  {"no_frontier", st.no_frontier},
                  {"path_blocked", st.path_blocked},
                  {"path_stuck", st.path_stuck},
                  {"abandoned", st.abandoned},
                  {"backups", st.backups},
                  {"slipping_scans", st.slipping_scans},
                  {"scans_matched", st.scans_matched},
                  {"scans_ambiguous", st.scans_ambiguous},
                  {"scans_unmatched", st.scans_unmatched}};
    }
  }
  return j;
}

/// A depth in metres as a colour: near red through yellow and green to far blue; black for none.
Rgb8 depth_colour(float z) {
  if (!std::isfinite(z)) return {0, 0, 0};
  const double t = std::clamp(z / 8.0, 0.0, 1.0);
  const double r = std::clamp(1.5 - std::abs(4 * t - 1), 0.0, 1.0), g = std::clamp(1.5 - std::abs(4 * t - 2), 0.0, 1.0),
               b = std::clamp(1.5 - std::abs(4 * t - 3), 0.0, 1.0);
  return {static_cast<std::uint8_t>(255 * r), static_cast<std::uint8_t>(255 * g), static_cast<std::uint8_t>(255 * b)};
}

}  // namespace

void Session::write_camera_frames(const std::filesystem::path& dir) const {
  if (!cameras_) return;
  const World& world = sim_->world();
  for (const auto& f : cameras_->last_frames()) {
    const msg::Image& m = f.image;
    Canvas img(static_cast<int>(m.width), static_cast<int>(m.height));
    for (std::uint32_t y = 0; y < m.height; ++y) {
      for (std::uint32_t x = 0; x < m.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * m.width + x;
        Rgb8 c;
        if (m.encoding == "rgb8") {
          c = {m.data[i * 3], m.data[i * 3 + 1], m.data[i * 3 + 2]};
        } else if (m.encoding == "32FC1") {
          float z;
          std::memcpy(&z, &m.data[i * 4], 4);
          c = depth_colour(z);
        } else if (m.encoding == "16UC1") {
          std::uint16_t v;
          std::memcpy(&v, &m.data[i * 2], 2);
          c = depth_colour(v == 0 ? NAN : v * 0.001f);
        } else if (m.encoding == "mono16") {
          // thermal: the mono8 window of the sensor, as grey
          std::uint16_t v;
          std::memcpy(&v, &m.data[i * 2], 2);
          const std::uint8_t g = thermal_grey(v, world.robot(f.robot).spec.find_sensor(f.sensor)->camera);
          c = {g, g, g};
        }
        img.set(static_cast<int>(x), static_cast<int>(y), c);
      }
    }
    const std::string name = (sim_->base_robots() > 1 ? world.robot(f.robot).name + "_" : std::string()) + f.sensor + ".png";
    img.write_png(dir / "sensors" / name);
  }
}

std::optional<msg::Image> Session::victim_picture(RobotIndex robot) const {
  if (!cameras_) return std::nullopt;
  const RobotSpec& spec = sim_->world().robots.at(robot.slot()).spec;
  const SensorSpec* thermal = nullptr;  // the last thermal camera, as the victim detectors take it
  for (const SensorSpec& s : spec.sensors) {
    if (s.type == SensorSpec::Type::thermal_camera && s.enabled) thermal = &s;
  }
  if (thermal == nullptr) return std::nullopt;
  const msg::Image* frame = cameras_->last_frame(robot, thermal->name);
  if (frame == nullptr || frame->encoding != "mono16") return std::nullopt;
  msg::Image grey;
  grey.header = frame->header;
  grey.width = frame->width;
  grey.height = frame->height;
  grey.encoding = "mono8";
  grey.step = grey.width;
  grey.data.resize(static_cast<std::size_t>(grey.width) * grey.height);
  for (std::size_t i = 0; i < grey.data.size(); ++i) {
    std::uint16_t v;
    std::memcpy(&v, &frame->data[i * 2], 2);
    grey.data[i] = thermal_grey(v, thermal->camera);
  }
  return grey;
}

void Session::write_outputs(const std::filesystem::path& dir, const RunResult& result) const {
  const World& world = sim_->world();
  write_file_atomic(dir / "summary.json", summary_json(result, scenario_, spec_).dump(2) + "\n");
  write_file_atomic(dir / "world.svg", world_to_svg(spec_));

  // overview: the world, then each system's layer (the explorers' maps, the robots' paths: see
  // sim/run_outputs.h), then the victims found (green ring) or missed (red cross)
  WorldPlotOptions po;
  po.title = scenario_.name + " - " + spec_.name + ", seed " + std::to_string(scenario_.seed) + ", " +
             std::to_string(result.victims_found) + "/" + std::to_string(result.victims.size()) + " victims in " +
             std::to_string(static_cast<int>(result.sim_time)) + " s";
  Canvas img = plot_world(spec_, po);
  const PlotFrame frame = plot_frame_for(spec_, po);
  RunOutputs out{dir, scenario_.name, result.sim_time, img, frame};
  for (const RunSystem* system : systems_) system->write_outputs(*sim_, out);
  for (std::size_t v = 0; v < world.victims.size() && v < result.victims.size(); ++v) {
    const Vec2 p = frame.to_px(world.victims[v].pose.position());
    if (result.victims[v].found) {
      img.circle(p, 14, {20, 170, 40}, 3.0);
    } else {
      img.line(p + Vec2(-10, -10), p + Vec2(10, 10), {220, 30, 30}, 3.0);
      img.line(p + Vec2(-10, 10), p + Vec2(10, -10), {220, 30, 30}, 3.0);
    }
  }
  img.write_png(dir / "overview.png");
  write_camera_frames(dir);
}

}  // namespace rescuesim
