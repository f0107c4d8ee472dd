// rescuesim snapshot: the seed paper's Fig. 2 as a PNG, headless. Runs a scenario in lockstep
// to a sim time, renders a chase view of the robot, and composes it with the last images and
// scan the robot's sensors published (src/app/figure.h).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <type_traits>

#include <fmt/format.h>

#include "app/commands.h"
#include "app/data_dir.h"
#include "app/figure.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "robots/rescue_robot.h"
#include "sensors/camera/camera.h"
#include "session/scenario_load.h"
#include "session/session.h"

namespace rescuesim::app {

namespace {

struct SnapshotCommand {
  std::string scenario;
  double time = 20.0;
  std::string out = "snapshot.png";
  std::optional<std::uint64_t> seed;
  int width = 1600;
  std::string quality = "medium";
};

Quality parse_quality(const std::string& q) {
  if (q == "low") return Quality::low;
  if (q == "high") return Quality::high;
  return Quality::medium;
}

int snapshot(const SnapshotCommand& c) {
  // the renderer first: without one there is nothing to draw, so fail before simulating
  std::unique_ptr<Renderer> renderer;
  try {
    renderer = Renderer::create_headless(parse_quality(c.quality));
  } catch (const Error& e) {
    std::fprintf(stderr, "rescuesim: error: %s\n", e.what());
    return kExitBadInput;
  }

  const ModelMap models = builtin_models();
  ScenarioOverrides overrides;
  overrides.seed = c.seed;
  const Scenario s = load_scenario_with_overrides(c.scenario, models, overrides);
  Session session(s, models);
  print_diagnostics(session.diagnostics());
  Simulation& sim = session.sim();
  if (sim.world().robots.empty()) {
    std::fprintf(stderr, "rescuesim: error: scenario %s has no robot to show\n", s.name.c_str());
    return kExitBadInput;
  }

  // keep the robot's last laser scan and camera images, as its sensors published them
  const FigureSensors sensors = figure_sensors(sim.world().robots[0].spec);
  const SensorSpec *laser = sensors.laser, *color = sensors.color, *depth = sensors.depth, *thermal = sensors.thermal;
  msg::LaserScan scan;
  msg::Image color_msg, thermal_msg, depth_msg;
  const auto keep = [&sim](const SensorSpec* spec, auto& into) {
    if (spec == nullptr || !spec->enabled) return;
    sim.bus().subscribe(sim.topic_name(RobotIndex(0), spec->topic),
                        [&into](const Topic&, const msg::Message& m) { into = std::get<std::decay_t<decltype(into)>>(m); });
  };
  keep(laser, scan);
  keep(color, color_msg);
  keep(thermal, thermal_msg);
  keep(depth, depth_msg);

  // run the scenario (its own controllers drive) to the requested time
  std::printf("scenario %s (seed %llu): simulating %.1f s ...\n", s.name.c_str(), static_cast<unsigned long long>(s.seed), c.time);
  std::fflush(stdout);
  const bool ok = sim.step_until(SimTime::from_seconds(c.time));
  if (!ok) std::fprintf(stderr, "rescuesim: warning: the simulation stopped early: %s\n", sim.state().trouble.first.c_str());
  const State& state = sim.state();

  // the main view: the chase camera, raised or moved in when a wall would hide the robot
  const FigureLayout layout = figure_layout(c.width);
  RenderScene scene = build_render_scene(sim.world());
  update_render_scene(scene, state);
  renderer->load(scene);
  FigureInputs in;
  in.width = c.width;
  const Pose3& X_WB = state.robots[0].base.X_WB;
  const ChasePoints chase = chase_points(X_WB);
  const Vec3 eye = clear_eye(sim.ray_scene(), chase.eye, chase.target, X_WB.p, RobotIndex(0));
  in.main = renderer->color(look_at_view(eye, chase.target, Intrinsics::from_hfov(layout.main.w, layout.main.h, 65 * M_PI / 180)));
  in.main_caption = fmt::format("main view: chase camera {} m back, {:.1f} m up{}, quality {}", kChaseBack, eye.z() - X_WB.p.z(),
                                (eye - chase.eye).norm() > 1e-6 ? " (over wall)" : "", c.quality);

  // the sensor panels: the last published images (a camera that is off shows as such)
  const auto name = [](const SensorSpec* spec, const char* what) {
    return spec == nullptr  ? fmt::format("no {}", what)
           : !spec->enabled ? fmt::format("{} off", what)
                            : fmt::format("{} {}x{}", what, spec->camera.width, spec->camera.height);
  };
  in.color_caption = name(color, "colour camera");
  if (!color_msg.data.empty()) in.color = color_image_of(color_msg);
  in.depth_caption = depth != nullptr && depth->enabled ? "depth camera (black: none)" : name(depth, "depth camera");
  if (depth != nullptr) {
    in.depth_min = depth->camera.min_range;
    in.depth_max = depth->camera.max_range;
    if (!depth_msg.data.empty()) in.depth = depth_image_of(depth_msg);
  }
  in.thermal_caption = name(thermal, "thermal camera");
  if (thermal != nullptr) {
    in.thermal_min = thermal->camera.mono8_min;
    in.thermal_max = thermal->camera.mono8_max;
    if (!thermal_msg.data.empty()) {
      in.thermal = thermal_image_of(thermal_msg);
      const float hottest = *std::max_element(in.thermal.kelvin.begin(), in.thermal.kelvin.end());
      in.thermal_caption = fmt::format("thermal camera, max {:.1f} C", hottest - 273.15);
    }
  }
  in.scan = scan;
  in.laser_radius = laser != nullptr ? std::min(5.0, laser->lidar.max_range) : 5.0;
  in.laser_caption = laser != nullptr
                         ? fmt::format("laser {:.0f} deg, 1 m rings", (laser->lidar.max_angle - laser->lidar.min_angle) * 180 / M_PI)
                         : std::string("no laser");

  int found = 0;
  for (const VictimState& v : state.victims) found += v.first_seen.ns >= 0;
  in.title = fmt::format("rescuesim | scenario {} | seed {} | t = {:.1f} s | victims found {}/{}", s.name, s.seed,
                         state.time.seconds(), found, state.victims.size());

  const Canvas fig = compose_figure(in);
  fig.write_png(c.out);
  std::printf("wrote %s (%dx%d px; %s)\n", c.out.c_str(), fig.width(), fig.height(), renderer->device().c_str());
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void add_snapshot_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<SnapshotCommand>();
  CLI::App* cmd = app.add_subcommand("snapshot", "Render the paper's Fig. 2: a robot's view and its sensors at a sim time, as PNG");
  cmd->footer(
      "Runs the scenario headless (its built-in controllers drive the robot) to --time, then\n"
      "renders a figure like Fig. 2 of the jmeSim paper: on the left a chase camera 2.5 m behind\n"
      "and 1.8 m above the robot (raised, or moved in, when a wall would hide it); on the right,\n"
      "clockwise from top right, the last images the robot's sensors published: colour camera,\n"
      "thermal camera (iron colours over its temperature window, in degrees C), depth camera\n"
      "(colours in metres, black = no return) and the laser scan seen from above (robot at the\n"
      "centre, forward up, 1 m rings). Cameras publish at about 10 Hz, so their images are up to\n"
      "0.2 s older than the main view.\n\n"
      "Size: --width W gives W x (about 0.42 W) px; the default 1600 gives 1600 x 669.\n"
      "Rendering uses OpenGL through EGL (no display needed; llvmpipe works); without it the\n"
      "command exits with code 2 and the reason.\n\n"
      "Examples:\n"
      "  rescuesim snapshot --time 30 --out fig2.png\n"
      "  rescuesim snapshot worlds/arena.yaml --seed 3 --quality high --width 2400\n"
      "  xvfb-run -a rescuesim view            the same picture, live, in a window");
  cmd->add_option("scenario", c->scenario,
                  "scenario YAML file (default: built-in); a relative path not found here is looked for in the installed worlds")
      ->transform(data_file());
  cmd->add_option("--time,-t", c->time, "sim time to run to, in seconds")->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--out,-o", c->out, "PNG file to write (atomically)")->capture_default_str();
  cmd->add_option("--seed", c->seed, "run seed (overrides the scenario's; also reseeds a generated maze)");
  cmd->add_option("--width", c->width, "figure width in px")->capture_default_str()->check(CLI::Range(kFigureMinWidth, kFigureMaxWidth));
  cmd->add_option("--quality", c->quality, "main view quality: low, medium or high")
      ->capture_default_str()
      ->check(CLI::IsMember({"low", "medium", "high"}));
  cmd->final_callback([c, &action] { action = [c] { return snapshot(*c); }; });
}

}  // namespace rescuesim::app
