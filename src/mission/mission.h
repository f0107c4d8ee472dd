#pragma once
/// The mission of a run: the referee judging victim reports, the radio network kept in step
/// with the robots (robots, base stations, dropped relays), and what both publish on the Bus:
///   /rescue/score                   std_msgs/String, JSON {score, victims_found, victims,
///                                   false_reports, reports, elapsed}: latched, on every change
///   /<robot>/rescue/report_result   std_msgs/String, JSON: the answer to each of its reports
///   /<robot>/rescue/comms/status    std_msgs/String, JSON: neighbours with RSSI, hops to base,
///                                   bytes sent/received/dropped, relays left; at 1 Hz
///   /<robot>/rescue/comms/inbox     std_msgs/String, JSON: each datagram delivered to it
///                                   (mission/datagram_json.h), as it is delivered
///   /<robot>/rescue/comms/result    std_msgs/String, JSON: the answer to each send and relay
///                                   drop that came in through a topic
/// Reports, datagrams and relays come in through the calls below (the built-in team autonomy,
/// the Python API) and through the topics it adds as Simulation inputs, which every bridge
/// subscribes (ROS 1, ROS 2):
///   /<robot>/rescue/report          geometry_msgs/PoseStamped: a victim at pose.position in
///                                   the map frame (header.frame_id "map" or empty)
///   /<robot>/rescue/report_image    sensor_msgs/Image: the picture of a report, paired with
///                                   the report of the same header.stamp (either may come first)
///   /<robot>/rescue/comms/send      std_msgs/String, JSON {"to", "data" | "text"}
///   /<robot>/rescue/drop_relay      std_msgs/String (content ignored): drop a relay here
/// Driven from the stepping thread: after_step() after every Simulation step. The Simulation
/// calls back into the Mission for those inputs: the Mission must live while it steps.
/// Deterministic: the network's shadowing draws come from the run seed, wall counts do not
/// depend on thread count, and link updates happen on a schedule of sim time.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bus/topic_id.h"
#include "mission/map_metrics.h"
#include "mission/referee.h"
#include "msgs/messages.h"
#include "radio/radio_network.h"
#include "world/mission_spec.h"

namespace rescuesim {

class Simulation;

/// The score of the last map a team submitted on /rescue/map (map_eval::score_map: occupied
/// cells within one cell of the truth, and the truth the robots' lasers could have seen that
/// the map has).
struct MapScoreResult {
  double stamp = 0;            ///< sim time it was scored (s)
  double precision = 0, recall = 0;
  long map_occupied = 0, map_matched = 0, visible = 0, visible_matched = 0;
  int maps = 0;                ///< maps received so far (refused ones included)
  std::string error;           ///< why the last map was refused, or ""
};

/// Which report a kept picture belongs to.
struct ReportPicture {
  std::uint64_t report = 0;   ///< the report's id (ReportReply::id)
  RobotIndex robot;
  double t = 0;               ///< sim time the picture was attached (s)
  ReportOutcome outcome = ReportOutcome::invalid;
  VictimIndex victim;  ///< as the report's reply
};

/// The picture a report came with, kept for the run's outputs (reports/ in the output folder).
struct ReportImage {
  ReportPicture about;
  msg::Image image;           ///< rgb8, bgr8, rgba8, bgra8 or mono8 (image_problem)
};

/// Why `image` cannot be a report's picture ("" when it can): an encoding other than rgb8,
/// bgr8, rgba8, bgra8 and mono8, a side of 0 or over 4096 pixels, a step shorter than a row, or
/// data that is not step × height bytes.
std::string image_problem(const msg::Image& image);

/// What a mission came to, for summary.json and the score figure.
struct MissionResult {
  std::string rules;                          ///< the rules preset
  std::string radio_model;                    ///< ideal, wss or subt
  double score = 0;
  int victims_found = 0;
  int victims = 0;
  RefereeCounts counts;                       ///< reports by outcome
  std::vector<ScoreEvent> timeline;           ///< charged reports in order
  std::vector<std::string> victim_names;
  std::vector<RefereeVictimState> victim_states;
  std::vector<std::string> robot_names;
  std::vector<double> contact_fraction;       ///< per robot: share of link updates with a route to a base
  std::vector<int> relays_dropped;            ///< per robot
  std::uint64_t link_updates = 0;
  std::uint64_t datagrams_sent = 0;           ///< accepted by send()
  std::uint64_t datagrams_delivered = 0;       ///< copies handed to inboxes (a broadcast: one per neighbour)
  std::uint64_t datagrams_dropped = 0;        ///< no route or beyond capacity
  std::optional<MapScoreResult> map;          ///< with map scoring, once a map came
  std::vector<ReportPicture> pictures;        ///< reports that came with a picture (Mission::report_images)
};

class Mission {
 public:
  /// Sets the network up: one radio per robot (at its base link, antenna_height above it), the
  /// spec's bases (or "base", 1 m above the first robot's start), and the referee with the
  /// world's victims. Links are computed at once, so in_contact() is valid before the first
  /// step. Keeps a reference to `sim`, which must outlive it.
  Mission(const MissionSpec& spec, Simulation& sim);

  /// After every Simulation step: at the link rate moves the radios with their robots,
  /// recomputes the links (walls through the simulation's ray scene) and delivers the
  /// datagrams queued since; publishes the comms status at 1 Hz.
  void after_step();

  /// A report by `robot` of a victim at p_W (map frame = world frame), judged now; the answer
  /// is also published on /<robot>/rescue/report_result, and the score when it changes.
  ReportReply report(RobotIndex robot, const Vec3& p_W);
  /// The same with its picture (checked by image_problem; a picture that is refused, or that
  /// would take the kept pictures over kReportImageBytes, is left out and the reply says why in
  /// `message`; the report is judged all the same).
  ReportReply report(RobotIndex robot, const Vec3& p_W, msg::Image image);
  /// A picture for robot `robot`'s report of the same header.stamp: attached to its last
  /// report if that has this stamp and no picture yet, else kept until such a report comes (a
  /// newer picture replaces it). Returns "" or why it was refused (also published on
  /// /<robot>/rescue/report_result).
  std::string report_image(RobotIndex robot, msg::Image image);
  /// Every report picture kept, in the order they were attached.
  const std::vector<ReportImage>& report_images() const { return report_images_; }
  static constexpr std::size_t kReportImageBytes = std::size_t{256} << 20;

  /// Scores team maps against `world` (the WorldSpec the run was built from): adds the input
  /// /rescue/map (nav_msgs/OccupancyGrid in the map frame) and the latched /rescue/map_score;
  /// from now on every link update adds to the surface the robots could have seen what each
  /// robot's first lidar sees from its true pose (when it moved 0.2 m or turned 0.3 rad).
  /// Call once, before bridges start (Session does for every mission).
  void enable_map_scoring(const WorldSpec& world);
  /// Scores `map` now: published on /rescue/map_score and kept for result(). A map that is not
  /// one (a bad size or resolution, another frame) is answered with the reason and not scored.
  MapScoreResult score_map(const msg::OccupancyGrid& map);

  /// True when `robot` had a radio route to a base at the last link update.
  bool in_contact(RobotIndex robot) const;
  /// Sends a datagram from `robot` to `to` ("base", a robot's name, or "*" for every
  /// neighbour); delivered at the next link update along the route of that moment.
  SendResult send(RobotIndex robot, std::string_view to, std::vector<std::uint8_t> bytes);
  /// Empties the robot's inbox (which keeps the newest kInboxKeep datagrams not taken; every
  /// one is also published on /<robot>/rescue/comms/inbox as it arrives).
  std::vector<Datagram> take_inbox(RobotIndex robot);
  /// Empties base `index`'s inbox (base_nodes()[index]) and returns what was in it. A base's
  /// inbox keeps the newest kInboxKeep datagrams not taken, as a robot's does.
  std::vector<Datagram> take_base_inbox(std::size_t index);
  static constexpr std::size_t kInboxKeep = 1024;
  RadioStatus status(RobotIndex robot) const;
  /// Drops a relay where the robot stands (its antenna position); from the robot's budget.
  RelayResult drop_relay(RobotIndex robot);
  /// The radio node of robot `robot`, of base `index`.
  RadioNodeIndex robot_node(RobotIndex robot) const { return robot_nodes_.at(robot); }
  const std::vector<RadioNodeIndex>& base_nodes() const { return base_nodes_; }

  const Referee& referee() const { return referee_; }
  const RadioNetwork& network() const { return network_; }
  const MissionSpec& spec() const { return spec_; }
  MissionResult result() const;

  /// Everything of the mission that changes, for Session snapshots (restore puts it back).
  struct Memory;
  Memory save() const;
  void load(const Memory& memory);

 private:
  void update_links();
  /// Publishes the datagrams delivered since `before` (inbox sizes per robot before deliver()).
  void publish_inboxes(const std::vector<std::size_t>& before);
  void publish_reply(RobotIndex robot, const ReportReply& reply, const Vec3& p_W);
  ReportReply judge(RobotIndex robot, const Vec3& p_W);
  /// Keeps `image` as report `reply`'s picture; "" or why not.
  std::string keep_image(RobotIndex robot, const ReportReply& reply, msg::Image image);
  void publish_image_result(RobotIndex robot, std::uint64_t report, const std::string& problem);
  void publish_comms_result(RobotIndex robot, const std::string& json);
  void add_inputs();
  void publish_score();
  void publish_status();
  std::vector<Vec3> radio_positions() const;

  MissionSpec spec_;
  Simulation& sim_;
  Referee referee_;
  RadioNetwork network_;
  IndexedVector<RobotTag, RadioNodeIndex> robot_nodes_;
  std::vector<RadioNodeIndex> base_nodes_;
  std::vector<std::uint64_t> in_contact_updates_;  ///< per robot
  std::vector<bool> in_contact_;                   ///< per robot, at the last update
  std::int64_t next_link_ns_ = 0, next_status_ns_ = 0;
  TopicId score_topic_ = kNoTopic;
  IndexedVector<RobotTag, TopicId> result_topics_, status_topics_, inbox_topics_, comms_result_topics_;
  // map scoring (enable_map_scoring): what does not change, then what does (in Memory too)
  struct MapTruth {
    map_eval::Grid truth, ignore;
    std::vector<map_eval::LaserModel> lasers;  ///< per robot
    std::vector<bool> has_laser;
  };
  std::shared_ptr<const MapTruth> map_truth_;
  map_eval::Grid visible_;
  std::vector<std::optional<Pose2>> seen_from_;  ///< per robot: the pose of its last visibility update
  std::optional<MapScoreResult> map_score_;
  TopicId map_score_topic_ = kNoTopic;
  void update_visible();
  // report pictures (in Memory too)
  struct LastReport {
    SimTime stamp;            ///< header.stamp of the report as it came in on the topic
    ReportReply reply;
    bool has_image = false;
  };
  std::vector<std::optional<LastReport>> last_report_;     ///< per robot: its last report from the topic
  std::vector<std::optional<msg::Image>> waiting_image_;   ///< per robot: a picture whose report has not come
  std::vector<ReportImage> report_images_;
  std::size_t report_image_bytes_ = 0;
};

/// See Mission::save.
struct Mission::Memory {
  Referee referee;
  RadioNetwork network;
  std::vector<std::uint64_t> in_contact_updates;
  std::vector<bool> in_contact;
  std::int64_t next_link_ns = 0, next_status_ns = 0;
  map_eval::Grid visible;
  std::vector<std::optional<Pose2>> seen_from;
  std::optional<MapScoreResult> map_score;
  std::vector<std::optional<LastReport>> last_report;
  std::vector<std::optional<msg::Image>> waiting_image;
  std::vector<ReportImage> report_images;
  std::size_t report_image_bytes = 0;
};

}  // namespace rescuesim
