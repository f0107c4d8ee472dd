// RunControl's spawning (SpawnEntity, DeleteEntity, GetSpawnables, a reset of spawned
// entities) in the public TurtleBot3 maze: a URDF robot from its package, a rescuesim YAML robot,
// built-in robots and loose bodies; each bad request gets its standard code and says why.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "raycast/ray_scene.h"
#include "robots/rescue_robot.h"
#include "session/run_control.h"
#include "session/session.h"

namespace rescuesim {
namespace {

using namespace control;

const std::filesystem::path kWorlds = std::filesystem::path(RESCUESIM_SOURCE_DIR) / "worlds";
const char* kBurger = "package://turtlebot3_description/urdf/turtlebot3_burger.urdf";

std::unique_ptr<Session> maze_session() {
  const ModelMap models = builtin_models();
  Scenario s = load_scenario(kWorlds / "turtlebot3_maze.yaml", models);
  s.duration = 1e9;
  SessionOptions o;
  o.cameras = false;
  o.control = true;
  return std::make_unique<Session>(s, models, o);
}

/// The centre of a maze cell with no victim and no robot in it (the maze's cells are 1 m).
Pose3 free_cell(const Session& session, const std::vector<Vec2>& taken) {
  const WorldSpec& w = session.world_spec();
  for (double x = w.floor_min.x() + 0.5; x < w.floor_max.x(); x += 1.0) {
    for (double y = w.floor_min.y() + 0.5; y < w.floor_max.y(); y += 1.0) {
      const Vec2 c(x, y);
      bool free = true;
      for (const VictimSpec& v : w.victims) free = free && (v.pose.position() - c).norm() > 0.7;
      for (const Vec2& t : taken) free = free && (t - c).norm() > 0.7;
      if (free) return Pose3{Vec3(x, y, 0), Quat::Identity()};
    }
  }
  ADD_FAILURE() << "no free cell";
  return {};
}

SpawnRequest request(const std::string& name, const std::string& uri, const Pose3& pose) {
  SpawnRequest r;
  r.name = name;
  r.uri = uri;
  r.pose = pose;
  return r;
}

bool has_topic(Session& s, const std::string& name) {
  for (const Topic& t : s.sim().bus().topics()) {
    if (t.name == name && !t.retired) return true;
  }
  return false;
}

TEST(RunControlSpawn, AURDFRobotFromItsPackageIsSpawnedDrivenAndDeleted) {
  auto session = maze_session();
  RunControl& c = *session->control();
  c.arm();
  const std::uint64_t start_hash = c.state_hash();
  const SimulatorFeatures f = c.features();
  for (std::uint16_t want : {feature::kSpawning, feature::kDeleting, feature::kSpawnables, feature::kSpawningResourceString,
                             feature::kSimulationResetSpawned}) {
    EXPECT_NE(std::find(f.features.begin(), f.features.end(), want), f.features.end()) << want;
  }
  EXPECT_EQ(f.spawn_formats, (std::vector<std::string>{"urdf", "sdf", "yaml"}));

  // GetSpawnables: the built-in robots and bodies, and the URDFs on the scenario's resource paths
  std::vector<Spawnable> sp;
  ASSERT_TRUE(c.spawnables({}, sp).is_ok());
  const auto listed = [&](const std::string& uri) {
    return std::any_of(sp.begin(), sp.end(), [&](const Spawnable& s) { return s.uri == uri; });
  };
  EXPECT_TRUE(listed("rescue_robot"));
  EXPECT_TRUE(listed("box"));
  EXPECT_TRUE(std::any_of(sp.begin(), sp.end(), [&](const Spawnable& s) { return s.uri.ends_with("turtlebot3_burger.urdf"); }));

  session->step_until(SimTime::from_seconds(0.5));
  const Vec2 tb3 = session->sim().state().robots[0].base.X_WB.to_pose2().position();
  const Pose3 X = free_cell(*session, {tb3});
  // a URDF robot of its own, through a YAML entry with its drive (the raw URDF has none)
  SpawnRequest r = request("tb3b", "", X);
  r.resource_string =
      std::string("{urdf: ") + kBurger + ", drive: {type: diff_drive, left: [wheel_left_joint], right: [wheel_right_joint]}}";
  std::string name;
  const Result ok = c.spawn(r, name);
  ASSERT_TRUE(ok.is_ok()) << ok.error_message;
  EXPECT_EQ(name, "tb3b");
  EntityInfo info;
  ASSERT_TRUE(c.entity_info("tb3b", info).is_ok());
  EXPECT_EQ(info.category, category::kRobot);
  // its topics at once, under its namespace; the scenario robot's stay where they were
  EXPECT_TRUE(has_topic(*session, "/tb3b/robot_description"));
  EXPECT_TRUE(has_topic(*session, "/tb3b/odom"));
  EXPECT_TRUE(has_topic(*session, "/odom"));
  EXPECT_EQ(session->sim().topic_name(RobotIndex(1), "cmd_vel"), "/tb3b/cmd_vel");
  EntityState st;
  ASSERT_TRUE(c.entity_state("tb3b", st).is_ok());
  EXPECT_NEAR(st.pose.p.x(), X.p.x(), 1e-6);
  EXPECT_NEAR(st.pose.p.y(), X.p.y(), 1e-6);

  // cmd_vel drives it: 0.1 m/s for 2 s is about 0.2 m, less the speed-up
  for (int i = 0; i < 20; ++i) {
    msg::Twist t;
    t.linear.x() = 0.1;
    ASSERT_TRUE(session->sim().command_velocity(RobotIndex(1), t));
    session->step_until(session->sim().time() + SimTime::from_ms(100));
  }
  ASSERT_TRUE(c.entity_state("tb3b", st).is_ok());
  const double moved = (st.pose.p - X.p).head<2>().norm();
  EXPECT_GT(moved, 0.15);
  EXPECT_LT(moved, 0.201);

  // the name is taken now; renaming gives the next free one
  EXPECT_EQ(c.spawn(request("tb3b", kBurger, free_cell(*session, {tb3, X.p.head<2>()})), name).result, code::kNameNotUnique);
  r = request("tb3b", "box", free_cell(*session, {tb3, X.p.head<2>()}));
  r.allow_renaming = true;
  ASSERT_TRUE(c.spawn(r, name).is_ok());
  EXPECT_EQ(name, "tb3b_1");
  ASSERT_TRUE(c.entity_info("tb3b_1", info).is_ok());
  EXPECT_EQ(info.category, category::kDynamicObject);

  // only what was spawned can be deleted; its topics go with it
  EXPECT_EQ(c.remove("tb3").result, code::kOperationFailed);
  EXPECT_EQ(c.remove("nobody").result, code::kNotFound);
  ASSERT_TRUE(c.remove("tb3b").is_ok());
  EXPECT_FALSE(has_topic(*session, "/tb3b/odom"));
  EXPECT_EQ(c.entity_info("tb3b", info).result, code::kNotFound);
  EXPECT_EQ(session->sim().world().robots.size(), 1u);
  session->step_until(session->sim().time() + SimTime::from_seconds(0.5));

  // a reset of everything is the start again, bitwise, with nothing spawned
  ASSERT_TRUE(c.reset(scope::kDefault).is_ok());
  EXPECT_EQ(c.state_hash(), start_hash);
  EXPECT_EQ(c.entity_info("tb3b_1", info).result, code::kNotFound);
}

TEST(RunControlSpawn, ResetScopesKeepOrRemoveWhatWasSpawned) {
  auto session = maze_session();
  RunControl& c = *session->control();
  c.arm();
  session->step_until(SimTime::from_seconds(0.2));
  const Vec2 tb3 = session->sim().state().robots[0].base.X_WB.to_pose2().position();
  Pose3 X = free_cell(*session, {tb3});
  X.p.z() = 0.5;  // dropped from 0.5 m
  std::string name;
  ASSERT_TRUE(c.spawn(request("ball", "sphere", X), name).is_ok());
  const std::size_t ball = session->sim().base_bodies();
  session->step_until(SimTime::from_seconds(1.5));
  // at rest on the floor: the centre at its radius, 0.1 m
  EXPECT_NEAR(session->sim().state().dynamics[ball].X_WB.p.z(), 0.1, 0.005);
  // STATE: bodies back where they started, the spawned ball too (at its spawn pose), the clock runs on
  ASSERT_TRUE(c.reset(scope::kState).is_ok());
  EXPECT_EQ(session->sim().time().ns, SimTime::from_seconds(1.5).ns);
  ASSERT_EQ(session->sim().world().dynamics.size(), ball + 1);
  EXPECT_NEAR(session->sim().state().dynamics[ball].X_WB.p.z(), 0.5, 1e-9);
  session->step_until(SimTime::from_seconds(2.5));
  // TIME: the clock back to 0, the ball where it lies now
  const double z = session->sim().state().dynamics[ball].X_WB.p.z();
  ASSERT_TRUE(c.reset(scope::kTime).is_ok());
  EXPECT_EQ(session->sim().time().ns, 0);
  ASSERT_EQ(session->sim().world().dynamics.size(), ball + 1);
  EXPECT_EQ(session->sim().state().dynamics[ball].X_WB.p.z(), z);
  // SPAWNED: the ball goes, nothing else changes
  const std::uint64_t robot_hash = std::hash<double>()(session->sim().state().robots[0].base.X_WB.p.x());
  ASSERT_TRUE(c.reset(scope::kSpawned).is_ok());
  EXPECT_EQ(session->sim().world().dynamics.size(), ball);
  EntityInfo info;
  EXPECT_EQ(c.entity_info("ball", info).result, code::kNotFound);
  EXPECT_EQ(std::hash<double>()(session->sim().state().robots[0].base.X_WB.p.x()), robot_hash);
}

TEST(RunControlSpawn, BadRequestsGetTheirCodesAndSayWhy) {
  auto session = maze_session();
  RunControl& c = *session->control();
  const Pose3 X = free_cell(*session, {session->sim().state().robots[0].base.X_WB.to_pose2().position()});
  std::string name;
  const auto code_of = [&](const SpawnRequest& r) {
    const Result res = c.spawn(r, name);
    EXPECT_FALSE(res.is_ok());
    EXPECT_FALSE(res.error_message.empty());
    return res.result;
  };
  EXPECT_EQ(code_of(request("", "box", X)), code::kNameInvalid);
  EXPECT_EQ(code_of(request("1robot", "box", X)), code::kNameInvalid);
  EXPECT_EQ(code_of(request("tb3", "box", X)), code::kNameNotUnique);
  SpawnRequest r = request("b", "rescue_robot", X);
  r.entity_namespace = "/a b";
  EXPECT_EQ(code_of(r), code::kNamespaceInvalid);
  EXPECT_EQ(code_of(request("b", "", X)), code::kNoResource);
  EXPECT_EQ(code_of(request("b", "package://no_such_package/urdf/x.urdf", X)), code::kNoResource);
  EXPECT_EQ(code_of(request("b", (kWorlds / "robots/turtlebot3_description/LICENSE").string(), X)), code::kUnsupportedFormat);
  r = request("b", "", X);
  r.resource_string = "<robot name='x'><link name='a'></robot>";
  EXPECT_EQ(code_of(r), code::kResourceParseError);
  // a collision mesh that is not there (a visual one is left out with a warning, as in Gazebo)
  r.resource_string = "<robot name='x'><link name='a'><collision><geometry><mesh "
                      "filename='package://turtlebot3_description/meshes/none.stl'/></geometry></collision></link></robot>";
  EXPECT_EQ(code_of(r), code::kMissingAssets);
  r.resource_string = "{model: no_such_robot}";
  EXPECT_EQ(code_of(r), code::kResourceParseError);
  r.resource_string = "<html/>";
  EXPECT_EQ(code_of(r), code::kUnsupportedFormat);
  Pose3 bad = X;
  bad.q = Quat(0, 0, 0, 0);
  EXPECT_EQ(code_of(request("b", "box", bad)), code::kSpawnInvalidPose);
  r = request("b", "box", X);
  r.frame_id = "nowhere";
  EXPECT_EQ(code_of(r), code::kSpawnInvalidPose);
  // nothing of it stayed
  EXPECT_EQ(session->sim().world().robots.size(), 1u);
  EXPECT_EQ(session->sim().world().dynamics.size(), session->sim().base_bodies());
  EXPECT_EQ(session->sim().bus().layout_version(), 0u);
}


TEST(RunControlSpawnCameras, ASpawnedRobotsDepthCameraSeesTheWallTheRaysSee) {
  // one 6 m maze cell, nothing in it but the scenario's robot in the middle
  const ModelMap models = builtin_models();
  Scenario s = parse_scenario(
      "world: {maze: {cols: 1, rows: 1, cell_size: 6.0, victims: 0, rubble: 0, raised_fraction: 0, terrain_fraction: 0}}\n"
      "robots: [{name: robot, controller: none}]\n",
      "cell.yaml", models);
  s.duration = 1e9;
  SessionOptions o;
  o.control = true;
  Session session(s, models, o);
  if (session.render_device().empty()) GTEST_SKIP() << "no renderer (EGL)";
  RunControl& c = *session.control();
  std::map<std::string, std::vector<msg::Image>> images;
  session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    if (t.name.ends_with("depth/image_raw")) images[t.name].push_back(std::get<msg::Image>(m));
  });
  session.step_until(SimTime::from_seconds(0.5));
  const std::size_t before = images["/camera/depth/image_raw"].size();
  EXPECT_GT(before, 0u);
  const SessionSnapshot at_half = session.snapshot();  // a frame of the first robot is in flight

  // a second rescue robot 1 m west of the first, facing west (yaw 180 degrees): the wall ahead
  const Vec3 p0 = session.sim().state().robots[0].base.X_WB.p;
  SpawnRequest r;
  r.name = "p3at";
  r.uri = "rescue_robot";
  r.pose = Pose3{Vec3(p0.x() - 1.0, p0.y(), 0), Quat(0, 0, 0, 1)};
  std::string name;
  const Result ok = c.spawn(r, name);
  ASSERT_TRUE(ok.is_ok()) << ok.error_message;
  session.step_until(SimTime::from_seconds(1.5));
  const auto& depth = images["/p3at/camera/depth/image_raw"];
  ASSERT_GE(depth.size(), 5u);  // 10 Hz for a second, less the first frame's latency
  EXPECT_EQ(depth.back().header.frame_id, "p3at/camera_depth_optical_frame");
  // the scenario robot's camera went on through the renderer's rebuild: 10 more frames a second
  EXPECT_GE(images["/camera/depth/image_raw"].size(), before + 9);

  // the centre pixel's depth is the distance along the optical axis to the wall, as a ray from
  // the camera finds it (the robot stands still: the newest frame shows it where it is now)
  const World& world = session.sim().world();
  const RobotSpec& spec = world.robots[1].spec;
  const SensorSpec& cam = *spec.find_sensor("depth_camera");
  const Pose3 X_WC = session.sim().state().robots[1].X_WL[static_cast<std::size_t>(spec.link_index(cam.link))] * cam.X_LS;
  const RayScene& rays = session.sim().ray_scene();
  std::vector<Ray> ray{{X_WC.p, X_WC.q * Vec3::UnitX(), 20.0f}};
  std::vector<RayHit> hit(1);
  rays.cast(ray, hit, RobotIndex(1));
  ASSERT_TRUE(std::isfinite(hit[0].distance));
  const msg::Image& img = depth.back();
  float z = 0;
  std::memcpy(&z, &img.data[(img.height / 2 * img.width + img.width / 2) * 4], 4);
  EXPECT_NEAR(z, hit[0].distance, 0.03) << "wall at " << hit[0].distance << " m";

  // deleted: its camera stops, the first robot's goes on
  ASSERT_TRUE(c.remove("p3at").is_ok());
  const std::size_t spawned_frames = depth.size(), first_frames = images["/camera/depth/image_raw"].size();
  session.step_until(SimTime::from_seconds(2.5));
  EXPECT_EQ(images["/p3at/camera/depth/image_raw"].size(), spawned_frames);
  EXPECT_GE(images["/camera/depth/image_raw"].size(), first_frames + 9);

  // spawned again, then the snapshot from before the first spawn restored: the renderer is the
  // snapshot's world's again and the frame that was in flight then is delivered, so the first
  // robot's frames from 0.5 to 1.5 s carry the stamps they carried the first time
  ASSERT_TRUE(c.spawn(r, name).is_ok());
  session.step_until(SimTime::from_seconds(2.7));
  const auto stamps = [&](std::size_t from) {
    std::vector<std::int64_t> out;
    const auto& all = images["/camera/depth/image_raw"];
    for (std::size_t i = from; i < all.size(); ++i) {
      if (all[i].header.stamp.ns <= SimTime::from_seconds(1.5).ns) out.push_back(all[i].header.stamp.ns);
    }
    return out;
  };
  const std::vector<std::int64_t> first_pass = stamps(before);
  session.restore(at_half);
  EXPECT_EQ(session.sim().world().robots.size(), 1u);
  const std::size_t restored_from = images["/camera/depth/image_raw"].size();
  session.step_until(SimTime::from_seconds(1.6));  // the frame of 1.5 s is delivered one period later
  EXPECT_EQ(stamps(restored_from), first_pass);
}

}  // namespace
}  // namespace rescuesim
