// rescuesim_nav: the simulator's built-in explorer (src/autonomy: wall following, and A* to the
// nearest frontier when stuck) as a ROS 1 node of its own. It hears /scan, /odom and /tf_static,
// answers with /cmd_vel, and shows what it plans on /nav/path and what it mapped on /nav/map:
// messages flow both ways, as in the seed's second demonstration (section 4.2).

#include <ros/callback_queue.h>
#include <ros/init.h>
#include <ros/master.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "autonomy/explorer.h"
#include "bridges/ros1/ros1_console.h"
#include "bridges/ros1/ros1_endpoint.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "bridges/ros1/ros1_raw_message.h"
#include "robots/rescue_robot.h"
#include "session/explorer_settings.h"

namespace rescuesim::nav {

using ros1_wire::RawMessage;

namespace {

constexpr int kExitOk = 0;
constexpr int kExitUsage = 2;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

const char* kUsage =
    "rescuesim_nav: the simulator's built-in explorer as a ROS 1 node (docs/demos.md, Demonstration 2)\n"
    "\n"
    "Usage: rescuesim_nav [--out FILE] [--controller explorer|wall_follower] [--map-period S]\n"
    "                     [--master-timeout S] [--base-frame NAME] [--look on|off]\n"
    "\n"
    "Subscribes  /scan (sensor_msgs/LaserScan), /odom (nav_msgs/Odometry), /tf_static (the laser's\n"
    "            mounting on the base frame).\n"
    "Publishes   /cmd_vel (geometry_msgs/Twist) once per scan, /nav/path (nav_msgs/Path, map frame,\n"
    "            latched) whenever it plans, /nav/map (nav_msgs/OccupancyGrid, map frame) every\n"
    "            --map-period s of sim time, /tf map -> odom (its scan-matching correction) per scan.\n"
    "It is the same rescuesim::autonomy::Explorer, with the same settings, that drives the robot\n"
    "in-process in 'rescuesim run'; all its time comes from message stamps (sim time). One\n"
    "difference: in-process the explorer swings the mast to look from side to side; this node\n"
    "leaves the head where it starts (a head command on its own topic would race the cmd_vel a\n"
    "synchronous run waits for) and turns the whole robot to look at ground its camera missed.\n"
    "\n"
    "Options:\n"
    "  --out FILE          write what it did (counters, every planned path, its map) as JSON\n"
    "                      to FILE, every few seconds and on exit (atomically)\n"
    "  --controller NAME   explorer (default: wall following + A* to frontiers) or wall_follower\n"
    "  --map-period S      sim seconds between /nav/map messages (default 1; 0: never)\n"
    "  --master-timeout S  give up when no ROS master answers within S wall seconds (default 10)\n"
    "  --base-frame NAME   the robot's base frame in /tf_static (default base_link)\n"
    "  --look on|off       on (default): besides frontiers, drive to free ground the victim camera\n"
    "                      has not looked at yet: the built-in rescue robot's thermal camera, 85 %\n"
    "                      of its 57 deg field of view and 80 % of its 6 m range, looking where the\n"
    "                      head starts (ahead); off: frontiers only\n"
    "\n"
    "The master is ROS_MASTER_URI (default http://localhost:11311). Ctrl-C or SIGTERM ends it.\n"
    "Exit codes: 0 stopped, 2 bad arguments or no master.\n";

struct Options {
  std::string out;
  std::string controller = "explorer";
  double map_period = 1.0;
  double master_timeout = 10.0;
  std::string base_frame = "base_link";
  bool look = true;
};

/// Parses the command line; prints the problem and returns nothing for bad arguments.
std::optional<Options> parse(int argc, char** argv, bool* help) {
  Options o;
  const auto number = [](const std::string& flag, const std::string& text, double lo) -> std::optional<double> {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != 0 || !(v >= lo) || !std::isfinite(v)) {
      std::fprintf(stderr, "rescuesim_nav: %s wants a number >= %g, not '%s'\n", flag.c_str(), lo, text.c_str());
      return std::nullopt;
    }
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      *help = true;
      return o;
    }
    // roscpp's own remapping arguments (name:=value, __name:=...) are allowed and passed on
    if (a.find(":=") != std::string::npos) continue;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "rescuesim_nav: unknown argument or missing value: '%s' (see --help)\n", a.c_str());
      return std::nullopt;
    }
    const std::string v = argv[++i];
    if (a == "--out") {
      o.out = v;
    } else if (a == "--controller") {
      if (v != "explorer" && v != "wall_follower") {
        std::fprintf(stderr, "rescuesim_nav: --controller is explorer or wall_follower, not '%s'\n", v.c_str());
        return std::nullopt;
      }
      o.controller = v;
    } else if (a == "--map-period") {
      const auto x = number(a, v, 0);
      if (!x) return std::nullopt;
      o.map_period = *x;
    } else if (a == "--master-timeout") {
      const auto x = number(a, v, 0.1);
      if (!x) return std::nullopt;
      o.master_timeout = *x;
    } else if (a == "--base-frame") {
      o.base_frame = v;
    } else if (a == "--look") {
      if (v != "on" && v != "off") {
        std::fprintf(stderr, "rescuesim_nav: --look is on or off, not '%s'\n", v.c_str());
        return std::nullopt;
      }
      o.look = v == "on";
    } else {
      std::fprintf(stderr, "rescuesim_nav: unknown argument '%s' (see --help)\n", a.c_str());
      return std::nullopt;
    }
  }
  return o;
}

const msg::TypeSupport& type(const char* name) {
  const msg::TypeSupport* t = msg::find_type(name);
  RS_DEMAND(t, "rescuesim's serialisers lack a ROS 1 message type the node needs");
  return *t;
}

/// A planned path as the node recorded it.
struct PlannedPath {
  double t = 0;                  ///< s, sim time of the plan
  std::string mode;              ///< to_frontier or to_goal
  std::vector<Vec2> points_O;    ///< m, the explorer's map frame (the odom frame at the start, corrected by scan matching)
};

class NavNode {
 public:
  NavNode(ros::NodeHandle& nh, Options options)
      : options_(std::move(options)),
        scan_t_(type("sensor_msgs/LaserScan")),
        odom_t_(type("nav_msgs/Odometry")),
        tf_t_(type("tf2_msgs/TFMessage")),
        twist_t_(type("geometry_msgs/Twist")),
        path_t_(type("nav_msgs/Path")),
        grid_t_(type("nav_msgs/OccupancyGrid")) {
    cmd_pub_ = advertise(nh, "/cmd_vel", twist_t_, false);
    path_pub_ = advertise(nh, "/nav/path", path_t_, true);
    map_pub_ = advertise(nh, "/nav/map", grid_t_, true);
    tf_pub_ = advertise(nh, "/tf", tf_t_, false);
    // laser and odometry in, and the laser's mounting from the latched /tf_static
    subs_.push_back(subscribe(nh, "/scan", scan_t_, 5, [this](const msg::Message& m) { on_scan(std::get<msg::LaserScan>(m)); }));
    subs_.push_back(subscribe(nh, "/odom", odom_t_, 50, [this](const msg::Message& m) { on_odom(std::get<msg::Odometry>(m)); }));
    subs_.push_back(subscribe(nh, "/tf_static", tf_t_, 10, [this](const msg::Message& m) { on_tf_static(std::get<msg::TFMessage>(m)); }));
  }

  /// Writes the JSON record (when asked for one).
  void write_record() const {
    if (options_.out.empty()) return;
    nlohmann::ordered_json j;
    j["node"] = "rescuesim_nav";
    j["controller"] = options_.controller;
    j["frame_id"] = explorer_ ? explorer_->config().frame_id : std::string("map");
    j["scans"] = scans_;
    j["odometry"] = odoms_;
    j["commands"] = commands_;
    j["rejected_messages"] = rejected_;
    j["last_stamp_s"] = last_stamp_;
    j["step_ms_mean"] = scans_ > 0 ? step_ms_sum_ / static_cast<double>(scans_) : 0.0;
    j["step_ms_max"] = step_ms_max_;
    if (explorer_) {
      const auto& s = explorer_->stats();
      j["laser_in_base"] = {X_BS_.x, X_BS_.y, X_BS_.yaw};
      j["mode"] = mode_name(explorer_->mode());
      j["exploration_complete"] = explorer_->exploration_complete();
      j["stats"] = {{"scans_mapped", s.scans},          {"cells_learned", s.cells_learned},
                    {"plans", s.plans},                 {"frontier_trips", s.frontier_trips},
                    {"frontiers_reached", s.frontiers_reached}, {"stuck_no_progress", s.stuck_no_progress},
                    {"stuck_blocked", s.stuck_blocked}, {"stuck_looping", s.stuck_looping},
                    {"no_frontier", s.no_frontier},     {"path_blocked", s.path_blocked},
                    {"path_stuck", s.path_stuck},       {"abandoned", s.abandoned},
                    {"backups", s.backups},             {"slipping_scans", s.slipping_scans},
                    {"scans_matched", s.scans_matched}, {"scans_ambiguous", s.scans_ambiguous},
                    {"scans_unmatched", s.scans_unmatched}, {"look_trips", s.look_trips}};
      j["look"] = explorer_->config().look.enabled;
      const Pose2& X_MO = explorer_->X_MO();
      j["X_MO"] = {X_MO.x, X_MO.y, X_MO.yaw};
    }
    auto paths = nlohmann::json::array();
    for (const PlannedPath& p : paths_) {
      auto pts = nlohmann::json::array();
      for (const Vec2& v : p.points_O) pts.push_back({std::round(v.x() * 1000) / 1000, std::round(v.y() * 1000) / 1000});
      paths.push_back({{"t", p.t}, {"mode", p.mode}, {"points", pts}});
    }
    j["paths"] = paths;
    if (explorer_) j["map"] = map_json(explorer_->map(SimTime::from_seconds(last_stamp_)));
    try {
      write_file_atomic(options_.out, j.dump(1) + "\n");
    } catch (const std::exception& e) {
      log::error("rescuesim_nav: {}", e.what());
    }
  }

  int commands() const { return commands_; }
  int scans() const { return scans_; }

 private:
  using Handler = std::function<void(const msg::Message&)>;

  /// The known part of the map as rows of characters from the origin's row up: '?' unknown,
  /// '.' free (< 35), '+' uncertain, '#' occupied (>= 65); origin = pose of the first cell's
  /// corner in the odom frame (m, m, rad).
  static nlohmann::ordered_json map_json(const msg::OccupancyGrid& g) {
    // the window of observed cells only: the grid itself is sized for any world
    std::uint32_t x0 = g.width, y0 = g.height, x1 = 0, y1 = 0;
    for (std::uint32_t y = 0; y < g.height; ++y) {
      for (std::uint32_t x = 0; x < g.width; ++x) {
        if (g.data[static_cast<std::size_t>(y) * g.width + x] < 0) continue;
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x + 1);
        y1 = std::max(y1, y + 1);

      }
    }
    if (x0 >= x1) x0 = x1 = y0 = y1 = 0;
    const Pose2 X_OM = g.origin.to_pose2();
    const Pose2 X_OW = X_OM * Pose2{x0 * static_cast<double>(g.resolution), y0 * static_cast<double>(g.resolution), 0.0};
    nlohmann::ordered_json j;
    j["resolution"] = g.resolution;
    j["width"] = x1 - x0;
    j["height"] = y1 - y0;
    j["origin"] = {X_OW.x, X_OW.y, X_OW.yaw};
    auto rows = nlohmann::json::array();
    for (std::uint32_t y = y0; y < y1; ++y) {
      std::string row(x1 - x0, '?');
      for (std::uint32_t x = x0; x < x1; ++x) {
        const int v = g.data[static_cast<std::size_t>(y) * g.width + x];
        row[x - x0] = v < 0 ? '?' : v < 35 ? '.' : v >= 65 ? '#' : '+';
      }
      rows.push_back(std::move(row));
    }
    j["rows"] = rows;
    return j;
  }


  /// The in-process explorer's settings; the victim camera is the built-in rescue robot's,
  /// fixed where the head starts (the node commands no joints).
  static autonomy::ExplorerConfig explorer_config(const Options& o) {
    autonomy::ExplorerConfig ec = builtin_explorer_config(o.controller);
    if (o.look && ec.frontier_trips) ec.look = victim_camera_look(rescue_robot(), /*swing=*/false);
    return ec;
  }

  static const char* mode_name(autonomy::ExplorerMode m) {

    switch (m) {
      case autonomy::ExplorerMode::wall_following: return "wall_following";
      case autonomy::ExplorerMode::to_frontier: return "to_frontier";
      case autonomy::ExplorerMode::to_goal: return "to_goal";
      case autonomy::ExplorerMode::at_goal: return "at_goal";
      case autonomy::ExplorerMode::backing_up: return "backing_up";
    }
    return "?";
  }

  static ros::Publisher advertise(ros::NodeHandle& nh, const std::string& topic, const msg::TypeSupport& t, bool latch) {
    ros::AdvertiseOptions ao(topic, 10, t.ros1_md5, t.ros1_name, t.ros1_definition);
    ao.latch = latch;
    return nh.advertise(ao);
  }

  ros::Subscriber subscribe(ros::NodeHandle& nh, const std::string& topic, const msg::TypeSupport& t, std::uint32_t queue,
                            Handler handler) {
    // roscpp connects only to publishers of this MD5, so the bytes are this type or malformed
    using Helper = ros::SubscriptionCallbackHelperT<const boost::shared_ptr<const RawMessage>&>;
    ros::SubscribeOptions so(topic, queue, t.ros1_md5, t.ros1_name);
    so.helper = boost::make_shared<Helper>([this, &t, topic, handler](const boost::shared_ptr<const RawMessage>& raw) {
      msg::Message m;
      try {
        m = msg::from_ros1(t, raw->bytes);
      } catch (const std::exception& e) {
        if (rejected_++ == 0) log::warn("rescuesim_nav: a malformed message on {}: {}", topic, e.what());
        return;
      }
      handler(m);
    });
    // TCP_NODELAY: a scan must not wait in Nagle's buffer
    so.transport_hints = ros::TransportHints().tcpNoDelay();
    return nh.subscribe(so);
  }

  void on_tf_static(const msg::TFMessage& tf) {
    for (const auto& t : tf.transforms) parent_of_[t.child_frame_id] = {t.header.frame_id, t.transform};
  }

  /// The pose of `frame` in the base frame from /tf_static, when the chain reaches it.
  std::optional<Pose3> in_base(std::string frame) const {
    Pose3 X_PF;  // frame in its current ancestor
    for (int depth = 0; depth < 32; ++depth) {
      if (frame == options_.base_frame) return X_PF;
      const auto it = parent_of_.find(frame);
      if (it == parent_of_.end()) return std::nullopt;
      X_PF = it->second.second * X_PF;
      frame = it->second.first;
    }
    return std::nullopt;
  }

  void on_odom(const msg::Odometry& odom) {
    ++odoms_;
    last_odom_ = odom.header.stamp;
    odom_frame_ = odom.header.frame_id;
    if (explorer_) explorer_->on_odometry(odom);
    // a scan that came in before the odometry of its own instant is answered now
    if (held_scan_ && last_odom_ >= held_scan_->header.stamp) {
      const msg::LaserScan scan = std::move(*held_scan_);
      held_scan_.reset();
      answer(scan);
    }
  }

  void on_scan(const msg::LaserScan& scan) {
    // Each topic has its own connection, so a scan may overtake the odometry the simulator
    // published in the same step (both sit on the 5 ms step grid: /odom every 20 ms, /scan every
    // 100 ms). Answering only once odometry has caught up makes the answer the same every time,
    // which a synchronous run (rescuesim run --sync) turns into a repeatable run.
    if (held_scan_) {
      const msg::LaserScan older = std::move(*held_scan_);
      held_scan_.reset();
      answer(older);  // its odometry never came: answer with what there is
    }
    if (last_odom_ < scan.header.stamp) {
      held_scan_ = scan;
      return;
    }
    answer(scan);
  }

  void answer(const msg::LaserScan& scan) {
    if (!explorer_) {
      // the explorer places scans with the laser's mounting pose, which /tf_static gives
      const std::optional<Pose3> X_BS = in_base(scan.header.frame_id);
      if (!X_BS) {
        if (!waiting_reported_) {
          log::info("rescuesim_nav: waiting for /tf_static to place frame '{}' on '{}'", scan.header.frame_id, options_.base_frame);
          waiting_reported_ = true;
        }
        return;
      }
      X_BS_ = X_BS->to_pose2();
      explorer_ = std::make_unique<autonomy::Explorer>(X_BS_, explorer_config(options_));
      log::info("rescuesim_nav: laser '{}' at ({:.3f}, {:.3f}) m, {:.3f} rad on '{}'; {} started", scan.header.frame_id, X_BS_.x,
                X_BS_.y, X_BS_.yaw, options_.base_frame, options_.controller);
    }
    const auto t0 = std::chrono::steady_clock::now();
    ++scans_;
    last_stamp_ = scan.header.stamp.seconds();
    // one scan in, one command out: what the simulator's session does on its Bus
    explorer_->on_scan(scan);
    const msg::Twist cmd = explorer_->command(scan.header.stamp);
    publish(cmd_pub_, cmd);
    ++commands_;
    // the map frame's correction of odometry, for anyone drawing the map over /odom
    msg::TransformStamped X_MO;
    X_MO.header = {scan.header.stamp, explorer_->config().frame_id};
    X_MO.child_frame_id = odom_frame_;
    X_MO.transform = Pose3::from_pose2(explorer_->X_MO());
    publish(tf_pub_, msg::TFMessage{{X_MO}});
    record_path(scan.header.stamp);
    if (options_.map_period > 0 && scan.header.stamp >= next_map_) {
      next_map_ = scan.header.stamp + SimTime::from_seconds(options_.map_period);
      if (map_pub_.getNumSubscribers() > 0) publish(map_pub_, explorer_->map(scan.header.stamp));
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    step_ms_sum_ += ms;
    step_ms_max_ = std::max(step_ms_max_, ms);
  }

  /// Publishes and keeps every new plan (a path whose stamp or length changed).
  void record_path(SimTime now) {
    const msg::Path& p = explorer_->current_path();
    if (p.poses.empty()) return;
    if (p.header.stamp == last_path_stamp_ && p.poses.size() == last_path_size_) return;
    last_path_stamp_ = p.header.stamp;
    last_path_size_ = p.poses.size();
    publish(path_pub_, p);
    PlannedPath rec;
    rec.t = (p.header.stamp.ns > 0 ? p.header.stamp : now).seconds();
    rec.mode = mode_name(explorer_->mode());
    for (const auto& ps : p.poses) rec.points_O.emplace_back(ps.pose.p.x(), ps.pose.p.y());
    paths_.push_back(std::move(rec));
    constexpr std::size_t kKeep = 500;  // the record stays small on long runs
    if (paths_.size() > kKeep) paths_.erase(paths_.begin());
  }

  void publish(ros::Publisher& pub, const msg::Message& m) {
    raw_.type = &msg::type_of(m);
    raw_.bytes.clear();
    msg::to_ros1(m, raw_.bytes, seq_++);
    pub.publish(raw_);
  }

  Options options_;
  const msg::TypeSupport &scan_t_, &odom_t_, &tf_t_, &twist_t_, &path_t_, &grid_t_;
  ros::Publisher cmd_pub_, path_pub_, map_pub_, tf_pub_;
  std::string odom_frame_ = "odom";  // header.frame_id of the odometry heard
  std::vector<ros::Subscriber> subs_;
  std::map<std::string, std::pair<std::string, Pose3>> parent_of_;  // static frames: child -> (parent, pose in parent)
  bool waiting_reported_ = false;
  Pose2 X_BS_;
  std::unique_ptr<autonomy::Explorer> explorer_;
  SimTime last_odom_{-1};                   ///< stamp of the newest odometry
  std::optional<msg::LaserScan> held_scan_;  ///< a scan waiting for the odometry of its instant
  RawMessage raw_;
  std::uint32_t seq_ = 0;
  SimTime next_map_;
  SimTime last_path_stamp_{-1};
  std::size_t last_path_size_ = 0;
  std::vector<PlannedPath> paths_;
  int scans_ = 0, odoms_ = 0, commands_ = 0, rejected_ = 0;
  double last_stamp_ = 0;
  double step_ms_sum_ = 0, step_ms_max_ = 0;
};

int run(const Options& options) {
  const Ros1Endpoint endpoint = resolve_ros1_endpoint(std::getenv("ROS_MASTER_URI"), std::getenv("ROS_HOSTNAME"), std::getenv("ROS_IP"));
  route_rosconsole_to_log();
  ros::M_string remappings{{"__master", endpoint.master_uri}};
  if (!endpoint.hostname.empty()) remappings["__hostname"] = endpoint.hostname;
  ros::init(remappings, "rescuesim_nav", ros::init_options::NoSigintHandler);
  ros::master::setRetryTimeout(ros::WallDuration(1.0));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options.master_timeout);
  while (!ros::master::check()) {
    if (g_stop || std::chrono::steady_clock::now() >= deadline) {
      std::fprintf(stderr, "rescuesim_nav: no ROS master at %s (ROS_MASTER_URI); start roscore first\n", endpoint.master_uri.c_str());
      return kExitUsage;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ros::start();
  int commands = 0;
  {
    ros::NodeHandle nh;
    NavNode node(nh, options);
    log::info("rescuesim_nav: registered with {}; waiting for /scan, /odom and /tf_static", endpoint.master_uri);
    // one thread runs every callback, in arrival order, like the simulator's Bus does in-process
    auto next_write = std::chrono::steady_clock::now();
    while (!g_stop && ros::ok()) {
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
      if (std::chrono::steady_clock::now() >= next_write) {
        node.write_record();
        next_write = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      }
    }
    node.write_record();
    commands = node.commands();
    std::printf("rescuesim_nav: %d scans in, %d commands out\n", node.scans(), commands);
  }
  ros::shutdown();
  return kExitOk;
}

}  // namespace

}  // namespace rescuesim::nav

int main(int argc, char** argv) {
  using namespace rescuesim::nav;
  bool help = false;
  const auto options = parse(argc, argv, &help);
  if (help) {
    std::fputs(kUsage, stdout);
    return kExitOk;
  }
  if (!options) return kExitUsage;
  if (!options->out.empty()) {
    const auto dir = std::filesystem::path(options->out).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir)) {
      std::fprintf(stderr, "rescuesim_nav: --out %s: folder %s does not exist\n", options->out.c_str(), dir.c_str());
      return kExitUsage;
    }
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    return run(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rescuesim_nav: %s\n", e.what());
    return 1;
  }
}
