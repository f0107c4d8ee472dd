#include "mission/mission.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "mission/datagram_json.h"
#include "sim/simulation.h"

namespace rescuesim {

namespace {

constexpr double kStatusRate = 1.0;  // Hz of /<robot>/rescue/comms/status

std::vector<RefereeVictim> referee_victims(const World& world) {
  std::vector<RefereeVictim> out;
  for (const auto& v : world.victims) out.push_back({v.name, v.centre});
  return out;
}

RadioNetworkOptions network_options(const MissionSpec& spec) {
  RadioNetworkOptions o;
  o.relays_per_robot = spec.radio.relays_per_robot;
  return o;
}

std::int64_t period_ns(double hz) { return std::max<std::int64_t>(1, std::llround(1e9 / hz)); }

/// A finite double for JSON (NaN and ±inf have no JSON form): null instead.
nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

std::string image_problem(const msg::Image& im) {
  int channels = 0;
  if (im.encoding == "rgb8" || im.encoding == "bgr8") channels = 3;
  if (im.encoding == "rgba8" || im.encoding == "bgra8") channels = 4;
  if (im.encoding == "mono8") channels = 1;
  if (channels == 0) return "encoding '" + im.encoding.substr(0, 32) + "': a report's picture is rgb8, bgr8, rgba8, bgra8 or mono8";
  constexpr std::uint32_t kMaxSide = 4096;
  if (im.width == 0 || im.height == 0 || im.width > kMaxSide || im.height > kMaxSide) {
    return "a picture of " + std::to_string(im.width) + " x " + std::to_string(im.height) + " pixels: each side must be 1 to 4096";
  }
  if (im.step < im.width * static_cast<std::uint32_t>(channels)) {
    return "step " + std::to_string(im.step) + " is shorter than a row of " + std::to_string(im.width) + " " + im.encoding + " pixels";
  }
  if (im.data.size() != static_cast<std::size_t>(im.step) * im.height) {
    return std::to_string(im.data.size()) +
           " bytes of data, expected step x height = " + std::to_string(static_cast<std::size_t>(im.step) * im.height);
  }
  return {};
}

Mission::Mission(const MissionSpec& spec, Simulation& sim)
    : spec_(spec),
      sim_(sim),
      referee_(spec.rules, referee_victims(sim.world()), static_cast<int>(sim.world().robots.size())),
      network_(spec.radio.model, sim.seed(), network_options(spec)) {
  const World& world = sim_.world();
  if (world.robots.empty()) throw Error("a mission needs at least one robot");
  const std::vector<Vec3> robots = radio_positions();
  for (RobotIndex r : world.robot_indices()) {
    robot_nodes_.push_back(network_.add_node(world.robot(r).name, RadioNodeKind::robot, robots[r.slot()]));
  }
  std::vector<BaseStationSpec> bases = spec_.bases;
  if (bases.empty()) {
    BaseStationSpec b;
    b.p_W = world.robots[0].X_W_start.p + Vec3(0, 0, 1.0);
    bases.push_back(b);
    spec_.bases = bases;
  }
  for (const auto& b : bases) {
    if (network_.find(b.name)) throw Error("mission base '" + b.name + "' has the name of a robot or another base");
    base_nodes_.push_back(network_.add_node(b.name, RadioNodeKind::base, b.p_W));
  }
  in_contact_updates_.assign(world.robots.size(), 0);
  in_contact_.assign(world.robots.size(), false);
  last_report_.assign(world.robots.size(), std::nullopt);
  waiting_image_.assign(world.robots.size(), std::nullopt);

  Bus& bus = sim_.bus();
  score_topic_ = bus.advertise("/rescue/score", "std_msgs/String", 0, true);
  for (RobotIndex ri : world.robot_indices()) {
    result_topics_.push_back(bus.advertise(sim_.topic_name(ri, "rescue/report_result"), "std_msgs/String", 0, false, ri));
    status_topics_.push_back(bus.advertise(sim_.topic_name(ri, "rescue/comms/status"), "std_msgs/String", kStatusRate, false, ri));
    inbox_topics_.push_back(bus.advertise(sim_.topic_name(ri, "rescue/comms/inbox"), "std_msgs/String", 0, false, ri));
    comms_result_topics_.push_back(bus.advertise(sim_.topic_name(ri, "rescue/comms/result"), "std_msgs/String", 0, false, ri));
  }
  add_inputs();
  update_links();
  next_link_ns_ = sim_.time().ns + period_ns(spec_.radio.link_rate_hz);
  next_status_ns_ = sim_.time().ns;
  publish_score();
}

std::vector<Vec3> Mission::radio_positions() const {
  const State& s = sim_.state();
  std::vector<Vec3> out;
  // the scenario's robots: the team (robots spawned while running carry no radio)
  const std::size_t robots = std::min(s.robots.size(), sim_.base_robots());
  for (std::size_t r = 0; r < robots; ++r) out.push_back(s.robots[r].base.X_WB.p + Vec3(0, 0, spec_.radio.antenna_height_m));
  return out;
}

void Mission::update_links() {
  const std::vector<Vec3> robots = radio_positions();
  for (RobotIndex r : indices<RobotTag>(robots.size())) network_.set_position(robot_nodes_[r], robots[r.slot()]);
  if (spec_.radio.model.kind == RadioModelKind::wss) {
    const WallCounter walls(sim_.ray_scene(), sim_.world());
    network_.update(&walls);
  } else {
    network_.update();
  }
  for (RobotIndex r : indices<RobotTag>(robots.size())) {
    const bool c = network_.status(robot_nodes_[r]).hops_to_base.has_value();
    in_contact_[r.slot()] = c;
    if (c) ++in_contact_updates_[r.slot()];
  }
}

void Mission::after_step() {
  const std::int64_t now = sim_.time().ns;
  if (now >= next_link_ns_) {
    // datagrams queued since the last update go along the routes of that update, then links move on
    const double dt = static_cast<double>(period_ns(spec_.radio.link_rate_hz)) * 1e-9;
    std::vector<std::size_t> before;
    for (RadioNodeIndex node : robot_nodes_) before.push_back(network_.inbox(node).size());
    network_.deliver(dt);
    publish_inboxes(before);
    update_links();
    update_visible();
    while (next_link_ns_ <= now) next_link_ns_ += period_ns(spec_.radio.link_rate_hz);
  }
  if (now >= next_status_ns_) {
    publish_status();
    while (next_status_ns_ <= now) next_status_ns_ += period_ns(kStatusRate);
  }
}

bool Mission::in_contact(RobotIndex robot) const { return in_contact_.at(robot.slot()); }

ReportReply Mission::report(RobotIndex robot, const Vec3& p_W) {
  ReportReply reply = judge(robot, p_W);
  publish_reply(robot, reply, p_W);
  return reply;
}

ReportReply Mission::report(RobotIndex robot, const Vec3& p_W, msg::Image image) {
  ReportReply reply = judge(robot, p_W);
  if (const std::string problem = keep_image(robot, reply, std::move(image)); !problem.empty()) {
    reply.message += "; its picture was not kept: " + problem;
  } else {
    reply.message += "; with its picture";
  }
  publish_reply(robot, reply, p_W);
  return reply;
}

ReportReply Mission::judge(RobotIndex robot, const Vec3& p_W) {
  VictimReport r;
  r.robot = robot;
  r.p_W = p_W;
  r.time = sim_.time();
  r.in_contact = robot_nodes_.contains(robot) && in_contact_[robot.slot()];
  const double before = referee_.score();
  const std::uint64_t charged = referee_.counts().charged;
  ReportReply reply = referee_.judge(r);
  if (referee_.score() != before || referee_.counts().charged != charged) publish_score();
  return reply;
}

std::string Mission::keep_image(RobotIndex robot, const ReportReply& reply, msg::Image image) {
  if (std::string problem = image_problem(image); !problem.empty()) return problem;
  if (report_image_bytes_ + image.data.size() > kReportImageBytes) {
    return "the run keeps at most " + std::to_string(kReportImageBytes >> 20) + " MiB of report pictures, and has " +
           std::to_string(report_image_bytes_ >> 20) + " MiB";
  }
  report_image_bytes_ += image.data.size();
  report_images_.push_back({{reply.id, robot, sim_.time().seconds(), reply.outcome, reply.victim}, std::move(image)});
  return {};
}

std::string Mission::report_image(RobotIndex robot, msg::Image image) {
  const auto r = robot.slot();
  std::string problem = image_problem(image);
  std::optional<LastReport>& last = last_report_.at(r);
  if (problem.empty() && last && !last->has_image && last->stamp == image.header.stamp) {
    const std::uint64_t id = last->reply.id;
    problem = keep_image(robot, last->reply, std::move(image));
    if (problem.empty()) last->has_image = true;
    publish_image_result(robot, id, problem);
    return problem;
  }
  if (problem.empty()) {
    waiting_image_[r] = std::move(image);
  } else {
    publish_image_result(robot, 0, problem);
  }
  return problem;
}

void Mission::publish_image_result(RobotIndex robot, std::uint64_t report, const std::string& problem) {
  nlohmann::json j;
  j["request"] = "report_image";
  j["accepted"] = problem.empty();
  j["id"] = report > 0 ? nlohmann::json(report) : nlohmann::json(nullptr);
  if (!problem.empty()) j["reason"] = problem;
  j["stamp"] = sim_.time().seconds();
  sim_.bus().publish(result_topics_.at(robot), msg::String{j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)});
}

void Mission::publish_reply(RobotIndex robot, const ReportReply& reply, const Vec3& p_W) {
  if (result_topics_.contains(robot)) {
    nlohmann::json j;
    j["id"] = reply.id;
    j["outcome"] = std::string(report_outcome_name(reply.outcome));
    j["victim"] = reply.victim.valid() ? nlohmann::json(referee_.victims()[reply.victim.slot()].name) : nlohmann::json(nullptr);
    j["distance"] = reply.distance_m >= 0 ? nlohmann::json(reply.distance_m) : nlohmann::json(nullptr);
    j["position"] = {number_or_null(p_W.x()), number_or_null(p_W.y()), number_or_null(p_W.z())};
    j["score_change"] = reply.score_change;
    j["score"] = reply.score;
    j["reports_left"] = reply.reports_left;
    j["message"] = reply.message;
    j["stamp"] = sim_.time().seconds();
    sim_.bus().publish(result_topics_[robot], msg::String{j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)});
  }
}

void Mission::publish_comms_result(RobotIndex robot, const std::string& json) {
  sim_.bus().publish(comms_result_topics_.at(robot), msg::String{json});
}

void Mission::publish_inboxes(const std::vector<std::size_t>& before) {
  for (RobotIndex r : robot_nodes_.indices()) {
    const RadioNodeIndex node = robot_nodes_[r];
    const std::vector<Datagram>& inbox = network_.inbox(node);
    for (std::size_t i = before[r.slot()]; i < inbox.size(); ++i) {
      const Datagram& d = inbox[i];
      InboxEntry e;
      e.seq = d.seq;
      e.from = network_.node(d.from).id;
      e.to = d.to == kRadioBroadcast ? std::string("*") : network_.node(d.to).id;
      e.hops = d.hops();
      e.sent = d.sent.seconds();
      e.delivered = d.delivered.seconds();
      e.bytes = &d.bytes;
      sim_.bus().publish(inbox_topics_[r], msg::String{inbox_json(e)});
    }
    // nobody may ever take them (a ROS team reads the topic): keep only the newest
    if (inbox.size() > kInboxKeep) network_.trim_inbox(node, kInboxKeep);
  }
  // nor a base's (datagrams "to base" from a ROS team, with no built-in team to read them)
  for (RadioNodeIndex node : base_nodes_) {
    if (network_.inbox(node).size() > kInboxKeep) network_.trim_inbox(node, kInboxKeep);
  }
}

void Mission::add_inputs() {
  for (RobotIndex ri : robot_nodes_.indices()) {
    sim_.add_input({sim_.topic_name(ri, "rescue/report"), "geometry_msgs/PoseStamped", ri}, [this, ri](const msg::Message& m) {
      const auto& pose = std::get<msg::PoseStamped>(m);
      const Vec3 p = pose.pose.p;
      const std::string& frame = pose.header.frame_id;
      if (!frame.empty() && frame != "map") {
        ReportReply reply;
        reply.outcome = ReportOutcome::invalid;
        reply.score = referee_.score();
        reply.reports_left = referee_.reports_left();
        reply.message = "frame_id '" + frame + "': reports are positions in the map frame (\"map\", or empty); not judged, not charged";
        publish_reply(ri, reply, p);
        return;
      }
      // a picture that came first with this stamp goes with it
      std::optional<msg::Image>& waiting = waiting_image_[ri.slot()];
      const bool paired = waiting && waiting->header.stamp == pose.header.stamp;
      ReportReply reply;
      if (paired) {
        reply = report(ri, p, std::move(*waiting));
        waiting.reset();
      } else {
        reply = report(ri, p);
      }
      last_report_[ri.slot()] = LastReport{pose.header.stamp, reply, paired};
    });
    sim_.add_input({sim_.topic_name(ri, "rescue/report_image"), "sensor_msgs/Image", ri},
                   [this, ri](const msg::Message& m) { report_image(ri, std::get<msg::Image>(m)); });
    sim_.add_input({sim_.topic_name(ri, "rescue/comms/send"), "std_msgs/String", ri}, [this, ri](const msg::Message& m) {
      nlohmann::json j;
      j["request"] = "send";
      j["stamp"] = sim_.time().seconds();
      try {
        SendRequest req = parse_send_request(std::get<msg::String>(m).data);
        j["to"] = req.to;
        j["bytes"] = req.bytes.size();
        const SendResult res = send(ri, req.to, std::move(req.bytes));
        j["accepted"] = res.accepted;
        if (res.accepted) j["seq"] = res.seq;
        if (!res.accepted) j["reason"] = res.reason;
      } catch (const Error& e) {
        j["accepted"] = false;
        j["reason"] = e.message();
      }
      publish_comms_result(ri, j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    });
    sim_.add_input({sim_.topic_name(ri, "rescue/drop_relay"), "std_msgs/String", ri}, [this, ri](const msg::Message&) {
      const RelayResult res = drop_relay(ri);
      nlohmann::json j;
      j["request"] = "drop_relay";
      j["stamp"] = sim_.time().seconds();
      j["accepted"] = res.ok();
      if (res.ok()) {
        j["relay"] = network_.node(res.node).id;
        const Vec3 p = network_.node(res.node).p_W;
        j["position"] = {p.x(), p.y(), p.z()};
      } else {
        j["reason"] = res.reason;
      }
      j["relays_left"] = network_.relays_left(robot_node(ri));
      publish_comms_result(ri, j.dump());
    });
  }
}

SendResult Mission::send(RobotIndex robot, std::string_view to, std::vector<std::uint8_t> bytes) {
  if (!robot_nodes_.contains(robot)) return {false, 0, "no robot " + std::to_string(robot.value())};
  RadioNodeIndex dest = kRadioBroadcast;
  if (to != "*") {
    const auto n = network_.find(to);
    if (!n) return {false, 0, "no radio called '" + std::string(to) + "' (robots, bases and '*' for every neighbour)"};
    dest = *n;
  }
  return network_.send(robot_nodes_[robot], dest, std::move(bytes));
}

std::vector<Datagram> Mission::take_inbox(RobotIndex robot) { return network_.take_inbox(robot_node(robot)); }

std::vector<Datagram> Mission::take_base_inbox(std::size_t index) { return network_.take_inbox(base_nodes_.at(index)); }

RadioStatus Mission::status(RobotIndex robot) const { return network_.status(robot_node(robot)); }

RelayResult Mission::drop_relay(RobotIndex robot) {
  const RadioNodeIndex node = robot_node(robot);
  return network_.add_relay(node, network_.node(node).p_W);
}

void Mission::publish_score() {
  nlohmann::json j;
  j["score"] = referee_.score();
  j["victims_found"] = referee_.victims_found();
  j["victims"] = referee_.victim_count();
  j["false_reports"] = referee_.counts()[ReportOutcome::false_report];
  j["reports"] = referee_.counts().charged;
  j["reports_left"] = referee_.reports_left();
  j["elapsed"] = sim_.time().seconds();
  sim_.bus().publish(score_topic_, msg::String{j.dump()});
}

void Mission::publish_status() {
  for (RobotIndex r : robot_nodes_.indices()) {
    const RadioNodeIndex node = robot_nodes_[r];
    const RadioStatus st = network_.status(node);
    nlohmann::json j;
    j["stamp"] = sim_.time().seconds();
    j["in_contact"] = in_contact_[r.slot()];
    j["hops_to_base"] = st.hops_to_base ? nlohmann::json(*st.hops_to_base) : nlohmann::json(nullptr);
    nlohmann::json nb = nlohmann::json::array();
    for (const auto& n : st.neighbours) {
      nb.push_back(
          {{"id", network_.node(n.node).id}, {"rssi_dbm", number_or_null(n.rssi_dbm)}, {"margin_db", number_or_null(n.margin_db)}});
    }
    j["neighbours"] = nb;
    j["bytes_sent"] = st.bytes_sent;
    j["bytes_received"] = st.bytes_received;
    j["bytes_dropped"] = st.bytes_dropped;
    j["datagrams_dropped"] = st.datagrams_dropped;
    j["relays_left"] = network_.relays_left(node);
    sim_.bus().publish(status_topics_[r], msg::String{j.dump()});
  }
}

MissionResult Mission::result() const {
  MissionResult m;
  m.rules = spec_.rules.preset;
  m.radio_model = std::string(radio_model_name(spec_.radio.model.kind));
  m.score = referee_.score();
  m.victims_found = referee_.victims_found();
  m.victims = referee_.victim_count();
  m.counts = referee_.counts();
  m.timeline = referee_.timeline();
  for (const auto& v : referee_.victims()) m.victim_names.push_back(v.name);
  m.victim_states = referee_.victim_states();
  m.link_updates = network_.update_count();
  for (RobotIndex r : robot_nodes_.indices()) {
    m.robot_names.push_back(network_.node(robot_nodes_[r]).id);
    m.contact_fraction.push_back(m.link_updates ? static_cast<double>(in_contact_updates_[r.slot()]) / static_cast<double>(m.link_updates)
                                                : 0.0);
    m.relays_dropped.push_back(spec_.radio.relays_per_robot - network_.relays_left(robot_nodes_[r]));
  }
  for (RadioNodeIndex n : network_.node_indices()) {
    const RadioStatus st = network_.status(n);
    m.datagrams_sent += st.datagrams_sent;
    m.datagrams_delivered += st.datagrams_received;
  }
  m.datagrams_dropped = network_.dropped(RadioDropReason::no_route) + network_.dropped(RadioDropReason::capacity);
  m.map = map_score_;
  for (const ReportImage& p : report_images_) m.pictures.push_back(p.about);
  return m;
}

Mission::Memory Mission::save() const {
  return Memory{referee_,  network_,    in_contact_updates_, in_contact_,   next_link_ns_,  next_status_ns_,     visible_,
                seen_from_, map_score_, last_report_,        waiting_image_, report_images_, report_image_bytes_};
}

void Mission::load(const Memory& m) {
  referee_ = m.referee;
  network_ = m.network;
  in_contact_updates_ = m.in_contact_updates;
  in_contact_ = m.in_contact;
  next_link_ns_ = m.next_link_ns;
  next_status_ns_ = m.next_status_ns;
  visible_ = m.visible;
  seen_from_ = m.seen_from;
  map_score_ = m.map_score;
  last_report_ = m.last_report;
  waiting_image_ = m.waiting_image;
  report_images_ = m.report_images;
  report_image_bytes_ = m.report_image_bytes;
}

void Mission::enable_map_scoring(const WorldSpec& world) {
  RS_DEMAND(!map_truth_, "Mission::enable_map_scoring called twice");
  constexpr double kResolution = 0.05;  // m, as the built-in explorer's maps
  auto t = std::make_shared<MapTruth>();
  const World& w = sim_.world();
  double laser_height = 0.3;
  for (std::size_t r = 0; r < w.robots.size(); ++r) {
    map_eval::LaserModel laser;
    bool found = false;
    for (const auto& sensor : w.robots[r].spec.sensors) {
      if (sensor.type != SensorSpec::Type::lidar || sensor.link != "base_link") continue;
      laser.X_BL = {sensor.X_LS.p.x(), sensor.X_LS.p.y(), sensor.X_LS.yaw()};
      laser.min_angle = sensor.lidar.min_angle;
      laser.max_angle = sensor.lidar.max_angle;
      laser.beams = sensor.lidar.samples;
      laser.max_range = sensor.lidar.max_range;
      // the scan plane above the floor: base_link's height at the start plus the mount
      if (r == 0) laser_height = w.robots[r].X_W_start.p.z() + sensor.X_LS.p.z();
      found = true;
      break;
    }
    t->lasers.push_back(laser);
    t->has_laser.push_back(found);
  }
  t->truth = map_eval::true_occupancy(world, kResolution, laser_height);
  t->ignore = map_eval::ignore_mask(world, t->truth, 0.3);
  visible_ = t->truth;
  std::fill(visible_.cells.begin(), visible_.cells.end(), 0);
  seen_from_.assign(w.robots.size(), std::nullopt);
  map_truth_ = std::move(t);
  map_score_topic_ = sim_.bus().advertise("/rescue/map_score", "std_msgs/String", 0, true);
  sim_.add_input({"/rescue/map", "nav_msgs/OccupancyGrid", {}},
                 [this](const msg::Message& m) { score_map(std::get<msg::OccupancyGrid>(m)); });
  update_visible();
}

void Mission::update_visible() {
  if (!map_truth_) return;
  const State& s = sim_.state();
  for (std::size_t r = 0; r < s.robots.size() && r < map_truth_->lasers.size(); ++r) {
    if (!map_truth_->has_laser[r]) continue;
    const Pose2 X_WB = s.robots[r].base.X_WB.to_pose2();
    const auto& last = seen_from_[r];
    if (last && (X_WB.position() - last->position()).norm() < 0.2 && std::abs(wrap_angle(X_WB.yaw - last->yaw)) < 0.3) continue;
    map_eval::add_visible(visible_, map_truth_->truth, X_WB, map_truth_->lasers[r]);
    seen_from_[r] = X_WB;
  }
}

MapScoreResult Mission::score_map(const msg::OccupancyGrid& map) {
  MapScoreResult out;
  out.stamp = sim_.time().seconds();
  out.maps = (map_score_ ? map_score_->maps : 0) + 1;
  nlohmann::json j;
  j["stamp"] = out.stamp;
  j["maps"] = out.maps;
  try {
    if (!map_truth_) throw Error("map scoring is off (Mission::enable_map_scoring)");
    if (!map.header.frame_id.empty() && map.header.frame_id != "map") {
      throw Error("map: frame_id '" + map.header.frame_id + "': maps are scored in the map frame (\"map\", or empty)");
    }
    const Pose2 X_WM = map.origin.to_pose2();
    if (!std::isfinite(X_WM.x) || !std::isfinite(X_WM.y) || !std::isfinite(X_WM.yaw)) throw Error("map: the origin is not finite");
    const map_eval::Grid grid =
        map_eval::grid_from_occupancy(static_cast<int>(map.width), static_cast<int>(map.height), map.resolution, map.data);
    const map_eval::MapScore sc = map_eval::score_map(grid, X_WM, map_truth_->truth, visible_, map_truth_->ignore);
    out.precision = sc.precision;
    out.recall = sc.recall;
    out.map_occupied = sc.map_occupied;
    out.map_matched = sc.map_matched;
    out.visible = sc.visible;
    out.visible_matched = sc.visible_matched;
    j["precision"] = out.precision;
    j["recall"] = out.recall;
    j["map_occupied"] = out.map_occupied;
    j["map_matched"] = out.map_matched;
    j["visible"] = out.visible;
    j["visible_matched"] = out.visible_matched;
    j["tolerance_m"] = map_truth_->truth.resolution;
  } catch (const Error& e) {
    out.error = e.message();
    // a refused map does not replace the score of the last good one
    if (map_score_) {
      MapScoreResult kept = *map_score_;
      kept.maps = out.maps;
      kept.error = out.error;
      out = kept;
    }
    j["error"] = e.message();
  }
  map_score_ = out;
  if (map_score_topic_ != kNoTopic) {
    sim_.bus().publish(map_score_topic_, msg::String{j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)});
  }
  return out;
}

}  // namespace rescuesim
