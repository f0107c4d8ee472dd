// rescuesim view: the interactive viewer. A window with the main 3D view (orbit camera or
// following the robot), keyboard teleop, and the robot's sensor feeds live in the seed paper's
// Fig. 2 layout. No GL here: the window (render/viewer_window.h) shows CPU images.
//
// Threads: the UI thread owns the window and the simulation, stepping it in realtime between
// frames; the sensor panels show the images the robot's sensors publish on the Bus (rendered by
// the session's own camera thread). A render thread of ours owns a headless Renderer for the
// main view (its own EGL context: one thread cannot hold the window's GLX context and an EGL
// one at once) and draws State copies handed to it at whatever rate it manages.

#include <imgui.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <future>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>

#include <fmt/format.h>

#include "app/commands.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "render/viewer_window.h"
#include "robots/rescue_robot.h"
#include "session/figure.h"
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

/// One frame for the render thread: a State copy and where the main camera is.
struct RenderRequest {
  State state;
  CameraView main;
  Quality quality = Quality::low;
};

/// What the render thread hands back: the main view.
struct RenderFrame {
  double time = 0;     ///< sim time of the State drawn (s)
  double seconds = 0;  ///< wall time the frame took to render
  ColorImage main;
};

/// The render thread: one pending request (a newer one replaces it), one finished frame.
class RenderWorker {
 public:
  /// Starts the thread and its renderer; throws Error when no renderer can be made.
  RenderWorker(const World& world, Quality q) : world_(world) {
    std::promise<std::string> started;
    auto result = started.get_future();
    thread_ = std::thread([this, q, &started] { run(q, started); });
    const std::string error = result.get();
    if (!error.empty()) {
      thread_.join();
      throw Error(error);
    }
  }

  ~RenderWorker() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  /// True while a request waits or is being drawn.
  bool busy() const {
    const std::lock_guard lock(mutex_);
    return pending_.has_value() || drawing_;
  }
  void submit(RenderRequest r) {
    {
      const std::lock_guard lock(mutex_);
      pending_ = std::move(r);
    }
    wake_.notify_all();
  }
  /// The latest finished frame, once.
  std::optional<RenderFrame> take() {
    const std::lock_guard lock(mutex_);
    return std::exchange(done_, std::nullopt);
  }
  /// The last rendering problem ("" when none).
  std::string error() const {
    const std::lock_guard lock(mutex_);
    return error_;
  }
  const std::string& device() const { return device_; }

 private:
  void run(Quality q, std::promise<std::string>& started) {
    std::unique_ptr<Renderer> renderer;
    RenderScene scene;
    try {
      renderer = Renderer::create_headless(q);
      scene = build_render_scene(world_);
      renderer->load(scene);
      device_ = renderer->device();
    } catch (const std::exception& e) {
      started.set_value(e.what());
      return;
    }
    started.set_value("");
    for (;;) {
      RenderRequest r;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
        if (stop_) return;
        r = std::move(*pending_);
        pending_.reset();
        drawing_ = true;
      }
      RenderFrame f;
      std::string problem;
      const auto t0 = Clock::now();
      try {
        draw(*renderer, scene, r, f);
      } catch (const std::exception& e) {
        problem = e.what();
      }
      f.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      const std::lock_guard lock(mutex_);
      drawing_ = false;
      error_ = problem;
      if (problem.empty()) done_ = std::move(f);
    }
  }

  static void draw(Renderer& renderer, RenderScene& scene, const RenderRequest& r, RenderFrame& f) {
    update_render_scene(scene, r.state);
    renderer.update(scene);
    renderer.set_quality(r.quality);
    f.time = r.state.time.seconds();
    renderer.color(r.main, f.main);
  }

  const World& world_;
  std::string device_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RenderRequest> pending_;
  std::optional<RenderFrame> done_;
  bool drawing_ = false, stop_ = false;
  std::string error_;
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
      az = heading + M_PI + yaw;
    }
    const Vec3 eye = t + distance * Vec3(std::cos(pitch) * std::cos(az), std::cos(pitch) * std::sin(az), std::sin(pitch));
    return look_at_view(follow ? clear_eye(scene, eye, t, X_WB.p, 0) : eye, t, k);
  }
  /// Switches between following and a free camera without a jump.
  void set_follow(bool on, const Pose3& X_WB) {
    if (on == follow) return;
    const double heading = X_WB.yaw();
    if (!on) {
      target = X_WB.p + kChaseAhead * Vec3(std::cos(heading), std::sin(heading), 0) + Vec3(0, 0, kChaseAim);
      yaw = heading + M_PI + yaw;
    } else {
      yaw = wrap_angle(yaw - heading - M_PI);
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
  std::vector<double> head;     ///< head joint targets (rad)
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
  Scenario s = c.scenario.empty() ? default_scenario(models) : load_scenario(c.scenario, models);
  if (c.seed) {
    s.seed = *c.seed;
    if (s.maze) s.maze->seed = *c.seed;
  }
  Session session(s, models);
  print_diagnostics(session.diagnostics());
  Simulation& sim = session.sim();
  if (sim.world().robots.empty()) {
    std::fprintf(stderr, "rescuesim: error: scenario %s has no robot to show\n", s.name.c_str());
    return kExitBadInput;
  }
  const RobotSpec& robot = sim.world().robots[0].spec;
  const FigureSensors sensors = figure_sensors(robot);
  const SensorSpec *laser = sensors.laser, *color = sensors.color, *depth = sensors.depth, *thermal = sensors.thermal;
  const bool has_controller = robot_configs(s, session.world_spec(), models)[0].controller != "none";

  ViewerState v;
  v.autonomous = has_controller;
  v.rate = static_cast<float>(c.rate);
  v.quality = c.quality == "high" ? 2 : c.quality == "medium" ? 1 : 0;
  std::unique_ptr<RenderWorker> worker;
  try {
    worker = std::make_unique<RenderWorker>(sim.world(), static_cast<Quality>(v.quality));
  } catch (const Error& e) {
    std::fprintf(stderr, "rescuesim: error: %s\n", e.what());
    return kExitBadInput;
  }

  // the sensor feeds, kept from the Bus as published (the UI thread steps, so callbacks run here)
  msg::LaserScan scan;
  msg::Image color_msg, depth_msg, thermal_msg;
  bool new_scan = false, new_color = false, new_depth = false, new_thermal = false;
  const auto keep = [&sim](const SensorSpec* spec, auto& into, bool& fresh) {
    if (spec == nullptr || !spec->enabled) return;
    sim.bus().subscribe(sim.topic_name(0, spec->topic), [&into, &fresh](const Topic&, const msg::Message& m) {
      into = std::get<std::decay_t<decltype(into)>>(m);
      fresh = true;
    });
  };
  keep(laser, scan, new_scan);
  keep(color, color_msg, new_color);
  keep(depth, depth_msg, new_depth);
  keep(thermal, thermal_msg, new_thermal);
  // head joints start at their initial positions, within their limits
  std::vector<const JointSpec*> head_joints;
  for (const std::string& name : robot.head_joints) {
    head_joints.push_back(&robot.joints[static_cast<std::size_t>(robot.joint_index(name))]);
    v.head.push_back(head_joints.back()->initial);
  }

  std::printf("rescuesim view: scenario %s (seed %llu), rendering with %s\n", s.name.c_str(), static_cast<unsigned long long>(s.seed),
              worker->device().c_str());
  std::fflush(stdout);
  const auto start = Clock::now();
  auto last = start, rtf_since = start;
  double rtf_sim_since = 0;
  int frames = 0;

  for (;;) {
    // paused with nothing left to draw: idle until input (or a tenth of a second)
    window->poll(v.paused && v.step_request == 0 && !worker->busy() ? 0.1 : 0);
    if (window->should_close() || window->key_down(ViewerKey::escape)) break;
    const auto now = Clock::now();
    const double dt = std::min(0.1, std::chrono::duration<double>(now - last).count());
    last = now;
    const ViewLayout l = view_layout(window->width(), window->height());
    const Pose3 X_WB = sim.state().robots[0].base.X_WB;

    // mouse: drag to orbit (pan with shift or the middle button), wheel to zoom
    const ViewerMouse mouse = window->mouse();
    const bool in_main = mouse.x < l.main_w && mouse.y > l.toolbar;
    const bool any_button = mouse.left || mouse.right || mouse.middle;
    if (any_button && !v.dragging && in_main && !mouse.over_ui) v.dragging = true;
    if (!any_button) v.dragging = false;
    if (v.dragging) {
      const double dx = mouse.x - v.drag_x, dy = mouse.y - v.drag_y;
      if (mouse.middle || window->key_down(ViewerKey::shift)) {
        v.camera.set_follow(false, X_WB);
        const double az = v.camera.yaw, k = 0.0015 * v.camera.distance;
        const Vec3 right(std::sin(az), -std::cos(az), 0), ahead(-std::cos(az), -std::sin(az), 0);
        v.camera.target += k * (-dx * right + dy * ahead);
      } else {
        v.camera.yaw -= 0.006 * dx;
        v.camera.pitch = std::clamp(v.camera.pitch + 0.006 * dy, -0.2, 1.55);
      }
    }
    v.drag_x = mouse.x;
    v.drag_y = mouse.y;
    if (in_main && !mouse.over_ui && mouse.scroll != 0) v.camera.distance = std::clamp(v.camera.distance * std::pow(0.88, mouse.scroll), 0.6, 80.0);
    const bool f = window->key_down(ViewerKey::f);
    if (f && !v.was_f) v.camera.set_follow(!v.camera.follow, X_WB);
    v.was_f = f;

    // keyboard teleop: any drive key (or space) takes over from the scenario's controller
    const auto held = [&](ViewerKey a, ViewerKey b) { return window->key_down(a) || window->key_down(b); };
    const double fwd = held(ViewerKey::up, ViewerKey::w) - held(ViewerKey::down, ViewerKey::s);
    const double turn = held(ViewerKey::left, ViewerKey::a) - held(ViewerKey::right, ViewerKey::d);
    if (fwd != 0 || turn != 0 || window->key_down(ViewerKey::space)) v.autonomous = false;
    v.teleop = msg::Twist{};
    v.teleop.linear.x() = 0.5 * fwd;
    v.teleop.angular.z() = 1.0 * turn;
    // head: I/K tilt (up/down), J/L mast yaw (left/right)
    if (v.head.size() == 4) {
      const double tilt = window->key_down(ViewerKey::k) - window->key_down(ViewerKey::i);
      const double pan = window->key_down(ViewerKey::j) - window->key_down(ViewerKey::l);
      if (tilt != 0 || pan != 0) {
        v.head[3] = std::clamp(v.head[3] + tilt * dt, head_joints[3]->lower, head_joints[3]->upper);
        v.head[0] = std::clamp(v.head[0] + pan * dt, head_joints[0]->lower, head_joints[0]->upper);
        sim.command_head(0, v.head);
      }
    }

    // step the simulation towards the wall clock x rate, for at most 40 ms of wall time a frame;
    // in teleop each step's command comes after the controller's, so it wins
    const double sim_before = sim.time().seconds();
    double advance = v.paused ? std::exchange(v.step_request, 0.0f) : dt * v.rate;
    const SimTime target = sim.time() + SimTime::from_seconds(advance);
    const auto budget = Clock::now() + std::chrono::milliseconds(40);
    while (sim.time() < target && Clock::now() < budget && !sim.in_trouble()) {
      sim.step();
      if (!v.autonomous) sim.command_velocity(0, v.teleop);
    }
    if (sim.in_trouble()) v.paused = true;
    rtf_sim_since += sim.time().seconds() - sim_before;
    ++frames;
    const double window_s = std::chrono::duration<double>(Clock::now() - rtf_since).count();
    if (window_s > 1.0) {
      v.rtf = rtf_sim_since / window_s;
      v.fps = frames / window_s;
      rtf_since = Clock::now();
      rtf_sim_since = 0;
      frames = 0;
    }

    // hand the render thread the State when it is free and the picture would change; upload
    // what it finished
    const int mw = std::max(16, static_cast<int>(l.main_w)), mh = std::max(16, static_cast<int>(l.main_h));
    const CameraView main_view = v.camera.view(sim.state().robots[0].base.X_WB, Intrinsics::from_hfov(mw, mh, 65 * M_PI / 180), sim.ray_scene());
    const auto key = std::make_tuple(sim.state().step, main_view.X_WC.p, main_view.X_WC.q.coeffs(), mw, mh, v.quality);
    if (!worker->busy() && key != v.drawn) {
      RenderRequest r;
      r.state = sim.state();
      r.main = main_view;
      r.quality = static_cast<Quality>(v.quality);
      worker->submit(std::move(r));
      v.drawn = key;
    }
    if (std::optional<RenderFrame> fr = worker->take()) {
      window->upload("main", fr->main.width, fr->main.height, fr->main.rgb.data());
      v.frame_time = fr->time;
      v.render_ms = 1000 * fr->seconds;
    }
    // sensor panels: each new message, in false colour where it needs one
    try {
      if (std::exchange(new_color, false)) {
        const ColorImage img = color_image_of(color_msg);
        window->upload("color", img.width, img.height, img.rgb.data());
        v.color_time = color_msg.header.stamp.seconds();
      }
      if (std::exchange(new_depth, false)) {
        const Canvas img = depth_canvas(depth_image_of(depth_msg), depth->camera.min_range, depth->camera.max_range);
        window->upload("depth", img.width(), img.height(), img.pixels().data());
      }
      if (std::exchange(new_thermal, false)) {
        const ThermalImage t = thermal_image_of(thermal_msg);
        const Canvas img = thermal_canvas(t, thermal->camera.mono8_min, thermal->camera.mono8_max);
        window->upload("thermal", img.width(), img.height(), img.pixels().data());
        v.hottest = *std::max_element(t.kelvin.begin(), t.kelvin.end()) - 273.15;
      }
    } catch (const Error& e) {
      v.feed_error = e.what();
    }
    if (std::exchange(new_scan, false)) {
      const Canvas plot = laser_canvas(scan, 2 * static_cast<int>(l.image_w), 2 * static_cast<int>(l.image_h), 5.0, 2);
      window->upload("laser", plot.width(), plot.height(), plot.pixels().data());
    }

    // the frame: main view behind, toolbar, four sensor panels and an info panel
    const State& st = sim.state();
    int found = 0;
    for (const VictimState& vs : st.victims) found += vs.first_seen.ns >= 0;
    const auto ui = [&] {
      const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoScrollbar;
      ImDrawList* bg = ImGui::GetBackgroundDrawList();
      if (void* t = window->texture("main")) bg->AddImage(t, {0, l.toolbar}, {l.main_w, l.toolbar + l.main_h});
      else bg->AddText({20, l.toolbar + 20}, IM_COL32(220, 220, 220, 255), "rendering the main view ...");
      const char* mode = v.camera.follow ? "following the robot (F: free camera)" : "free camera (F: follow the robot)";
      bg->AddRectFilled({0, l.toolbar + l.main_h - 22}, {l.main_w, l.toolbar + l.main_h}, IM_COL32(0, 0, 0, 140));
      bg->AddText({8, l.toolbar + l.main_h - 18}, IM_COL32(235, 235, 235, 255), mode);

      ImGui::SetNextWindowPos({0, 0});
      ImGui::SetNextWindowSize({static_cast<float>(window->width()), l.toolbar});
      ImGui::Begin("toolbar", nullptr, fixed | ImGuiWindowFlags_NoTitleBar);
      if (ImGui::Button(v.paused ? "Run  " : "Pause")) v.paused = !v.paused;
      ImGui::SameLine();
      if (ImGui::Button("Step 0.1 s")) {
        v.paused = true;
        v.step_request = 0.1f;
      }
      ImGui::SameLine();
      ImGui::SetNextItemWidth(120);
      ImGui::SliderFloat("speed", &v.rate, 0.1f, 10.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
      ImGui::SameLine();
      ImGui::Text("| t = %.1f s | %.2fx real time | victims %d/%zu |", st.time.seconds(), v.rtf, found, st.victims.size());
      ImGui::SameLine();
      bool follow = v.camera.follow;
      if (ImGui::Checkbox("follow (F)", &follow)) v.camera.set_follow(follow, st.robots[0].base.X_WB);
      ImGui::SameLine();
      if (has_controller) ImGui::Checkbox("autonomous", &v.autonomous);
      else ImGui::TextDisabled("no controller");
      ImGui::SameLine();
      ImGui::SetNextItemWidth(80);
      ImGui::Combo("quality", &v.quality, "low\0medium\0high\0");
      ImGui::End();

      // clockwise from top right: colour, thermal, depth, laser (as in the paper's Fig. 2)
      const auto panel = [&](const SensorSpec* spec, const char* what, const char* tex, float x, float y, const std::function<void()>& legend) {
        const std::string size = spec == nullptr ? "" : spec->type == SensorSpec::Type::lidar ? fmt::format("{:.0f} deg, {} beams", (spec->lidar.max_angle - spec->lidar.min_angle) * 180 / M_PI, spec->lidar.samples)
                                                                                              : fmt::format("{}x{}", spec->camera.width, spec->camera.height);
        const std::string title = fmt::format("{} {}###{}", what, spec == nullptr ? "(none)" : !spec->enabled ? "(off)" : size, tex);
        ImGui::SetNextWindowPos({x, y});
        ImGui::SetNextWindowSize({l.panel_w, l.panel_h});
        ImGui::Begin(title.c_str(), nullptr, fixed);
        if (void* t = window->texture(tex)) ImGui::Image(t, {l.image_w, l.image_h});
        else ImGui::Dummy({l.image_w, l.image_h});
        if (spec != nullptr) legend();
        ImGui::End();
      };
      const float x0 = l.main_w, y1 = l.toolbar + l.panel_h;
      panel(laser, "Laser", "laser", x0, l.toolbar, [&] { ImGui::TextUnformatted("top-down, forward up, rings every 1 m"); });
      panel(color, "Colour camera", "color", x0 + l.panel_w, l.toolbar, [&] { ImGui::Text("image of %.2f s", v.color_time); });
      panel(depth, "Depth camera", "depth", x0, y1, [&] {
        legend_bar(depth_color, fmt::format("{:g} m", depth->camera.min_range), fmt::format("{:g} m  (black: none)", depth->camera.max_range), l.image_w);
      });
      panel(thermal, "Thermal camera", "thermal", x0 + l.panel_w, y1, [&] {
        legend_bar(iron_color, fmt::format("{:.0f} C", thermal->camera.mono8_min - 273.15),
                   fmt::format("max {:.1f} C   {:.0f} C", v.hottest, thermal->camera.mono8_max - 273.15), l.image_w);
      });

      // run facts, victims and the controls
      ImGui::SetNextWindowPos({x0, l.info_y});
      ImGui::SetNextWindowSize({2 * l.panel_w, std::max(40.0f, window->height() - l.info_y)});
      ImGui::Begin("Run###info", nullptr, fixed);
      ImGui::Text("scenario %s, seed %llu: %s, %.0f fps, main view %.0f ms", s.name.c_str(), static_cast<unsigned long long>(s.seed),
                  v.autonomous ? "autonomous" : "teleop", v.fps, v.render_ms);
      for (std::size_t i = 0; i < st.victims.size(); ++i) {
        const VictimState& vs = st.victims[i];
        const char* name = sim.world().victims[i].name.c_str();
        if (vs.first_seen.ns >= 0) ImGui::Text("%s: found at %.1f s by %s", name, vs.first_seen.seconds(), vs.seen_by.c_str());
        else ImGui::TextDisabled("%s: not found yet", name);
      }
      const ImVec4 red{1, 0.4f, 0.3f, 1};
      if (sim.in_trouble()) ImGui::TextColored(red, "stopped: %s", st.trouble.first.c_str());
      if (!worker->error().empty()) ImGui::TextColored(red, "render: %s", worker->error().c_str());
      if (!v.feed_error.empty()) ImGui::TextColored(red, "sensor image: %s", v.feed_error.c_str());
      ImGui::Separator();
      ImGui::TextDisabled("mouse: drag to orbit, shift- or middle-drag to pan, wheel to zoom");
      ImGui::TextDisabled("keys: arrows/WASD drive, space stops (teleop), I/K head tilt,");
      ImGui::TextDisabled("      J/L mast, F follow, Esc quits");
      ImGui::TextDisabled("renderer: %s", worker->device().c_str());
      ImGui::End();
    };

    // --screenshot: once sim time has passed --after and every panel has its first image
    const auto ready = [&](const SensorSpec* spec, const char* tex) { return spec == nullptr || !spec->enabled || window->texture(tex) != nullptr; };
    const bool shoot = !c.screenshot.empty() && st.time.seconds() >= c.after && v.frame_time >= c.after && ready(laser, "laser") &&
                       ready(color, "color") && ready(depth, "depth") && ready(thermal, "thermal");
    ColorImage shot;
    window->frame(ui, shoot ? &shot : nullptr);
    if (shoot) {
      to_canvas(shot).write_png(c.screenshot);
      std::printf("wrote %s (%dx%d px) at sim time %.2f s\n", c.screenshot.c_str(), shot.width, shot.height, st.time.seconds());
      return kExitOk;
    }
    // at most 30 frames a second (the main view renders at about that on a CPU rasteriser), so
    // the loop does not spin when there is little to do, e.g. when paused
    std::this_thread::sleep_until(now + std::chrono::microseconds(33333));
    if (!c.screenshot.empty() && std::chrono::duration<double>(Clock::now() - start).count() > 120 + 20 * c.after) {
      std::fprintf(stderr, "rescuesim: error: gave up waiting for a frame at sim time %.1f s for --screenshot\n", c.after);
      return kExitFailure;
    }
  }
  return kExitOk;
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
  cmd->add_option("scenario", c->scenario, "scenario YAML file (default: built-in)");
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
