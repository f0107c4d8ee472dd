#include "bench/bench_soak.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "bus/bridge.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "msgs/message_fields.h"
#include "robots/rescue_robot.h"
#include "session/session.h"
#include "viz/canvas.h"
#ifdef RESCUESIM_HAS_MCAP
#include "bridges/mcap/mcap_bridge.h"
#endif
#ifdef RESCUESIM_HAS_FOXGLOVE
#include "bridges/foxglove/foxglove_bridge.h"
#endif
#ifdef RESCUESIM_HAS_ROS2
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_bridge.h"
#include "bridges/ros2/ros2_conventions.h"
#endif
#ifdef RESCUESIM_HAS_ROS1
#include "bridges/ros1/ros1_bridge.h"
#endif

namespace rescuesim::bench {

namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

/// Counts NaN in every float and double field of a message (images and point clouds are bytes,
/// so only their float fields are seen; ±inf is a valid range reading and not counted).
struct NanCounter {
  std::uint64_t nans = 0;
  std::string first;  ///< "topic field" of the first NaN
  const std::string* topic = nullptr;

  void hit(msg::fields::Name n) {
    if (nans++ == 0) first = *topic + " " + n.ros2;
  }
  template <class T>
  void value(msg::fields::Name n, const T& x) {
    if constexpr (std::is_floating_point_v<T>) {
      if (std::isnan(x)) hit(n);
    }
  }
  void time(msg::fields::Name, const SimTime&) {}
  void header(msg::fields::Name, const msg::Header&) {}
  template <class T, std::size_t N>
  void array(msg::fields::Name n, const std::array<T, N>& a) {
    for (const T& x : a) value(n, x);
  }
  template <class T>
  void sequence(msg::fields::Name n, const std::vector<T>& s) {
    if constexpr (std::is_floating_point_v<T>) {
      for (const T& x : s) value(n, x);
    }
  }
  template <class F>
  void message(msg::fields::Name, const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void messages(msg::fields::Name, const char*, const std::vector<E>& s, F&& f) {
    for (const E& e : s) f(*this, e);
  }
  void constant(const char*, const char*, const char*) {}
};

/// Resident memory now (MB), from /proc/self/statm.
double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return static_cast<double>(pages_resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / 1e6;
}

/// Bytes the allocator has handed out and not had back (MB): glibc's mallinfo2, small blocks
/// plus mmapped ones, summed over all its arenas (checked on glibc 2.36 with a block kept by
/// another thread; older manuals say the main arena only). Resident memory also counts pages the
/// arenas keep after a free: each thread that allocates gets an arena of its own (up to 8 per
/// core) and arenas rarely shrink, so a step in resident memory with a flat heap is a high-water
/// mark (the soak's recorder thread, restarted every segment, fills one arena after another),
/// while a heap that climbs is a leak.
/// Also what the arenas hold: all their memory from the system (mallinfo2 arena) and the free
/// part of it (fordblks); freed memory is resident until it is given back. One mallinfo2
/// call (it walks every arena under its lock).
struct HeapMb {
  double in_use = 0, arenas = 0, arenas_free = 0;
};
HeapMb heap_mb() {
  const struct mallinfo2 m = ::mallinfo2();
  return {static_cast<double>(m.uordblks + m.hblkhd) / 1e6, static_cast<double>(m.arena) / 1e6, static_cast<double>(m.fordblks) / 1e6};
}

/// Set by SIGINT/SIGTERM: the soak stops at the next step and still writes its files.
std::atomic<bool> g_soak_stop{false};
extern "C" void on_soak_signal(int) { g_soak_stop = true; }

/// Peak resident memory of this process so far (MB, 10^6 bytes, as resident_mb).
double peak_mb() {
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) * 1024.0 / 1e6;  // ru_maxrss is in KiB
}

struct Sample {
  double sim_s = 0, wall_s = 0, rtf = 0, resident_mb = 0, peak_mb = 0, heap_mb = 0, arena_mb = 0, arena_free_mb = 0;
  std::uint64_t messages = 0, nans = 0, recorded_bytes = 0;
};

std::string soak_csv(const std::vector<Sample>& samples) {
  std::string csv = "sim_s,wall_s,rtf,resident_mb,peak_mb,heap_mb,arena_mb,arena_free_mb,messages,nans,recorded_bytes\n";
  for (const Sample& x : samples) {
    csv += fmt::format("{:.3f},{:.3f},{:.3f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{},{},{}\n", x.sim_s, x.wall_s, x.rtf, x.resident_mb,
                       x.peak_mb, x.heap_mb, x.arena_mb, x.arena_free_mb, x.messages, x.nans, x.recorded_bytes);
  }
  return csv;
}

/// Least-squares slope of y against x (0 with fewer than two points).
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return 0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : 0;
}

/// Two stacked plots against sim time (h): resident and peak memory (MB), real-time factor.
void plot(const std::vector<Sample>& samples, const std::filesystem::path& png) {
  constexpr int kW = 900, kH = 600, kLeft = 70, kRight = 20, kTop = 30, kGap = 60;
  const int panel_h = (kH - kTop - kGap - 40) / 2;
  Canvas c(kW, kH);
  const double t_max = std::max(samples.empty() ? 1.0 : samples.back().sim_s / 3600, 1e-6);
  const auto panel = [&](int top, const char* title, const std::vector<std::pair<std::vector<double>, Rgb8>>& series) {
    double y_max = 1e-9;
    for (const auto& [ys, colour] : series) {
      for (double y : ys) y_max = std::max(y_max, y);
    }
    y_max *= 1.1;
    const int bottom = top + panel_h, right = kW - kRight;
    c.line({double(kLeft), double(bottom)}, {double(right), double(bottom)}, {0, 0, 0});
    c.line({double(kLeft), double(top)}, {double(kLeft), double(bottom)}, {0, 0, 0});
    c.text(kLeft, top - 18, title, {0, 0, 0}, 2);
    c.text(4, top, fmt::format("{:.0f}", y_max), {0, 0, 0});
    c.text(4, bottom - 8, "0", {0, 0, 0});
    c.text(right - 90, bottom + 6, fmt::format("{:.2f} h sim", t_max), {0, 0, 0});
    for (const auto& [ys, colour] : series) {
      std::vector<Vec2> pts;
      for (std::size_t i = 0; i < ys.size(); ++i) {
        pts.push_back({kLeft + (samples[i].sim_s / 3600 / t_max) * (right - kLeft), bottom - ys[i] / y_max * panel_h});
      }
      if (pts.size() > 1) c.polyline(pts, colour, 2.0);
    }
  };
  std::vector<double> rss, peak, heap, rtf;
  for (const Sample& s : samples) {
    rss.push_back(s.resident_mb);
    peak.push_back(s.peak_mb);
    heap.push_back(s.heap_mb);
    rtf.push_back(s.rtf);
  }
  panel(kTop, "memory MB (blue resident, red peak, black heap in use)",
        {{rss, {40, 90, 200}}, {peak, {200, 50, 40}}, {heap, {0, 0, 0}}});
  panel(kTop + panel_h + kGap, "real-time factor per sample", {{rtf, {30, 140, 60}}});
  c.write_png(png);
}

/// The soak's session: the default scenario for `o.hours` of sim time, lockstep, without stopping
/// when every victim is found; with cameras unless they cannot start here (no OpenGL), and then
/// without them and `attached["cameras"]` says why.
std::unique_ptr<Session> open_session(const SoakOptions& o, const ModelMap& models, json& attached) {
  Scenario s = default_scenario(models);
  s.duration = o.hours * 3600;
  s.realtime = false;
  s.stop_when_all_found = false;
  SessionOptions so;
  so.cameras = o.cameras;
  std::unique_ptr<Session> session;
  try {
    session = std::make_unique<Session>(s, models, so);
  } catch (const Error& e) {
    if (!o.cameras) throw;
    attached["cameras"] = std::string("off: ") + e.what();
    so.cameras = false;
    session = std::make_unique<Session>(s, models, so);
  }
  if (!attached.contains("cameras")) attached["cameras"] = so.cameras ? "on (" + session->render_device() + ")" : "off (--no-cameras)";
  return session;
}

/// Every message the simulation publishes, counted and checked for NaN on the simulation
/// thread as it is published, from construction to destruction.
class MessageCheck {
 public:
  explicit MessageCheck(Bus& bus) : bus_(bus) {
    handle_ = bus_.subscribe("", [this](const Topic& t, const msg::Message& m) {
      ++messages_;
      nan_.topic = &t.name;
      std::visit([this](const auto& x) { msg::fields::visit_fields(nan_, x); }, m);
    });
  }
  ~MessageCheck() { bus_.unsubscribe(handle_); }
  MessageCheck(const MessageCheck&) = delete;
  MessageCheck& operator=(const MessageCheck&) = delete;

  std::uint64_t messages() const { return messages_; }
  const NanCounter& nan() const { return nan_; }

 private:
  Bus& bus_;
  SubscriptionId handle_{};
  NanCounter nan_;
  std::uint64_t messages_ = 0;
};

/// Every bridge this build has, each with a local subscriber where one can be made here: the
/// MCAP recording (restarted into a fresh temporary file every `record_segment_seconds` of sim
/// time), Foxglove (a server, no client), ROS 2 (a Cyclone DDS reader in this process on /scan
/// and /odom), ROS 1 (when a roscore is up). What each is attached to, or why it is not, goes
/// into `attached` under its name.
class SoakBridges {
 public:
  SoakBridges(Simulation& sim, const SoakOptions& o, json& attached) : sim_(sim), o_(o), attached_(attached) {
    start_recording();
    start_foxglove();
    start_ros2();
    start_ros1();
  }

  /// Between two steps of the run: reads what the ROS 2 reader got, and starts a new recording
  /// file when a segment of sim time is over.
  void between_steps([[maybe_unused]] double sim_time) {
    take_ros2();
#ifdef RESCUESIM_HAS_MCAP
    if (sim_time >= next_segment_) {
      stop_recorder();
      start_recorder();
      next_segment_ += o_.record_segment_seconds;
    }
#endif
  }

  /// After the run: the last reads and the last recording file, every bridge stopped, and the
  /// recording's and the ROS 2 reader's totals in `attached`.
  void finish() {
    take_ros2();
#ifdef RESCUESIM_HAS_MCAP
    stop_recorder();
    attached_["mcap"] = "recorded to " + recording_.string() + ", restarted every " + fmt::format("{:g}", o_.record_segment_seconds) +
                        " s of sim time (" + std::to_string(segments_) + " files, " + fmt::format("{:.2f}", recorded_bytes_ / 1e9) +
                        " GB written, " + std::to_string(record_dropped_) + " messages dropped)";
#endif
    for (auto& b : bridges_) b->stop();
#ifdef RESCUESIM_HAS_ROS2
    if (peer_) attached_["ros2_received"] = ros2_received_;
#endif
  }

  /// Bytes of the recording files finished so far.
  std::uint64_t recorded_bytes() const { return recorded_bytes_; }

 private:
  /// Starts `b`, or says in `attached` why it could not be.
  void try_start(const char* name, std::unique_ptr<Bridge> b, const std::string& subscriber) {
    try {
      b->start(sim_);
      bridges_.push_back(std::move(b));
      attached_[name] = subscriber;
    } catch (const Error& e) {
      attached_[name] = std::string("skipped: ") + e.what();
    }
  }

  void start_recording() {
#ifdef RESCUESIM_HAS_MCAP
    recording_ = std::filesystem::temp_directory_path() / ("rescuesim-soak-" + std::to_string(::getpid()) + ".mcap");
    next_segment_ = o_.record_segment_seconds;
    start_recorder();
#else
    attached_["mcap"] = "not built";
#endif
  }

#ifdef RESCUESIM_HAS_MCAP
  void start_recorder() {
    McapOptions mo;
    mo.path = recording_;
    recorder_ = make_mcap_recorder(mo);
    recorder_->start(sim_);
    ++segments_;
  }

  void stop_recorder() {
    recorder_->stop();
    const BridgeStats st = recorder_->stats();
    record_dropped_ += st.dropped;
    std::error_code ec;
    recorded_bytes_ += std::filesystem::file_size(recording_, ec);
    std::filesystem::remove(recording_, ec);
    recorder_.reset();
  }
#endif

  void start_foxglove() {
#ifdef RESCUESIM_HAS_FOXGLOVE
    FoxgloveOptions fo;
    fo.port = 0;
    try_start("foxglove", make_foxglove_bridge(fo),
              "server started on a free port, no client connected (every channel advertised, none sent)");
#else
    attached_["foxglove"] = "not built";
#endif
  }

  /// A second DDS participant in this process reads /scan and /odom, so the bridge serialises
  /// and sends them.
  void start_ros2() {
#ifdef RESCUESIM_HAS_ROS2
    const int domain = 200 + static_cast<int>(::getpid() % 30);
    Ros2Options ro;
    ro.domain_id = domain;
    try_start("ros2", make_ros2_bridge(ro), "");
    if (attached_["ros2"] == "") {
      peer_ = std::make_unique<ros2::DdsParticipant>(domain, ros2::participant_user_data());
      scan_reader_ = peer_->create_reader("rt/scan", "sensor_msgs::msg::dds_::LaserScan_", {});
      odom_reader_ = peer_->create_reader("rt/odom", "nav_msgs::msg::dds_::Odometry_", {});
      attached_["ros2"] = "domain " + std::to_string(domain) + ", a Cyclone DDS reader in this process on rt/scan and rt/odom";
    }
#else
    attached_["ros2"] = "not built";
#endif
  }

  void take_ros2() {
#ifdef RESCUESIM_HAS_ROS2
    if (!peer_) return;
    for (int r : {scan_reader_, odom_reader_}) peer_->take(r, [&](std::span<const std::uint8_t>) { ++ros2_received_; });
#endif
  }

  void start_ros1() {
#ifdef RESCUESIM_HAS_ROS1
    if (std::getenv("ROS_MASTER_URI")) {
      try_start("ros1", make_ros1_bridge({}), std::string("registered with ") + std::getenv("ROS_MASTER_URI") + " (no subscriber started)");
    } else {
      attached_["ros1"] = "skipped: no ROS_MASTER_URI (start a roscore to attach it)";
    }
#else
    attached_["ros1"] = "not built";
#endif
  }

  Simulation& sim_;
  const SoakOptions& o_;
  json& attached_;
  std::vector<std::unique_ptr<Bridge>> bridges_;
  std::uint64_t recorded_bytes_ = 0;
#ifdef RESCUESIM_HAS_MCAP
  std::filesystem::path recording_;
  std::unique_ptr<Bridge> recorder_;
  std::uint64_t segments_ = 0, record_dropped_ = 0;
  double next_segment_ = 0;
#endif
#ifdef RESCUESIM_HAS_ROS2
  std::unique_ptr<ros2::DdsParticipant> peer_;
  int scan_reader_ = -1, odom_reader_ = -1;
  std::uint64_t ros2_received_ = 0;
#endif
};

/// The soak's samples, taken between steps; each rewrites soak.csv at once, so a soak that is
/// killed still leaves its curve. The wall clock starts at construction.
class SoakSampler {
 public:
  explicit SoakSampler(std::filesystem::path csv) : csv_(std::move(csv)), t0_(Clock::now()) {}

  void take(double sim_s, std::uint64_t messages, std::uint64_t nans, std::uint64_t recorded_bytes) {
    Sample x;
    x.sim_s = sim_s;
    x.wall_s = wall_seconds();
    x.rtf = x.wall_s > last_wall_ ? (sim_s - last_sim_) / (x.wall_s - last_wall_) : 0;
    x.resident_mb = resident_mb();
    x.peak_mb = peak_mb();
    const HeapMb heap = heap_mb();
    x.heap_mb = heap.in_use;
    x.arena_mb = heap.arenas;
    x.arena_free_mb = heap.arenas_free;
    x.messages = messages;
    x.nans = nans;
    x.recorded_bytes = recorded_bytes;
    last_wall_ = x.wall_s;
    last_sim_ = sim_s;
    samples_.push_back(x);
    std::fprintf(stderr,
                 "soak: %7.1f min sim, %7.1f s wall, %5.1fx, resident %.0f MB, peak %.0f MB, heap %.0f MB (arenas %.0f MB, %.0f free), "
                 "%llu messages, %llu NaN\n",
                 sim_s / 60, x.wall_s, x.rtf, x.resident_mb, x.peak_mb, x.heap_mb, x.arena_mb, x.arena_free_mb,
                 static_cast<unsigned long long>(x.messages), static_cast<unsigned long long>(x.nans));
    write_file_atomic(csv_, soak_csv(samples_));
  }

  /// Wall seconds since the sampler was made.
  double wall_seconds() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  const std::vector<Sample>& samples() const { return samples_; }

 private:
  std::filesystem::path csv_;
  Clock::time_point t0_;
  double last_wall_ = 0, last_sim_ = 0;
  std::vector<Sample> samples_;
};

/// SIGINT and SIGTERM set g_soak_stop while this lives (the run then stops at its next step);
/// the default handlers come back after.
struct StopOnSignal {
  StopOnSignal() {
    g_soak_stop = false;
    std::signal(SIGINT, on_soak_signal);
    std::signal(SIGTERM, on_soak_signal);
  }
  ~StopOnSignal() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
};

/// soak.json's summary of the samples: the memory curve (first, last, max, least-squares slopes
/// per sim hour, also after the first tenth of the run, when caches and pools have filled) and
/// the real-time factor of whole sample intervals, with the run's own figures.
json summarise(const std::vector<Sample>& samples, const RunResult& r, double wall_seconds, double sample_seconds, const json& attached,
               std::uint64_t messages, const NanCounter& nan) {
  std::vector<double> hours, rss, heap, rtf;
  double rss_max = 0, heap_max = 0;
  for (const Sample& x : samples) {
    hours.push_back(x.sim_s / 3600);
    rss.push_back(x.resident_mb);
    heap.push_back(x.heap_mb);
    rss_max = std::max(rss_max, x.resident_mb);
    heap_max = std::max(heap_max, x.heap_mb);
  }
  // the real-time factor of whole sample intervals (the first sample and a short last one excluded)
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].sim_s - samples[i - 1].sim_s >= 0.5 * sample_seconds) rtf.push_back(samples[i].rtf);
  }
  // the slope after the first tenth of the run, when caches and pools have filled
  std::vector<double> late_h, late_rss, late_heap;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (hours[i] >= 0.1 * hours.back()) {
      late_h.push_back(hours[i]);
      late_rss.push_back(rss[i]);
      late_heap.push_back(heap[i]);
    }
  }
  json j;
  j["sim_hours"] = r.sim_time / 3600;
  j["wall_seconds"] = wall_seconds;
  j["stop_reason"] = r.stop_reason;
  j["attached"] = attached;
  j["messages"] = messages;
  j["memory_mb"] = {{"resident_first", rss.size() > 1 ? rss[1] : rss.front()},
                    {"resident_last", rss.back()},
                    {"resident_max", rss_max},
                    {"peak", samples.back().peak_mb},
                    {"slope_per_sim_hour", slope(hours, rss)},
                    {"slope_per_sim_hour_after_first_tenth", slope(late_h, late_rss)},
                    {"heap_first", heap.size() > 1 ? heap[1] : heap.front()},
                    {"heap_last", heap.back()},
                    {"heap_max", heap_max},
                    {"heap_slope_per_sim_hour_after_first_tenth", slope(late_h, late_heap)}};
  if (!rtf.empty()) {
    double sum = 0;
    for (double x : rtf) sum += x;
    j["real_time_factor"] = {{"first", rtf.front()},
                             {"last", rtf.back()},
                             {"min", *std::min_element(rtf.begin(), rtf.end())},
                             {"max", *std::max_element(rtf.begin(), rtf.end())},
                             {"mean", sum / static_cast<double>(rtf.size())},
                             {"overall", r.sim_time / std::max(1e-9, wall_seconds)}};
  }
  j["nan"] = {{"count", nan.nans}, {"first", nan.first}};
  j["victims_found"] = r.victims_found;
  j["trouble"] = r.trouble;
  return j;
}

}  // namespace

json bench_soak(const SoakOptions& o) {
  fs::create_directories(o.out);
  const ModelMap models = builtin_models();
  json attached;
  std::unique_ptr<Session> session = open_session(o, models, attached);
  Simulation& sim = session->sim();
  std::optional<MessageCheck> check(std::in_place, sim.bus());
  SoakBridges bridges(sim, o, attached);

  // samples every sim minute, taken between steps; Ctrl-C (or a SIGTERM) ends the soak early and
  // what was sampled is still written
  SoakSampler sampler(o.out / "soak.csv");
  const auto sample = [&](double sim_s) { sampler.take(sim_s, check->messages(), check->nan().nans, bridges.recorded_bytes()); };
  sample(0);
  double next_sample = o.sample_seconds;
  RunResult r;
  {
    const StopOnSignal stop_on_signal;
    r = session->run(&g_soak_stop, [&](const RunResult& p) {
      bridges.between_steps(p.sim_time);
      if (p.sim_time >= next_sample) {
        sample(p.sim_time);
        next_sample += o.sample_seconds;
      }
    });
  }
  sample(r.sim_time);
  bridges.finish();
  const std::uint64_t messages = check->messages();
  const NanCounter nan = check->nan();
  check.reset();

  json j = summarise(sampler.samples(), r, sampler.wall_seconds(), o.sample_seconds, attached, messages, nan);
  write_file_atomic(o.out / "soak.csv", soak_csv(sampler.samples()));
  write_file_atomic(o.out / "soak.json", j.dump(2) + "\n");
  plot(sampler.samples(), o.out / "soak.png");
  j["files"] = {(o.out / "soak.csv").string(), (o.out / "soak.json").string(), (o.out / "soak.png").string()};
  return j;
}

}  // namespace rescuesim::bench
