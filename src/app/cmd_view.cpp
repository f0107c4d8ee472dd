// rescuesim view: the interactive viewer. A window with the main 3D view (orbit camera or
// following the robot), keyboard teleop, and the robot's sensor feeds live in the seed paper's
// Fig. 2 layout. No GL here: the window (render/viewer_window.h) shows CPU images.
//
// Threads: the UI thread owns the window; the simulation steps on a thread of its own
// (app/view_sim_loop.h), paced to the wall clock, so the window keeps its frame rate whatever a
// step costs. Once a frame the UI thread holds the simulation still for a moment
// (Viewer::sync): it copies the State, places the main view's camera, hands over commands and
// takes the sensor messages that arrived (published on the Bus, the cameras rendered by the
// session's own camera thread). A render thread of ours (app/view_render_worker.h) draws the
// main view from the State copies at whatever rate it manages. The frame loop is the Viewer
// class: handle_mouse, handle_teleop, sync, submit_render, upload_feeds, draw_frame.

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <thread>
#include <tuple>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/data_dir.h"
#include "app/figure.h"
#include "app/view_render_worker.h"
#include "app/view_sim_loop.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/viewer_window.h"
#include "robots/rescue_robot.h"
#include "sensors/camera/camera.h"
#include "session/scenario_load.h"
#include "session/session.h"

namespace rescuesim::app {

namespace {

using Clock = std::chrono::steady_clock;

struct ViewCommand {
  std::string scenario, quality = "low", screenshot;
  std::optional<std::uint64_t> seed;
  double rate = 1.0, after = 2.0;
  int width = 1280, height = 800;
};

/// The main view's camera: orbiting a target point, or trailing the robot (follow).
struct OrbitCamera {
  Vec3 target = Vec3::Zero();
  double yaw = 0;       ///< direction from the target to the eye (rad, world frame); in follow mode relative to straight behind the robot
  double pitch = std::atan2(kChaseUp - kChaseAim, kChaseBack + kChaseAhead);  ///< elevation of the eye (rad)
  double distance = std::hypot(kChaseUp - kChaseAim, kChaseBack + kChaseAhead);  ///< m
  bool follow = true;

  /// Eye and target for a robot at `X_WB` (follow mode tracks it; the default is the chase view,
  /// pulled in front of walls between the eye and the robot).
  CameraView view(const Pose3& X_WB, const Intrinsics& k, const RayScene& scene) const {
    Vec3 t = target;
    double az = yaw;
    if (follow) {
      const double heading = X_WB.yaw();
      t = X_WB.p + kChaseAhead * Vec3(std::cos(heading), std::sin(heading), 0) + Vec3(0, 0, kChaseAim);
      az = heading + std::numbers::pi + yaw;
    }
    const Vec3 eye = t + distance * Vec3(std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch));
    return look_at_view(follow ? clear_eye(scene, eye, t, X_WB.p, RobotIndex(0)) : eye, t, k);
  }
  /// Switches between following and a free camera without a jump.
  void set_follow(bool on, const Pose3& X_WB) {
    if (on == follow) return;
    const double heading = X_WB.yaw();
    if (!on) {
      target = X_WB.p + kChaseAhead * Vec3(std::cos(heading), std::sin(heading), 0) + Vec3(0, 0, kChaseAim);
      yaw = heading + std::numbers::pi + yaw;
    } else {
      yaw = wrap_angle(yaw - heading - std::numbers::pi);
    }
    follow = on;
  }
};

/// Screen rectangles of the window's parts (px).
struct ViewLayout {
  float toolbar = 34;
  float main_w = 0, main_h = 0;  ///< main view: x in [0, main_w), y in [toolbar, toolbar + main_h)
  float panel_w = 0, image_w = 0, image_h = 0, panel_h = 0;  ///< 2 x 2 panels right of the main view
  float info_y = 0;                                          ///< the info panel under them
};

ViewLayout view_layout(int w, int h) {
  ViewLayout l;
  const float right = std::round(0.42f * w);
  l.main_w = w - right;
  l.main_h = h - l.toolbar;
  l.panel_w = right / 2;
  l.image_w = l.panel_w - 16;
  l.image_h = std::round(l.image_w * 0.75f);
  l.panel_h = l.image_h + 62;
  l.info_y = l.toolbar + 2 * l.panel_h;
  return l;
}

ImU32 im_color(Rgb8 c) { return IM_COL32(c.r, c.g, c.b, 255); }

/// A colour bar the width of the panel image, with its end labels.
void legend_bar(Rgb8 (*colour)(double), const std::string& lo, const std::string& hi, float width) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const int n = 48;
  for (int i = 0; i < n; ++i) {
    const float x0 = p.x + width * i / n, x1 = p.x + width * (i + 1) / n;
    dl->AddRectFilledMultiColor({x0, p.y}, {x1, p.y + 8}, im_color(colour((i + 0.0) / n)), im_color(colour((i + 1.0) / n)),
                                im_color(colour((i + 1.0) / n)), im_color(colour((i + 0.0) / n)));
  }
  ImGui::Dummy({width, 9});
  ImGui::TextUnformatted(lo.c_str());
  ImGui::SameLine(width - ImGui::CalcTextSize(hi.c_str()).x + ImGui::GetStyle().WindowPadding.x);
  ImGui::TextUnformatted(hi.c_str());
}

/// Everything the viewer remembers between frames.
struct ViewerState {
  OrbitCamera camera;
  bool paused = false;
  float rate = 1;
  float step_request = 0;       ///< s of sim time to step while paused
  bool autonomous = true;       ///< the scenario's controller drives; off: keyboard teleop
  msg::Twist teleop;
  std::vector<double> head;     ///< head joint targets (rad), in RobotSpec::head_joints order
  int quality = 0;
  bool was_f = false;
  bool dragging = false;
  double drag_x = 0, drag_y = 0;
  double rtf = 0, fps = 0, render_ms = 0;
  double frame_time = -1;       ///< sim time of the main view on screen
  double color_time = -1;       ///< stamp of the colour image on screen
  double hottest = 0;           ///< C, warmest pixel of the thermal image on screen
  std::string feed_error;       ///< a sensor image that could not be shown
  std::tuple<std::int64_t, Vec3, Eigen::Vector4d, int, int, int> drawn;  ///< step, eye, rotation, size, quality last sent to render
};

/// The head joints the I/K and J/L keys move, by their place in RobotSpec::head_joints (the
/// rescue robot's /head/command order: mast_yaw, shoulder_pitch, elbow_pitch, head_tilt). A head
/// of any other length gets no keys.
struct HeadRoles {
  static constexpr std::size_t mast_yaw = 0;   ///< J/L: turns the mast left and right
  static constexpr std::size_t head_tilt = 3;  ///< I/K: tilts the head up and down
  static constexpr std::size_t count = 4;
};

/// The robot's sensor messages as published on the Bus, each with a flag set when a new one
/// arrives (the callbacks run on the simulation thread, under its lock; Viewer::sync takes
/// them over to the UI thread).
struct SensorFeeds {
  msg::LaserScan scan;
  msg::Image color, depth, thermal;
  bool new_scan = false, new_color = false, new_depth = false, new_thermal = false;
};

/// The interactive viewer's frame loop over a session: input, stepping, render hand-off and the
/// ImGui panels. Not copyable or movable: the Bus callbacks point into it.
class Viewer {
 public:
  Viewer(const ViewCommand& command, ViewerWindow& window, Session& session, RenderWorker& worker, bool has_controller)
      : c_(command), window_(window), session_(session), sim_(session.sim()), worker_(worker), has_controller_(has_controller),
        robot_(sim_.world().robots[0].spec), sensors_(figure_sensors(robot_)) {
    v_.autonomous = has_controller;
    v_.rate = static_cast<float>(c_.rate);
    v_.quality = c_.quality == "high" ? 2 : c_.quality == "medium" ? 1 : 0;
    subscribe_feeds();
    // head joints start at their initial positions, within their limits
    for (const std::string& name : robot_.head_joints) {
      head_joints_.push_back(&robot_.joints[static_cast<std::size_t>(robot_.joint_index(name))]);
      v_.head.push_back(head_joints_.back()->initial);
    }
  }
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// Frames until the window closes or Esc (kExitOk), or --screenshot is written (kExitOk) or
  /// gives up (kExitFailure).
  int run() {
    const auto start = Clock::now();
    last_ = fps_since_ = start;
    state_ = sim_.state();  // the simulation thread has not started: nothing steps yet
    ViewSimLoop loop(session_, controls());
    loop_ = &loop;
    const int code = frames(start);
    {
      const auto hold = loop.lock();
      const RunResult r = session_.result();
      std::printf("rescuesim view: stopped at sim time %.2f s; %.2f m driven\n", r.sim_time, r.distance);
    }
    loop_ = nullptr;
    return code;
  }

 private:
  ViewControls controls() const {
    ViewControls c;
    c.paused = v_.paused;
    c.rate = v_.rate;
    c.autonomous = v_.autonomous;
    c.teleop = v_.teleop;
    return c;
  }

  /// The frame loop: until the window closes or Esc, or --screenshot is done.
  int frames(Clock::time_point start) {
    for (;;) {
      // paused with nothing left to draw: idle until input (or a tenth of a second)
      window_.poll(v_.paused && v_.step_request == 0 && !worker_.busy() ? 0.1 : 0);
      if (window_.should_close() || window_.key_down(ViewerKey::escape)) break;
      const auto now = Clock::now();
      const double dt = std::min(0.1, std::chrono::duration<double>(now - last_).count());
      last_ = now;
      const ViewLayout l = view_layout(window_.width(), window_.height());
      handle_mouse(l, state_.robots[0].base.X_WB);
      handle_teleop(dt);
      const CameraView main_view = sync(l);
      count_frame();
      submit_render(l, main_view);
      upload_feeds(l);
      if (std::optional<int> done = draw_frame(l)) return *done;
      // at most 30 frames a second (the main view renders at about that on a CPU rasteriser),
      // so the loop does not spin when there is little to do, e.g. when paused
      std::this_thread::sleep_until(now + std::chrono::microseconds(33333));
      if (!c_.screenshot.empty() && std::chrono::duration<double>(Clock::now() - start).count() > 120 + 20 * c_.after) {
        std::fprintf(stderr, "rescuesim: error: gave up waiting for a frame at sim time %.1f s for --screenshot\n", c_.after);
        return kExitFailure;
      }
    }
    return kExitOk;
  }

  /// Keeps the robot's laser and camera messages as they are published.
  void subscribe_feeds() {
    const auto keep = [this](const SensorSpec* spec, auto& into, bool& fresh) {
      if (spec == nullptr || !spec->enabled) return;
      sim_.bus().subscribe(sim_.topic_name(RobotIndex(0), spec->topic), [&into, &fresh](const Topic&, const msg::Message& m) {
        into = std::get<std::decay_t<decltype(into)>>(m);
        fresh = true;
      });
    };
    keep(sensors_.laser, feeds_.scan, feeds_.new_scan);
    keep(sensors_.color, feeds_.color, feeds_.new_color);
    keep(sensors_.depth, feeds_.depth, feeds_.new_depth);
    keep(sensors_.thermal, feeds_.thermal, feeds_.new_thermal);
  }

  /// Mouse: drag to orbit (pan with shift or the middle button), wheel to zoom; F toggles
  /// following the robot at `X_WB`.
  void handle_mouse(const ViewLayout& l, const Pose3& X_WB) {
    const ViewerMouse mouse = window_.mouse();
    const bool in_main = mouse.x < l.main_w && mouse.y > l.toolbar;
    const bool any_button = mouse.left || mouse.right || mouse.middle;
    if (any_button && !v_.dragging && in_main && !mouse.over_ui) v_.dragging = true;
    if (!any_button) v_.dragging = false;
    if (v_.dragging) {
      const double dx = mouse.x - v_.drag_x, dy = mouse.y - v_.drag_y;
      OrbitCamera& cam = v_.camera;
      if (mouse.middle || window_.key_down(ViewerKey::shift)) {
        cam.set_follow(false, X_WB);
        const double az = cam.yaw, k = 0.0015 * cam.distance;
        const Vec3 right(std::sin(az), -std::cos(az), 0), ahead(-std::cos(az), -std::sin(az), 0);
        cam.target += k * (-dx * right + dy * ahead);
      } else {
        cam.yaw -= 0.006 * dx;
        cam.pitch = std::clamp(cam.pitch + 0.006 * dy, -0.2, 1.55);
      }
    }
    v_.drag_x = mouse.x;
    v_.drag_y = mouse.y;
    if (in_main && !mouse.over_ui && mouse.scroll != 0)
      v_.camera.distance = std::clamp(v_.camera.distance * std::pow(0.88, mouse.scroll), 0.6, 80.0);
    const bool f = window_.key_down(ViewerKey::f);
    if (f && !v_.was_f) v_.camera.set_follow(!v_.camera.follow, X_WB);
    v_.was_f = f;
  }

  /// Keyboard teleop: any drive key (or space) takes over from the scenario's controller; I/K
  /// tilt the head and J/L turn the mast at 1 rad/s, within the joints' limits.
  void handle_teleop(double dt) {
    const auto held = [&](ViewerKey a, ViewerKey b) { return window_.key_down(a) || window_.key_down(b); };
    const double fwd = held(ViewerKey::up, ViewerKey::w) - held(ViewerKey::down, ViewerKey::s);
    const double turn = held(ViewerKey::left, ViewerKey::a) - held(ViewerKey::right, ViewerKey::d);
    if (fwd != 0 || turn != 0 || window_.key_down(ViewerKey::space)) v_.autonomous = false;
    v_.teleop = msg::Twist{};
    v_.teleop.linear.x() = 0.5 * fwd;
    v_.teleop.angular.z() = 1.0 * turn;
    if (v_.head.size() != HeadRoles::count) return;
    const double tilt = window_.key_down(ViewerKey::k) - window_.key_down(ViewerKey::i);
    const double pan = window_.key_down(ViewerKey::j) - window_.key_down(ViewerKey::l);
    if (tilt == 0 && pan == 0) return;
    const auto move = [&](std::size_t role, double rate) {
      v_.head[role] = std::clamp(v_.head[role] + rate * dt, head_joints_[role]->lower, head_joints_[role]->upper);
    };
    move(HeadRoles::head_tilt, tilt);
    move(HeadRoles::mast_yaw, pan);
    head_moved_ = true;
  }

  /// Holds the simulation still for a moment: hands over the controls and a moved head,
  /// copies the State, places the main view's camera (pulled in front of walls through the ray
  /// scene) and takes the sensor messages that arrived. Returns the main view.
  CameraView sync(const ViewLayout& l) {
    if (v_.step_request > 0) loop_->request_step(std::exchange(v_.step_request, 0.0f));
    loop_->set_controls(controls());
    const int mw = std::max(16, static_cast<int>(l.main_w)), mh = std::max(16, static_cast<int>(l.main_h));
    CameraView main_view;
    {
      const auto hold = loop_->lock();
      if (std::exchange(head_moved_, false)) sim_.command_head(RobotIndex(0), v_.head);
      state_ = sim_.state();
      trouble_ = sim_.in_trouble();
      main_view = v_.camera.view(state_.robots[0].base.X_WB, Intrinsics::from_hfov(mw, mh, 65 * std::numbers::pi / 180), sim_.ray_scene());
      std::swap(shown_, feeds_);
      feeds_.new_scan = feeds_.new_color = feeds_.new_depth = feeds_.new_thermal = false;
    }
    if (trouble_) v_.paused = true;
    return main_view;
  }

  /// Frames per second and the simulation's real-time factor, over about a second.
  void count_frame() {
    ++frames_;
    const double window_s = std::chrono::duration<double>(Clock::now() - fps_since_).count();
    if (window_s > 1.0) {
      v_.rtf = loop_->real_time_factor();
      v_.fps = frames_ / window_s;
      fps_since_ = Clock::now();
      frames_ = 0;
    }
  }

  /// Hands the render thread the State when it is free and the picture would change; uploads
  /// the main view it finished.
  void submit_render(const ViewLayout& l, const CameraView& main_view) {
    const int mw = std::max(16, static_cast<int>(l.main_w)), mh = std::max(16, static_cast<int>(l.main_h));
    const auto key = std::make_tuple(state_.step, main_view.X_WC.p, main_view.X_WC.q.coeffs(), mw, mh, v_.quality);
    if (!worker_.busy() && key != v_.drawn) {
      RenderRequest r;
      r.state = state_;
      r.main = main_view;
      r.quality = static_cast<Quality>(v_.quality);
      worker_.submit(std::move(r));
      v_.drawn = key;
    }
    if (std::optional<RenderFrame> fr = worker_.take()) {
      window_.upload("main", fr->main.width, fr->main.height, fr->main.rgb.data());
      v_.frame_time = fr->time;
      v_.render_ms = 1000 * fr->seconds;
    }
  }

  /// Sensor panels: each new message uploaded, in false colour where it needs one.
  void upload_feeds(const ViewLayout& l) {
    try {
      if (std::exchange(shown_.new_color, false)) {
        const ColorImage img = color_image_of(shown_.color);
        window_.upload("color", img.width, img.height, img.rgb.data());
        v_.color_time = shown_.color.header.stamp.seconds();
      }
      if (std::exchange(shown_.new_depth, false)) {
        const CameraSpec& cam = sensors_.depth->camera;
        const Canvas img = depth_canvas(depth_image_of(shown_.depth), cam.min_range, cam.max_range);
        window_.upload("depth", img.width(), img.height(), img.pixels().data());
      }
      if (std::exchange(shown_.new_thermal, false)) {
        const ThermalImage t = thermal_image_of(shown_.thermal);
        const Canvas img = thermal_canvas(t, sensors_.thermal->camera.mono8_min, sensors_.thermal->camera.mono8_max);
        window_.upload("thermal", img.width(), img.height(), img.pixels().data());
        v_.hottest = *std::max_element(t.kelvin.begin(), t.kelvin.end()) - 273.15;
      }
    } catch (const Error& e) {
      v_.feed_error = e.what();
    }
    if (std::exchange(shown_.new_scan, false)) {
      const Canvas plot = laser_canvas(shown_.scan, 2 * static_cast<int>(l.image_w), 2 * static_cast<int>(l.image_h), 5.0, 2);
      window_.upload("laser", plot.width(), plot.height(), plot.pixels().data());
    }
  }

  /// Draws the frame; with --screenshot, once sim time has passed --after and every panel has
  /// its first image, saves it and returns kExitOk.
  std::optional<int> draw_frame(const ViewLayout& l) {
    const auto ready = [&](const SensorSpec* spec, const char* tex) {
      return spec == nullptr || !spec->enabled || window_.texture(tex) != nullptr;
    };
    const double t = state_.time.seconds();
    const bool shoot = !c_.screenshot.empty() && t >= c_.after && v_.frame_time >= c_.after && ready(sensors_.laser, "laser") &&
                       ready(sensors_.color, "color") && ready(sensors_.depth, "depth") && ready(sensors_.thermal, "thermal");
    ColorImage shot;
    window_.frame([&] { draw_ui(l); }, shoot ? &shot : nullptr);
    if (!shoot) return std::nullopt;
    to_canvas(shot).write_png(c_.screenshot);
    std::printf("wrote %s (%dx%d px) at sim time %.2f s\n", c_.screenshot.c_str(), shot.width, shot.height, t);
    return kExitOk;
  }

  /// The ImGui frame: main view behind, toolbar, four sensor panels and an info panel.
  void draw_ui(const ViewLayout& l) {
    ImDrawList* bg = ImGui::GetBackgroundDrawList();
    if (void* t = window_.texture("main")) bg->AddImage(t, {0, l.toolbar}, {l.main_w, l.toolbar + l.main_h});
    else bg->AddText({20, l.toolbar + 20}, IM_COL32(220, 220, 220, 255), "rendering the main view ...");
    const char* mode = v_.camera.follow ? "following the robot (F: free camera)" : "free camera (F: follow the robot)";
    bg->AddRectFilled({0, l.toolbar + l.main_h - 22}, {l.main_w, l.toolbar + l.main_h}, IM_COL32(0, 0, 0, 140));
    bg->AddText({8, l.toolbar + l.main_h - 18}, IM_COL32(235, 235, 235, 255), mode);
    draw_toolbar(l);
    draw_panels(l);
    draw_info(l);
  }

  static constexpr ImGuiWindowFlags kFixed = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                             ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoScrollbar;

  /// Run/Pause, Step, speed, the run's time and victims, follow, autonomous, quality.
  void draw_toolbar(const ViewLayout& l) {
    const State& st = state_;
    int found = 0;
    for (const VictimState& vs : st.victims) found += vs.first_seen.ns >= 0;
    ImGui::SetNextWindowPos({0, 0});
    ImGui::SetNextWindowSize({static_cast<float>(window_.width()), l.toolbar});
    ImGui::Begin("toolbar", nullptr, kFixed | ImGuiWindowFlags_NoTitleBar);
    if (ImGui::Button(v_.paused ? "Run  " : "Pause")) v_.paused = !v_.paused;
    ImGui::SameLine();
    if (ImGui::Button("Step 0.1 s")) {
      v_.paused = true;
      v_.step_request = 0.1f;
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    ImGui::SliderFloat("speed", &v_.rate, 0.1f, 10.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
    ImGui::SameLine();
    ImGui::Text("| t = %.1f s | %.2fx real time | victims %d/%zu |", st.time.seconds(), v_.rtf, found, st.victims.size());
    ImGui::SameLine();
    bool follow = v_.camera.follow;
    if (ImGui::Checkbox("follow (F)", &follow)) v_.camera.set_follow(follow, st.robots[0].base.X_WB);
    ImGui::SameLine();
    if (has_controller_) ImGui::Checkbox("autonomous", &v_.autonomous);
    else ImGui::TextDisabled("no controller");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    ImGui::Combo("quality", &v_.quality, "low\0medium\0high\0");
    ImGui::End();
  }

  /// One sensor panel at (x, y): its image, or an empty box, and its legend.
  void panel(const ViewLayout& l, const SensorSpec* spec, const char* what, const char* tex, float x, float y,
             const std::function<void()>& legend) {
    const std::string size =
        spec == nullptr ? ""
        : spec->type == SensorSpec::Type::lidar
            ? fmt::format("{:.0f} deg, {} beams", (spec->lidar.max_angle - spec->lidar.min_angle) * 180 / std::numbers::pi,
                          spec->lidar.samples)
            : fmt::format("{}x{}", spec->camera.width, spec->camera.height);
    const std::string title = fmt::format("{} {}###{}", what, spec == nullptr ? "(none)" : !spec->enabled ? "(off)" : size, tex);
    ImGui::SetNextWindowPos({x, y});
    ImGui::SetNextWindowSize({l.panel_w, l.panel_h});
    ImGui::Begin(title.c_str(), nullptr, kFixed);
    if (void* t = window_.texture(tex)) ImGui::Image(t, {l.image_w, l.image_h});
    else ImGui::Dummy({l.image_w, l.image_h});
    if (spec != nullptr) legend();
    ImGui::End();
  }

  /// Clockwise from top right: colour, thermal, depth, laser (as in the paper's Fig. 2).
  void draw_panels(const ViewLayout& l) {
    const SensorSpec *depth = sensors_.depth, *thermal = sensors_.thermal;
    const float x0 = l.main_w, y1 = l.toolbar + l.panel_h;
    panel(l, sensors_.laser, "Laser", "laser", x0, l.toolbar, [&] { ImGui::TextUnformatted("top-down, forward up, rings every 1 m"); });
    panel(l, sensors_.color, "Colour camera", "color", x0 + l.panel_w, l.toolbar, [&] { ImGui::Text("image of %.2f s", v_.color_time); });
    panel(l, depth, "Depth camera", "depth", x0, y1, [&] {
      legend_bar(depth_color, fmt::format("{:g} m", depth->camera.min_range), fmt::format("{:g} m  (black: none)", depth->camera.max_range),
                 l.image_w);
    });
    panel(l, thermal, "Thermal camera", "thermal", x0 + l.panel_w, y1, [&] {
      legend_bar(iron_color, fmt::format("{:.0f} C", thermal->camera.mono8_min - 273.15),
                 fmt::format("max {:.1f} C   {:.0f} C", v_.hottest, thermal->camera.mono8_max - 273.15), l.image_w);
    });
  }

  /// Run facts, victims, problems and the controls.
  void draw_info(const ViewLayout& l) {
    const State& st = state_;
    const Scenario& s = session_.scenario();
    ImGui::SetNextWindowPos({l.main_w, l.info_y});
    ImGui::SetNextWindowSize({2 * l.panel_w, std::max(40.0f, window_.height() - l.info_y)});
    ImGui::Begin("Run###info", nullptr, kFixed);
    ImGui::Text("scenario %s, seed %llu: %s, %.0f fps, main view %.0f ms", s.name.c_str(), static_cast<unsigned long long>(s.seed),
                v_.autonomous ? "autonomous" : "teleop", v_.fps, v_.render_ms);
    for (std::size_t i = 0; i < st.victims.size(); ++i) {
      const VictimState& vs = st.victims[i];
      const char* name = sim_.world().victims[i].name.c_str();
      if (vs.first_seen.ns >= 0) ImGui::Text("%s: found at %.1f s by %s", name, vs.first_seen.seconds(), vs.seen_by.c_str());
      else ImGui::TextDisabled("%s: not found yet", name);
    }
    const ImVec4 red{1, 0.4f, 0.3f, 1};
    if (trouble_) ImGui::TextColored(red, "stopped: %s", st.trouble.first.c_str());
    if (const std::string e = loop_->error(); !e.empty()) ImGui::TextColored(red, "simulation: %s", e.c_str());
    if (!worker_.error().empty()) ImGui::TextColored(red, "render: %s", worker_.error().c_str());
    if (!v_.feed_error.empty()) ImGui::TextColored(red, "sensor image: %s", v_.feed_error.c_str());
    ImGui::Separator();
    ImGui::TextDisabled("mouse: drag to orbit, shift- or middle-drag to pan, wheel to zoom");
    ImGui::TextDisabled("keys: arrows/WASD drive, space stops (teleop), I/K head tilt,");
    ImGui::TextDisabled("      J/L mast, F follow, Esc quits");
    ImGui::TextDisabled("renderer: %s", worker_.device().c_str());
    ImGui::End();
  }

  const ViewCommand& c_;
  ViewerWindow& window_;
  Session& session_;
  Simulation& sim_;
  RenderWorker& worker_;
  const bool has_controller_;
  const RobotSpec& robot_;
  const FigureSensors sensors_;
  std::vector<const JointSpec*> head_joints_;  ///< in RobotSpec::head_joints order
  ViewerState v_;
  ViewSimLoop* loop_ = nullptr;  ///< the simulation thread, while run() runs
  SensorFeeds feeds_;            ///< filled on the simulation thread, under its lock
  SensorFeeds shown_;            ///< taken over by sync(), for the UI thread
  State state_;                  ///< the State as of the last sync()
  bool trouble_ = false;         ///< the simulation stopped on numerical trouble (as of the last sync())
  bool head_moved_ = false;      ///< head targets changed since the last sync()
  Clock::time_point last_, fps_since_;  ///< the previous frame; the start of the rate window
  int frames_ = 0;                      ///< frames in the rate window
};

/// Opens the window, loads the scenario and starts the render thread, then runs a Viewer.
int view(const ViewCommand& c) {
  // the window first: without a display nothing else is worth building
  std::unique_ptr<ViewerWindow> window;
  try {
    ViewerWindowOptions wo;
    wo.width = c.width;
    wo.height = c.height;
    wo.title = "rescuesim view";
    window = ViewerWindow::open(wo);
  } catch (const Error& e) {
    std::fprintf(stderr,
                 "rescuesim: error: rescuesim view needs a display; try xvfb-run -a rescuesim view, or rescuesim snapshot for a "
                 "headless figure\n  (%s)\n",
                 e.what());
    return kExitBadInput;
  }

  const ModelMap models = builtin_models();
  ScenarioOverrides overrides;
  overrides.seed = c.seed;
  const Scenario s = load_scenario_with_overrides(c.scenario, models, overrides);
  Session session(s, models);
  print_diagnostics(session.diagnostics());
  if (session.sim().world().robots.empty()) {
    std::fprintf(stderr, "rescuesim: error: scenario %s has no robot to show\n", s.name.c_str());
    return kExitBadInput;
  }
  const bool has_controller = robot_configs(s, session.world_spec(), models)[0].controller != "none";
  const Quality quality = c.quality == "high" ? Quality::high : c.quality == "medium" ? Quality::medium : Quality::low;
  std::unique_ptr<RenderWorker> worker;
  try {
    worker = std::make_unique<RenderWorker>(session.sim().world(), quality);
  } catch (const Error& e) {
    std::fprintf(stderr, "rescuesim: error: %s\n", e.what());
    return kExitBadInput;
  }
  Viewer viewer(c, *window, session, *worker, has_controller);
  std::printf("rescuesim view: scenario %s (seed %llu), rendering with %s\n", s.name.c_str(), static_cast<unsigned long long>(s.seed),
              worker->device().c_str());
  std::fflush(stdout);
  return viewer.run();
}

}  // namespace

void add_view_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<ViewCommand>();
  CLI::App* cmd = app.add_subcommand("view", "Watch and drive a scenario in a window: 3D view and live sensor panels");
  cmd->footer(
      "A window with the main 3D view on the left and the robot's sensors on the right, clockwise\n"
      "from top right: colour camera, thermal camera, depth camera, laser (the jmeSim paper's\n"
      "Fig. 2), above a panel listing the victims. The scenario runs in real time (speed slider,\n"
      "Pause, Step 0.1 s in the toolbar); its own controller drives until you take over.\n\n"
      "Mouse: drag to orbit, shift-drag or middle-drag to pan, wheel to zoom; F follows the robot.\n"
      "Keys: arrows or WASD drive (0.5 m/s, 1 rad/s), space stops; I/K tilt the head, J/L turn\n"
      "the mast; Esc quits. Tick 'autonomous' to give the robot back to its controller.\n\n"
      "Needs a display (X11); on a machine without one use xvfb-run, or rescuesim snapshot for a\n"
      "headless figure. --screenshot saves the window as PNG once --after seconds of sim time\n"
      "have passed, then exits (how CI checks the viewer).\n\n"
      "Examples:\n"
      "  rescuesim view\n"
      "  rescuesim view worlds/arena.yaml --seed 3 --quality medium\n"
      "  xvfb-run -a rescuesim view --screenshot view.png --after 5");
  cmd->add_option("scenario", c->scenario,
                  "scenario YAML file (default: built-in); a relative path not found here is looked for in the installed worlds")
      ->transform(data_file());
  cmd->add_option("--seed", c->seed, "run seed (overrides the scenario's; also reseeds a generated maze)");
  cmd->add_option("--quality", c->quality, "main view quality: low, medium or high")
      ->capture_default_str()
      ->check(CLI::IsMember({"low", "medium", "high"}));
  cmd->add_option("--rate", c->rate, "sim seconds per wall second to start with")->capture_default_str()->check(CLI::Range(0.1, 10.0));
  cmd->add_option("--width", c->width, "window width in px")->capture_default_str()->check(CLI::Range(640, 8192));
  cmd->add_option("--height", c->height, "window height in px")->capture_default_str()->check(CLI::Range(480, 8192));
  cmd->add_option("--screenshot", c->screenshot, "save the window to this PNG after --after s of sim time, then exit");
  cmd->add_option("--after", c->after, "sim seconds before --screenshot")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->final_callback([c, &action] { action = [c] { return view(*c); }; });
}

}  // namespace rescuesim::app
