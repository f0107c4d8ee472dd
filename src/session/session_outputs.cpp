// The files a run leaves behind: summary.json, trajectory.csv, world.svg, overview.png,
// score.png and reports/ (with a mission) and sensors/laser.png, each written atomically.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "import/svg/svg_world.h"
#include "sensors/camera/render_camera_service.h"
#include "session/session.h"
#include "viz/world_plot.h"

namespace rescuesim {

namespace {

/// A thermal pixel (mono16, centikelvin) as grey through the sensor's mono8 window.
std::uint8_t thermal_grey(std::uint16_t v, const CameraSpec& camera) {
  const double t = (v * 0.01 - camera.mono8_min) / (camera.mono8_max - camera.mono8_min);
  return static_cast<std::uint8_t>(std::clamp(std::lround(255 * t), 0L, 255L));
}

/// Where a report's picture is written, relative to the output folder: the report's id, robot
/// and outcome ("reports/3_r1_accepted.png").
std::string picture_file(const ReportPicture& p, const std::vector<std::string>& robot_names) {
  return "reports/" + std::to_string(p.report) + "_" + robot_names.at(static_cast<std::size_t>(p.robot)) + "_" +
         std::string(report_outcome_name(p.outcome)) + ".png";
}

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
    victims.push_back({{"name", m.victim_names[v]}, {"found", s.found}, {"time_s", or_null(s.time)},
                       {"by", s.found ? nlohmann::ordered_json(m.robot_names[static_cast<std::size_t>(s.by)]) : nlohmann::ordered_json()},
                       {"error_m", or_null(s.error_m)}});
  }
  auto& pictures = j["report_pictures"] = nlohmann::ordered_json::array();
  for (const ReportPicture& p : m.pictures) {
    pictures.push_back({{"report", p.report},
                        {"robot", m.robot_names.at(static_cast<std::size_t>(p.robot))},
                        {"time_s", p.t},
                        {"outcome", report_outcome_name(p.outcome)},
                        {"victim", p.victim >= 0 ? nlohmann::ordered_json(m.victim_names.at(static_cast<std::size_t>(p.victim)))
                                                 : nlohmann::ordered_json()},
                        {"file", picture_file(p, m.robot_names)}});
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
    const Rgb8 c = e.outcome == ReportOutcome::accepted ? Rgb8{20, 170, 40}
                   : e.outcome == ReportOutcome::false_report ? Rgb8{220, 30, 30} : Rgb8{150, 150, 150};
    img.fill_circle(px(e.t, e.score), 4, c);
  }
  img.text(left, 8, title, {0, 0, 0});
  img.text(left, 22, "score (black; dots: green found, red false, grey duplicate), victims found (blue)", {90, 90, 90});
  return img;
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

std::string trajectory_csv(const std::vector<TrajectoryPoint>& traj, const World& world) {
  std::string out = "t,robot,x,y,yaw,odom_x,odom_y,odom_yaw,v,w\n";
  char line[256];
  for (const auto& p : traj) {
    std::snprintf(line, sizeof line, "%.3f,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", p.t,
                  world.robots[static_cast<std::size_t>(p.robot)].name.c_str(), p.truth.x, p.truth.y, p.truth.yaw, p.odom.x, p.odom.y,
                  p.odom.yaw, p.v, p.w);
    out += line;
  }
  return out;
}

/// A depth in metres as a colour: near red through yellow and green to far blue; black for none.
Rgb8 depth_colour(float z) {
  if (!std::isfinite(z)) return {0, 0, 0};
  const double t = std::clamp(z / 8.0, 0.0, 1.0);
  const double r = std::clamp(1.5 - std::abs(4 * t - 1), 0.0, 1.0), g = std::clamp(1.5 - std::abs(4 * t - 2), 0.0, 1.0),
               b = std::clamp(1.5 - std::abs(4 * t - 3), 0.0, 1.0);
  return {static_cast<std::uint8_t>(255 * r), static_cast<std::uint8_t>(255 * g), static_cast<std::uint8_t>(255 * b)};
}

/// A polar plot of a laser scan: the robot at the centre, 1 m rings, returns as dots.
Canvas laser_plot(const msg::LaserScan& scan, const std::string& title) {
  const int size = 520, c = size / 2;
  Canvas img(size, size + 24, {255, 255, 255});
  const double max_r = std::min<double>(scan.range_max > 0 ? scan.range_max : 10.0, 10.0);
  const double scale = (size / 2 - 20) / max_r;
  for (int ring = 1; ring <= static_cast<int>(max_r); ++ring) img.circle({c, c}, ring * scale, {225, 225, 225}, 1.0);
  img.line({c - 10.0, double(c)}, {c + 10.0, double(c)}, {150, 150, 150});
  img.line({double(c), c - 10.0}, {double(c), c + 10.0}, {150, 150, 150});
  // x forward points up the image, y left points left
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const Vec2 dir(-std::sin(a), -std::cos(a));
    const float r = scan.ranges[i];
    if (std::isfinite(r)) {
      img.line({double(c), double(c)}, Vec2(c, c) + dir * r * scale, {200, 225, 255}, 1.0, 0.5);
      img.fill_circle(Vec2(c, c) + dir * r * scale, 1.8, {200, 30, 30});
    }
  }
  img.fill_circle({double(c), double(c)}, 5, {44, 160, 44});
  img.text(8, size + 6, title + "  (rings 1 m)", {0, 0, 0}, 1);
  return img;
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
          const std::uint8_t g = thermal_grey(v, world.robots[static_cast<std::size_t>(f.robot)].spec.find_sensor(f.sensor)->camera);
          c = {g, g, g};
        }
        img.set(static_cast<int>(x), static_cast<int>(y), c);
      }
    }
    const std::string name =
        (sim_->base_robots() > 1 ? world.robots[static_cast<std::size_t>(f.robot)].name + "_" : std::string()) + f.sensor + ".png";
    img.write_png(dir / "sensors" / name);
  }
}

std::optional<msg::Image> Session::victim_picture(int robot) const {
  if (!cameras_) return std::nullopt;
  const RobotSpec& spec = sim_->world().robots.at(static_cast<std::size_t>(robot)).spec;
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
  write_file_atomic(dir / "trajectory.csv", trajectory_csv(recorder_->trajectory(), world));
  write_file_atomic(dir / "world.svg", world_to_svg(spec_));

  // overview: the world, each robot's laser map (its map frame placed at its start), its
  // path, and the victims found (green ring) or missed (red cross)
  WorldPlotOptions po;
  po.title = scenario_.name + " - " + spec_.name + ", seed " + std::to_string(scenario_.seed) + ", " +
             std::to_string(result.victims_found) + "/" + std::to_string(result.victims.size()) + " victims in " +
             std::to_string(static_cast<int>(result.sim_time)) + " s";
  Canvas img = plot_world(spec_, po);
  const PlotFrame frame = plot_frame_for(spec_, po);
  for (std::size_t r = 0; r < controllers_->size(); ++r) {
    const autonomy::Explorer* ex = controllers_->explorer(r);
    if (!ex) continue;
    const msg::OccupancyGrid map = ex->map(sim_->time());
    const Pose2 X_WM = controllers_->X_WO(r);  // the map frame starts on the odom frame
    const Pose2 X_MG = map.origin.to_pose2();  // the grid's corner in the map frame
    for (std::uint32_t y = 0; y < map.height; ++y) {
      for (std::uint32_t x = 0; x < map.width; ++x) {
        const std::int8_t v = map.data[y * map.width + x];
        if (v < 65) continue;
        const Vec2 p_W = (X_WM * X_MG).transform({(x + 0.5) * map.resolution, (y + 0.5) * map.resolution});
        img.fill_circle(frame.to_px(p_W), std::max(1.0, 0.5 * map.resolution * frame.px_per_m), {90, 110, 200}, 0.6);
      }
    }
  }
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    std::vector<Vec2> path;
    for (const auto& p : recorder_->trajectory()) {
      if (p.robot == static_cast<int>(r)) path.push_back(frame.to_px(p.truth.position()));
    }
    img.polyline(path, {20, 160, 60}, 2.0);
    if (!path.empty()) img.fill_circle(path.back(), 5, {20, 120, 40});
  }
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
  if (result.mission) {
    const MissionResult& m = *result.mission;
    char title[160];
    std::snprintf(title, sizeof title, "%s: score %g, %d/%d victims, %llu false (%s rules, %s radio)", scenario_.name.c_str(), m.score,
                  m.victims_found, m.victims, static_cast<unsigned long long>(m.counts[ReportOutcome::false_report]), m.rules.c_str(),
                  m.radio_model.c_str());
    score_plot(m, result.sim_time, title).write_png(dir / "score.png");
    for (const ReportImage& p : mission_->report_images()) picture_canvas(p.image).write_png(dir / picture_file(p.about, m.robot_names));
  }

  write_camera_frames(dir);
  const std::vector<msg::LaserScan>& last_scans = recorder_->last_scans();
  for (std::size_t r = 0; r < last_scans.size(); ++r) {
    if (last_scans[r].ranges.empty()) continue;
    const std::string name = sim_->base_robots() > 1 ? "laser_" + world.robots[r].name + ".png" : "laser.png";
    char t[64];
    std::snprintf(t, sizeof t, "%.1f s", last_scans[r].header.stamp.seconds());
    laser_plot(last_scans[r], world.robots[r].name + " laser at " + t).write_png(dir / "sensors" / name);
  }
}

}  // namespace rescuesim
