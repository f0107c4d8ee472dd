// The `bench` command of rescuesim-bench (`rescuesim bench` forwards to it): every speed figure
// beside a raw baseline measured in the same run, and the default run's peak memory. Speed goals
// live here, not in tests.

#include "bench/bench_command.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <thread>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/data_dir.h"
#include "bench/bench_batch.h"
#include "bench/bench_child.h"
#include "bench/bench_cold_start.h"
#include "bench/bench_control.h"
#include "bench/bench_figures.h"
#include "bench/bench_mission.h"
#include "bench/bench_reset.h"
#include "bench/bench_ros.h"
#include "bench/bench_scale.h"
#include "bench/bench_sdf.h"
#include "bench/bench_soak.h"
#include "bench/bench_urdf.h"
#include "core/atomic_file.h"
#include "physics/bench/bare_bullet.h"
#include "physics/physics.h"
#include "raycast/bench/raycast_bench.h"
#include "render/bench/render_bench.h"
#include "render/renderer.h"
#include "robots/drive_controller.h"
#include "robots/rescue_robot.h"
#include "sensors/camera/camera.h"
#include "sensors/lidar.h"
#include "session/session.h"
#ifdef RESCUESIM_HAS_MCAP
#include "bridges/mcap/mcap_bridge.h"
#include "run_record/run_record.h"
#endif

namespace rescuesim::bench {

using app::Action;
using app::kExitOk;

namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

struct BenchOptions {
  std::string out;
  double seconds = 1.0;        ///< per ray measurement
  double scenario_time = 180;  ///< sim seconds of the default scenario
  int physics_steps = 4000;
  int batch_trials = 4;                                       ///< per batch measurement (0: skip)
  bool ros = true;                                            ///< the ROS figures (latency, bridge cost)
  bool ros_only = false;                                      ///< only the ROS figures
  std::string urdf_scenario = "worlds/turtlebot3_maze.yaml";  ///< the URDF figures' scenario
  bool urdf_only = false;                                     ///< only the URDF figures
  std::string sdf_world = "worlds/rescue_yard.sdf";           ///< the SDF figures' world
  std::vector<std::string> sdf_resource_paths = {"worlds/models"};
  bool sdf_only = false;                              ///< only the SDF figures
  std::string mission_scenario = "worlds/team.yaml";  ///< the mission figures' scenario
  bool mission_only = false;                          ///< only the mission figures
  bool reset_only = false;                            ///< only the reset figure (bench_reset.h)
  bool control_only = false;                          ///< only the control figures (bench_control.h)
  BenchControlOptions control_options;
  bool lidar_only = false;    ///< only the lidar figures (rays, the laser sampler, the laser in smoke)
  bool cameras_only = false;  ///< only the camera figures (frames/s beside bare GL, and in smoke)
  BenchRosOptions ros_options;
  bool soak = false;        ///< only the soak run (bench_soak.h); --out is then its folder
  double soak_hours = 10;   ///< sim hours of the soak run
  bool scale = false;       ///< only the scale figures (bench_scale.h)
  bool cold_start = false;  ///< only the cold start figure (bench_cold_start.h)
  std::vector<int> scale_robots = {1, 10, 30, 100};
  double scale_time = 10;  ///< sim seconds of each scale run
};

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

json figure(double value, const char* unit, double baseline, const char* baseline_name, double target_ratio) {
  json j;
  j["value"] = value;
  j["unit"] = unit;
  j["baseline"] = baseline;
  j["baseline_is"] = baseline_name;
  j["ratio"] = baseline > 0 ? value / baseline : 0.0;
  j["target_ratio"] = target_ratio;
  j["meets_target"] = baseline > 0 && value / baseline >= target_ratio;
  return j;
}

/// Our physics step (controllers, read-back, contacts) beside a bare Bullet loop, both driving
/// the robot straight ahead at the same wheel speed from a fresh start.
json bench_physics(const World& world, int steps) {
  const double wheel_speed = 4.0;  // rad/s: 0.44 m/s on 0.11 m wheels
  const double bare = bare_bullet_steps_per_second(world, PhysicsOptions{}, steps, wheel_speed);
  Physics physics(world);
  State s;
  physics.init_state(s);
  const RobotSpec& spec = world.robots[0].spec;
  const auto t0 = Clock::now();
  for (int k = 0; k < steps; ++k) {
    RobotState& rs = s.robots[0];
    rs.cmd_linear = Vec3(wheel_speed * spec.drive.wheel_radius, 0, 0);
    rs.cmd_angular = Vec3::Zero();
    rs.cmd_time = s.time;
    update_drive(spec, rs, s.time, physics.dt());
    update_head(spec, rs);
    physics.step(s);
    s.time += SimTime::from_seconds(physics.dt());
  }
  const double ours = steps / since(t0);
  json j = figure(ours, "steps/s", bare, "bare Bullet stepSimulation loop, same world and wheel speed", 0.8);
  j["steps"] = steps;
  j["dt_s"] = physics.dt();
  j["static_bodies"] = physics.stats().static_bodies;
  j["dynamic_bodies"] = physics.stats().dynamic_bodies;
  return j;
}

/// The world with a slab of smoke 1.5 m thick and 4 m wide, 2 m ahead of the first robot (as in
/// worlds/smoke_corridor), or all around it (8 x 8 m), 2 m high, of `density` (1/m).
World with_smoke(const World& world, bool around, double density) {
  const Vec2 c = world.robots[0].X_W_start.p.head<2>() + Vec2(0.26, 0);  // where bench_rays' laser stands
  const Vec2 ahead = world.robots[0].X_W_start.q.toRotationMatrix().col(0).head<2>().normalized();
  const Vec2 side(-ahead.y(), ahead.x());
  World smoky = world;
  MediumSpec smoke;
  smoke.name = "bench_smoke";
  smoke.outline = around ? Polygon2{c + Vec2(-4, -4), c + Vec2(4, -4), c + Vec2(4, 4), c + Vec2(-4, 4)}
                         : Polygon2{c + 2.0 * ahead - 2.0 * side, c + 3.5 * ahead - 2.0 * side, c + 3.5 * ahead + 2.0 * side,
                                    c + 2.0 * ahead + 2.0 * side};
  if (signed_area(smoke.outline) < 0) std::reverse(smoke.outline.begin(), smoke.outline.end());
  smoke.density = density;
  smoke.height = 2.0;
  smoky.media.push_back(smoke);
  return smoky;
}

/// Lidar rays: RayScene beside bare rtcIntersect16, and a whole laser scan (noise, REP-117) per second.
json bench_rays(const World& world, double seconds) {
  const Vec3 origin = world.robots[0].X_W_start.p + Vec3(0.26, 0, 0.16);
  // the scene as a run starts: resting rubble asleep
  State s;
  Physics(world).init_state(s);
  const RayBenchResult r = measure_ray_throughput(world, origin, 1080, seconds, &s);
  json j = figure(r.scene_rays_per_s, "rays/s", r.bare_rays_per_s, "bare Embree rtcIntersect16, same triangles, one thread", 0.7);
  // the whole laser sampler: rays, noise, message
  RayScene scene(world);
  scene.update(s);
  const SensorSpec& laser = *world.robots[0].spec.find_sensor("laser");
  Rng rng(1, "bench");
  int scans = 0;
  const auto t0 = Clock::now();
  while (since(t0) < seconds) {
    for (int k = 0; k < 50; ++k) sample_lidar(world, s, scene, RobotIndex(0), laser, SimTime{}, rng);
    scans += 50;
  }
  const double rate = scans / since(t0);
  j["laser_scans_per_s"] = rate;
  j["laser_beams"] = laser.lidar.samples;
  j["laser_rays_per_s_end_to_end"] = rate * laser.lidar.samples;

  // the same laser in smoke (docs/environment.md), two ways: a slab of 0.8 /m smoke 1.5 m thick
  // across the laser's view 2 m ahead (as in worlds/smoke_corridor), the beams that miss it paying
  // one box test; and the worst case, every beam starting inside 0.5 /m smoke 8 x 8 m around the
  // robot, each paying its optical depth, a draw and, when lost, its early echo
  const auto laser_in = [&](bool around, double density) {
    const World smoky = with_smoke(world, around, density);
    RayScene smoky_scene(smoky);
    smoky_scene.update(s);
    int smoky_scans = 0;
    const auto t1 = Clock::now();
    while (since(t1) < seconds) {
      for (int k = 0; k < 50; ++k) sample_lidar(smoky, s, smoky_scene, RobotIndex(0), laser, SimTime{}, rng);
      smoky_scans += 50;
    }
    return smoky_scans / since(t1) * laser.lidar.samples;
  };
  const double clear = rate * laser.lidar.samples;
  j["laser_in_smoke"] =
      figure(laser_in(false, 0.8), "rays/s", clear,
             "the same laser sampler without smoke (laser_rays_per_s_end_to_end); smoke: a 1.5 x 4 m slab of 0.8 /m, 2 m ahead", 0.8);
  j["laser_all_in_smoke"] = ratio_figure(laser_in(true, 0.5), "rays/s", clear,
                                         "the same laser sampler without smoke; smoke: 0.5 /m, 8 x 8 m around the robot, every beam inside "
                                         "(the worst case)");
  return j;
}

/// Camera frames per second (low quality) beside a bare GL loop drawing the same number of
/// triangles with readback, for colour, depth and thermal at two sizes; then at 320 x 240
/// through a slab of smoke beside the same camera without it.
json bench_cameras(const World& world, double seconds) {
  json j;
  std::unique_ptr<Renderer> renderer;
  try {
    renderer = Renderer::create_headless(Quality::low);
  } catch (const Error& e) {
    j["error"] = e.what();
    return j;
  }
  RenderScene scene = build_render_scene(world);
  renderer->load(scene);
  State s;
  Physics(world).init_state(s);
  update_render_scene(scene, s);
  renderer->update(scene);
  j["device"] = renderer->device();
  j["triangles"] = scene.triangle_count();
  const SensorSpec* head = world.robots[0].spec.find_sensor("color_camera");
  const std::pair<BenchImage, const char*> kinds[3] = {
      {BenchImage::color, "color"}, {BenchImage::depth, "depth"}, {BenchImage::thermal, "thermal"}};
  CameraView view = camera_view(world, s, RobotIndex(0), *head);
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{640, 480}, {320, 240}}) {
    const double bare = bare_gl_frames_per_second(w, h, static_cast<int>(scene.triangle_count()), seconds);
    view.k = Intrinsics::from_hfov(w, h, 70 * M_PI / 180);
    for (const auto& [image, name] : kinds) {
      const double fps = renderer_frames_per_second(*renderer, view, image, seconds);
      j[std::string(name) + "_" + std::to_string(w) + "x" + std::to_string(h)] =
          figure(fps, "frames/s", bare, "bare GL loop, same triangles, RGB8 readback", 0.8);
    }
  }
  // through smoke (docs/environment.md): every pixel pays its optical depth through the slab's
  // prism, an axis-aligned box (the shaders' fast path), then the same slab turned by 30 degrees
  // (their general convex path). A second renderer holds the smoky scene, and the two are
  // measured in alternating short runs (medians of 5): a CPU rasteriser on a shared machine
  // drifts by more than the difference between one long run of each.
  const auto through = [&](const World& smoky, const std::string& suffix, const char* smoke, std::optional<double> target) {
    std::unique_ptr<Renderer> fogged = Renderer::create_headless(Quality::low);
    RenderScene smoky_scene = build_render_scene(smoky);
    update_render_scene(smoky_scene, s);
    fogged->load(smoky_scene);
    fogged->update(smoky_scene);
    const std::string baseline = std::string("the same camera without smoke, alternating runs, medians of 5; smoke: ") + smoke;
    for (const auto& [image, name] : kinds) {
      std::vector<double> clear, thick;
      for (int round = 0; round < 5; ++round) {
        clear.push_back(renderer_frames_per_second(*renderer, view, image, seconds / 5));
        thick.push_back(renderer_frames_per_second(*fogged, view, image, seconds / 5));
      }
      const double fps = median(thick), base = median(clear);
      j[std::string(name) + "_320x240_" + suffix] =
          target ? figure(fps, "frames/s", base, baseline.c_str(), *target) : ratio_figure(fps, "frames/s", base, baseline.c_str());
    }
  };
  through(with_smoke(world, false, 0.8), "in_smoke", "a 1.5 x 4 m slab of 0.8 /m, 2 m ahead", 0.8);
  World turned = with_smoke(world, false, 0.8);
  const Vec2 centre = centroid(turned.media[0].outline);
  for (Vec2& p : turned.media[0].outline) p = centre + Eigen::Rotation2Dd(M_PI / 6) * (p - centre);
  through(turned, "in_turned_smoke", "the same slab turned 30 degrees (the general convex path)", std::nullopt);
  return j;
}

#ifdef RESCUESIM_HAS_MCAP
/// What an MCAP recording cost: sizes, compression, and write throughput beside bare zstd.
json recording_figures(const McapRecordingStats& st, double sim_time, double finish_s) {
  const double mb = 1e-6;
  const double uncompressed = static_cast<double>(st.writer.uncompressed_bytes) * mb;
  // our whole write path (CDR, chunking, CRCs, zstd, file) beside the zstd part of it alone
  const double ours = st.busy_seconds > 0 ? uncompressed / st.busy_seconds : 0.0;
  const double bare = st.writer.compress_seconds > 0 ? uncompressed / st.writer.compress_seconds : 0.0;
  json j = figure(ours, "MB/s", bare, "bare zstd level 3 on the same chunks, timed inside the same recording", 0.7);
  j["file_mb"] = static_cast<double>(st.writer.file_bytes) * mb;
  j["uncompressed_mb"] = uncompressed;
  j["compression_ratio"] = st.writer.compressed_bytes > 0
                               ? static_cast<double>(st.writer.uncompressed_bytes) / static_cast<double>(st.writer.compressed_bytes)
                               : 0.0;
  j["file_mb_per_sim_s"] = sim_time > 0 ? static_cast<double>(st.writer.file_bytes) * mb / sim_time : 0.0;
  j["messages"] = st.writer.messages;
  j["chunks"] = st.writer.chunks;
  j["dropped"] = st.dropped;
  j["recorder_busy_s"] = st.busy_seconds;
  j["finish_s"] = finish_s;
  if (!st.error.empty()) j["error"] = st.error;
  return j;
}
#endif

/// Runs a scenario in a child process; returns its result and the child's peak memory (MB).
/// With `record`, an MCAP recorder is attached and its figures are added under "recording".
json run_child(const Scenario& scenario, const ModelMap& models, bool cameras, [[maybe_unused]] const std::filesystem::path& record = {}) {
  ChildReport child = run_in_child([&] {
    json out;
    SessionOptions so;
    so.cameras = cameras;
    Session session(scenario, models, so);
#ifdef RESCUESIM_HAS_MCAP
    std::unique_ptr<McapRecorder> recorder;
    if (!record.empty()) {
      McapOptions mo;
      mo.path = record;
      describe_run(mo, session.scenario(), session.world_spec(), cameras, RESCUESIM_VERSION);
      recorder = std::make_unique<McapRecorder>(mo);
      recorder->start(session.sim());
    }
#endif
    const RunResult r = session.run();
    out = {{"sim_time_s", r.sim_time},
           {"wall_time_s", r.wall_time},
           {"real_time_factor", r.real_time_factor},
           {"victims_found", r.victims_found},
           {"collisions", r.collisions}};
    if (r.mission) {
      out["mission"] = {{"score", r.mission->score},
                        {"victims_reported", r.mission->victims_found},
                        {"victims", r.mission->victims},
                        {"false_reports", r.mission->counts[ReportOutcome::false_report]}};
    }
#ifdef RESCUESIM_HAS_MCAP
    if (recorder) {
      const auto t0 = Clock::now();
      recorder->stop();
      out["recording"] = recording_figures(recorder->recording(), r.sim_time, since(t0));
      std::filesystem::remove(record);
    }
#endif
    return out;
  });
  json j = std::move(child.report);
  j["peak_memory_mb"] = static_cast<double>(child.usage.ru_maxrss) / 1024.0;
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  j["cpu_time_s"] = seconds(child.usage.ru_utime) + seconds(child.usage.ru_stime);
  return j;
}

/// MCAP recording: the default scenario with and without --record in the same bench run (its
/// real-time factor both ways), then with every camera on for the write throughput.
json bench_recording([[maybe_unused]] const Scenario& def, [[maybe_unused]] const ModelMap& models) {
#ifdef RESCUESIM_HAS_MCAP
  const std::filesystem::path file = std::filesystem::temp_directory_path() / ("rescuesim-bench-" + std::to_string(::getpid()) + ".mcap");
  json j;
  const auto pair = [&](const Scenario& s, bool cameras) {
    const json without = run_child(s, models, cameras);
    const json with = run_child(s, models, cameras, file);
    const double a = without.value("real_time_factor", 0.0), b = with.value("real_time_factor", 0.0);
    json p = figure(b, "x real time", a, "the same run without recording, in this bench run", 0.8);
    p["real_time_factor_without"] = a;
    p["real_time_factor_with"] = b;
    p["recording"] = with.value("recording", json());
    if (with.contains("error")) p["error"] = with["error"];
    return p;
  };
  Scenario plain = def;
  plain.duration = std::min(def.duration, 60.0);
  std::fprintf(stderr, "bench: MCAP recording, default scenario without cameras, %.0f s ...\n", plain.duration);
  j["default_scenario"] = pair(plain, false);
  Scenario full = def;
  full.duration = std::min(def.duration, 20.0);
  std::fprintf(stderr, "bench: MCAP recording, every sensor (shipped cameras), %.0f s ...\n", full.duration);
  j["full_sensors"] = pair(full, true);
  j["note"] = "ratio = real-time factor with recording / without; recording.value = MB/s of uncompressed chunk data "
              "through the recorder thread (CDR, chunking, CRC, zstd, file), beside zstd alone on the same chunks";
  return j;
#else
  return json{{"error", "built without the MCAP recorder"}};
#endif
}

int run_bench(const BenchOptions& given) {
  // the default figures' files are the shipped worlds: found from any folder once installed
  BenchOptions o = given;
  const auto installed = [](const std::string& f) {
    try {
      return app::locate_data_file(f);
    } catch (const Error&) {
      return f;  // the figure that needs it says what is missing
    }
  };
  o.urdf_scenario = installed(o.urdf_scenario);
  o.sdf_world = installed(o.sdf_world);
  o.mission_scenario = installed(o.mission_scenario);
  for (auto& p : o.sdf_resource_paths) p = installed(p);
  if (o.soak) {
    SoakOptions so;
    so.hours = o.soak_hours;
    if (!o.out.empty()) so.out = o.out;
    std::fputs((bench_soak(so).dump(2) + "\n").c_str(), stdout);
    return kExitOk;
  }
  const ModelMap models = builtin_models();
  Scenario def = default_scenario(models);
  def.duration = o.scenario_time;
  const WorldSpec spec = build_world(def);
  const World world = compile_scenario(def, spec, models);

  json report;
  // the report on stdout, and in --out when given
  const auto print_report = [&o](const json& r) {
    const std::string text = r.dump(2) + "\n";
    std::fputs(text.c_str(), stdout);
    if (!o.out.empty()) write_file_atomic(o.out, text);
    return kExitOk;
  };
  report["rescuesim"] = RESCUESIM_VERSION;
  report["machine"] = {{"cores", std::thread::hardware_concurrency()}};
  if (o.ros_only) {
    report["ros"] = bench_ros(def, models, o.ros_options);
    return print_report(report);
  }
  if (o.cold_start) {
    report["cold_start"] = bench_cold_start();
    return print_report(report);
  }
  if (o.reset_only) {
    report["reset"] = bench_reset(def, models);
    return print_report(report);
  }
  if (o.control_only) {
    report["control"] = bench_control(def, models, o.control_options);
    return print_report(report);
  }
  if (o.lidar_only) {
    report["lidar"] = bench_rays(world, o.seconds);
    return print_report(report);
  }
  if (o.cameras_only) {
    report["cameras"] = bench_cameras(world, o.seconds);
    return print_report(report);
  }
  if (o.urdf_only) {
    report["urdf"] = bench_urdf(o.urdf_scenario, std::min(o.scenario_time, 60.0),
                                [](const Scenario& s, const ModelMap& m) { return run_child(s, m, false); });
    return print_report(report);
  }
  const std::vector<std::filesystem::path> sdf_paths(o.sdf_resource_paths.begin(), o.sdf_resource_paths.end());
  if (o.sdf_only) {
    report["sdf"] = bench_sdf(o.sdf_world, sdf_paths, o.seconds);
    return print_report(report);
  }
  const RunChild child_without_cameras = [&](const Scenario& s, const ModelMap& m) { return run_child(s, m, false); };
  if (o.scale) {
    // the plot beside the report: --out's name with .png, else scale.png here
    const std::filesystem::path png =
        o.out.empty() ? std::filesystem::path("scale.png") : std::filesystem::path(o.out).replace_extension(".png");
    report["scale"] = bench_scale(o.scale_robots, o.scale_time, child_without_cameras, png);
    return print_report(report);
  }
  if (o.mission_only) {
    report["mission"] = bench_mission(o.mission_scenario, std::min(o.scenario_time, 60.0), child_without_cameras);
    return print_report(report);
  }
  std::fprintf(stderr, "bench: physics ...\n");
  report["physics"] = bench_physics(world, o.physics_steps);
  std::fprintf(stderr, "bench: lidar rays ...\n");
  report["lidar"] = bench_rays(world, o.seconds);
  std::fprintf(stderr, "bench: cameras ...\n");
  report["cameras"] = bench_cameras(world, o.seconds);
  std::fprintf(stderr, "bench: default scenario, %.0f s of sim time, no cameras ...\n", o.scenario_time);
  json d = run_child(def, models, false);
  d["target_real_time_factor"] = 30;
  d["meets_target"] = d.value("real_time_factor", 0.0) >= 30;
  report["default_scenario"] = d;
  std::fprintf(stderr, "bench: default scenario with the tracked robot, no cameras ...\n");
  Scenario tracked = def;
  for (auto& rc : tracked.robots) {
    rc.model = "tracked_robot";
    rc.spec = models.at("tracked_robot");
  }
  json t = run_child(tracked, models, false);
  const double wheeled_rtf = d.value("real_time_factor", 0.0);
  t["baseline"] = "the default scenario with the wheeled rescue robot, this run (default_scenario)";
  t["ratio_to_wheeled"] = wheeled_rtf > 0 ? t.value("real_time_factor", 0.0) / wheeled_rtf : 0.0;
  t["target_ratio"] = 0.5;  // within 2x of the wheeled robot (issue 18)
  t["meets_target"] = t.value("ratio_to_wheeled", 0.0) >= 0.5;
  report["default_scenario_tracked"] = t;
  std::fprintf(stderr, "bench: 300 rubble bodies ...\n");
  Scenario heavy = def;
  heavy.maze->rubble = 300;
  heavy.duration = std::min(o.scenario_time, 60.0);
  json h = run_child(heavy, models, false);
  h["rubble_requested"] = 300;
  h["rubble_placed"] = build_world(heavy).rubble.size();
  h["target_real_time_factor"] = 10;
  h["meets_target"] = h.value("real_time_factor", 0.0) >= 10;
  report["rubble_300"] = h;
  std::fprintf(stderr, "bench: default scenario with all cameras at 320x240, 10 Hz ...\n");
  Scenario cams = def;
  cams.duration = std::min(o.scenario_time, 60.0);
  for (auto& rc : cams.robots) {
    for (auto& sensor : rc.spec.sensors) {
      if (sensor.is_camera()) {
        sensor.camera.width = 320;
        sensor.camera.height = 240;
        sensor.rate = 10;
      }
    }
  }
  json c = run_child(cams, models, true);
  c["target_real_time_factor"] = 5;
  c["meets_target"] = c.value("real_time_factor", 0.0) >= 5;
  report["default_scenario_cameras_320x240"] = c;
  Scenario shipped = def;
  shipped.duration = std::min(o.scenario_time, 60.0);
  json d2 = run_child(shipped, models, true);
  d2["note"] = "the shipped camera settings: colour 640x480, depth 320x240, thermal 160x120, all 10 Hz";
  report["default_scenario_cameras_shipped"] = d2;
  report["urdf"] = bench_urdf(o.urdf_scenario, std::min(o.scenario_time, 60.0),
                              [](const Scenario& s, const ModelMap& m) { return run_child(s, m, false); });
  report["sdf"] = bench_sdf(o.sdf_world, sdf_paths, o.seconds);
  report["mission"] = bench_mission(o.mission_scenario, std::min(o.scenario_time, 60.0), child_without_cameras);
  report["mcap_recording"] = bench_recording(def, models);
  if (o.batch_trials > 0) report["batch"] = bench_batch(def, o.batch_trials);
  report["reset"] = bench_reset(def, models);
  report["python_step"] = bench_python_step();
  if (o.ros) report["ros"] = bench_ros(def, models, o.ros_options);
  if (o.ros) report["control"] = bench_control(def, models, o.control_options);
  return print_report(report);
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure speed and memory, each figure beside a raw baseline from the same run");
  cmd->footer("Prints a JSON report: physics steps/s beside a bare Bullet loop of the same world; lidar\n"
              "rays/s beside bare Embree rtcIntersect16 on the same triangles, and the laser in smoke\n"
              "(lidar.laser_in_smoke) beside the same laser in clear air (target >= 0.8x); the default scenario's\n"
              "real-time factor and peak memory (run in a child process); and a 300-rubble maze.\n"
              "Targets (2-core machine): physics >= 0.8x bare, lidar >= 0.7x bare, default >= 30x real\n"
              "time, 300 rubble >= 10x real time. MCAP recording (mcap_recording): the default run's real-time\n"
              "factor with and without --record (target >= 0.8x), and the recorder's write MB/s with every\n"
              "camera on, beside zstd alone on the same chunks. Batch (batch): trials/hour of the default\n"
              "scenario without cameras at --jobs 1 and 2 (target >= 1000 at 2), beside the same trials in\n"
              "this process; python_step: Python Env.step() beside the same steps in C++ (target <= 10%).\n"
              "ROS (ros; about a minute; --no-ros skips it, --ros-only runs nothing else): latency from\n"
              "publication on the Bus to a subscriber in another process on loopback (median, p99, samples) for\n"
              "/scan and a 640x480 rgb8 image over ROS 1 (a roscpp node; roscore is started on a free port),\n"
              "ROS 2 (a Cyclone DDS reader) and Foxglove (a WebSocket client), in realtime runs; and the\n"
              "real-time factor with --ros1 --ros2 --foxglove attached and subscribed beside the same\n"
              "lockstep run without bridges (target >= 0.9x; also\n"
              "with /scan subscribers alone). A transport this build or machine lacks is reported as skipped,\n"
              "with the reason (docs/ros.md).\n"
              "Control (control; about 8 s, with the ROS figures; --control-only runs nothing else;\n"
              "docs/performance.md): the default scenario without cameras, started paused, with the ROS 2 bridge,\n"
              "and a client in another process on loopback: ResetSimulation round trip p50/p99 beside\n"
              "Session::restore alone and beside rebuilding the Session (target < 5 ms p50); StepSimulation(1)\n"
              "round trip beside one step in-process (target < 1 ms p50); a 10,000-step SimulateSteps goal beside\n"
              "the same steps lockstep in-process (alternating, medians of 3; target >= 0.9x).\n"
              "URDF (urdf; docs/robots.md): reading the --urdf-scenario's robot with its meshes beside loading\n"
              "the mesh files alone; convex hull of its largest mesh (64 vertices) beside the exact hull, and\n"
              "its convex decomposition; the robot's real-time factor beside the built-in robot in the same maze.\n"
              "SDF (sdf; docs/worlds.md): reading --sdf-world beside loading its mesh files alone; lidar rays/s\n"
              "through a room of walls and pillars as one 100k-triangle static mesh beside the same room from\n"
              "box primitives.\n"
              "Mission (mission; docs/missions.md): the --mission-scenario's real-time factor with its mission\n"
              "(referee and radio) beside the same run without it (median of 3, target >= 0.9x), and the cost\n"
              "of one radio link update for 4, 10 and 30 radios in its world.\n"
              "Scale (--scale; docs/performance.md): the scale scenario for 1, 10, 30 and 100 robots, e.g.\n"
              "  rescuesim bench --scale --scale-robots 1,10,30,100,300 --out scale.json   (writes scale.png too)\n"
              "Cold start (--cold-start; docs/performance.md): exec to the first /scan, target < 1 s.");
  cmd->add_option("--out,-o", o->out, "also write the report to this file");
  cmd->add_option("--seconds", o->seconds, "wall seconds per ray measurement")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--scenario-time", o->scenario_time, "sim seconds of the default scenario")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--physics-steps", o->physics_steps, "steps per physics measurement")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--batch-trials", o->batch_trials, "trials per batch measurement (twice as many at --jobs 2; 0 skips)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("!--no-ros", o->ros, "skip the ROS figures (latency over ROS 1 / ROS 2, bridge cost) and the control figures");
  cmd->add_flag("--ros-only", o->ros_only, "measure only the ROS figures");
  cmd->add_flag("--urdf-only", o->urdf_only, "measure only the URDF figures");
  cmd->add_flag("--sdf-only", o->sdf_only, "measure only the SDF figures");
  cmd->add_flag("--mission-only", o->mission_only, "measure only the mission figures");
  cmd->add_option("--mission-scenario", o->mission_scenario, "scenario with a mission: block for the mission figures")
      ->capture_default_str();
  cmd->add_option("--sdf-world", o->sdf_world, "SDF world for the SDF load figure")->capture_default_str();
  cmd->add_option("--sdf-resource-path", o->sdf_resource_paths, "where the SDF world's model:// URIs are looked for first")
      ->capture_default_str();
  cmd->add_flag("--reset-only", o->reset_only, "measure only the reset figure (snapshot restore beside a rebuild)");
  cmd->add_flag("--control-only", o->control_only,
                "measure only the control figures (ResetSimulation, StepSimulation, SpawnEntity and DeleteEntity round trips, the "
                "SimulateSteps action, "
                "over ROS 2 on loopback, each beside the same in-process)");
  cmd->add_option("--control-resets", o->control_options.resets, "timed ResetSimulation calls of the control figures")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--control-steps", o->control_options.steps, "timed StepSimulation(1) calls of the control figures")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--control-action-steps", o->control_options.action_steps, "steps of each SimulateSteps goal of the control figures")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--control-rounds", o->control_options.action_rounds,
                  "SimulateSteps goals and lockstep runs, alternating (the medians count)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--control-spawns", o->control_options.spawns, "timed SpawnEntity and DeleteEntity pairs of the control figures")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--lidar-only", o->lidar_only,
                "measure only the lidar figures (rays beside bare Embree, the laser sampler, the laser in smoke)");
  cmd->add_flag("--cameras-only", o->cameras_only, "measure only the camera figures (frames/s beside a bare GL loop, and through smoke)");
  cmd->add_option("--urdf-scenario", o->urdf_scenario, "scenario whose first robot is a URDF robot, for the URDF figures")
      ->capture_default_str();
  cmd->add_option("--ros-latency-time", o->ros_options.latency_seconds, "wall seconds of each realtime ROS latency run")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--ros-cost-time", o->ros_options.rtf_seconds, "sim seconds of each lockstep run with and without bridges")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--ros-cost-rounds", o->ros_options.rtf_rounds,
                  "rounds of lockstep runs without bridges, with them and /scan + image subscribers, and with /scan subscribers "
                  "alone (alternating; the best real-time factor of each kind counts: more rounds, less noise from other load)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--soak", o->soak,
                "only a soak run: the default scenario for --soak-hours of sim time with cameras and every bridge built "
                "attached, memory and real-time factor every sim minute, every message checked for NaN; writes soak.csv, "
                "soak.json and soak.png into --out (a folder, default runs/soak); Ctrl-C stops early and still writes them");
  cmd->add_option("--soak-hours", o->soak_hours, "sim hours of the soak run")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_flag("--scale", o->scale,
                "only the scale figures: the scale scenario (a 20 m maze, N robots with 1081-beam 30 m lidars at 10 Hz, wall "
                "following, no cameras) for each --scale-robots count, in a child process each; real-time factor beside N "
                "robots costing N times the first count, lidar rays/s, peak memory, CPU use per core; the plot goes beside "
                "--out (its name with .png; scale.png without --out)");
  cmd->add_option("--scale-robots", o->scale_robots, "robot counts of the scale figures")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000))
      ->delimiter(',');
  cmd->add_option("--scale-time", o->scale_time, "sim seconds of each scale run")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_flag("--cold-start", o->cold_start,
                "only the cold start figure: seconds from exec to the first /scan of `rescuesim run` (default scenario, "
                "with cameras and without; median of 5) beside exec to exit of `rescuesim --version`");
  cmd->final_callback([o, &action] { action = [o] { return run_bench(*o); }; });
  add_bench_probe_command(app, action);
}

}  // namespace rescuesim::bench
