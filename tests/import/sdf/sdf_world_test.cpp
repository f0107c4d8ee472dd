// tests/data/sdf/test_world.sdf read into a WorldSpec: every pose, size and number checked here
// is the one written in the file (or follows from it by hand).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import/sdf/sdf_test_files.h"
#include "world/world.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using namespace sdf_test;

const SdfWorld& test_world() {
  static const SdfWorld w = load_sdf_world(data_dir() / "test_world.sdf", isolated());
  return w;
}

TEST(SdfWorld, NameSettingsAndDefaultMaterials) {
  const SdfWorld& w = test_world();
  EXPECT_EQ(w.spec.name, "test_world");
  EXPECT_EQ(w.spec.source_file, (data_dir() / "test_world.sdf").string());
  EXPECT_EQ(w.sdf_version, "1.9");
  EXPECT_DOUBLE_EQ(w.spec.gravity, 9.8);
  EXPECT_DOUBLE_EQ(w.spec.physics_dt, 0.004);
  for (const auto& m : default_materials()) EXPECT_NE(w.spec.find_material(m.name), nullptr) << m.name;
  // the usual gz systems are listed, without a warning
  EXPECT_THAT(w.plugins_ignored, ::testing::Contains("world::gz-sim-physics-system"));
  EXPECT_THAT(warnings(w.diagnostics), ::testing::Not(HasSubstr("physics-system")));
}

TEST(SdfWorld, BuiltInSunAndGroundPlaneNeedNoFiles) {
  const SdfWorld& w = test_world();
  const SdfModelReport* ground = report_named(w, "ground_plane");
  ASSERT_NE(ground, nullptr);
  EXPECT_EQ(ground->becomes, "floor");
  const SdfModelReport* sun = report_named(w, "sun");
  ASSERT_NE(sun, nullptr);
  EXPECT_EQ(sun->becomes, "light");
  // the floor plane is the WorldSpec's floor, not a solid
  for (const auto& s : w.spec.solids) EXPECT_THAT(s.name, ::testing::Not(HasSubstr("ground_plane")));
}

TEST(SdfWorld, StaticBoxesArePlacedWhereTheFileSays) {
  const WorldSpec& spec = test_world().spec;
  const SolidSpec& a = solid_named(spec, "box_a::link::collision");
  EXPECT_EQ(a.geometry.type, Geometry::Type::box);
  EXPECT_LT((a.geometry.size - Vec3(1, 0.2, 0.5)).norm(), 1e-12);
  expect_pose(a.X_WS, Pose3{Vec3(3, 0, 0.25), Quat::Identity()});
  const SolidSpec& b = solid_named(spec, "box_b::link::collision");
  expect_pose(b.X_WS, Pose3::from_rpy(Vec3(0, 3, 0.25), 0, 0, M_PI / 4));
  // relative_to box_a: (0, 1, 0) in box_a's frame, turned a quarter
  const SolidSpec& c = solid_named(spec, "box_c::link::collision");
  expect_pose(c.X_WS, Pose3::from_rpy(Vec3(3, 1, 0.25), 0, 0, M_PI / 2));
  EXPECT_EQ(a.source.file, (data_dir() / "test_world.sdf").string());
  EXPECT_GT(a.source.line, 0);
}

TEST(SdfWorld, MaterialsComeFromVisualsAndSurfaces) {
  const WorldSpec& spec = test_world().spec;
  const SolidSpec& a = solid_named(spec, "box_a::link::collision");
  EXPECT_EQ(a.material, "box_a::link::visual");
  const MaterialSpec* ma = spec.find_material(a.material);
  ASSERT_NE(ma, nullptr);
  EXPECT_LT((ma->color - Vec3(0.2, 0.4, 0.8)).norm(), 1e-6);
  // <mu> 0.3 and no visual: the obstacle's looks with the file's friction
  const MaterialSpec* mb = spec.find_material(solid_named(spec, "box_b::link::collision").material);
  ASSERT_NE(mb, nullptr);
  EXPECT_DOUBLE_EQ(mb->friction, 0.3);
  // nothing given: the obstacle default
  EXPECT_EQ(solid_named(spec, "box_c::link::collision").material, "obstacle");
}

TEST(SdfWorld, StaticCylinder) {
  const SolidSpec& p = solid_named(test_world().spec, "pillar::link::collision");
  EXPECT_EQ(p.geometry.type, Geometry::Type::cylinder);
  EXPECT_LT((p.geometry.size - Vec3(0.4, 0.4, 1.0)).norm(), 1e-12);
  expect_pose(p.X_WS, Pose3{Vec3(-3, 0, 0.5), Quat::Identity()});
}

TEST(SdfWorld, IncludedRampIsTheExactMeshAtTheIncludePose) {
  const SdfWorld& w = test_world();
  const SolidSpec& r = solid_named(w.spec, "ramp_1::link::collision");
  ASSERT_EQ(r.geometry.type, Geometry::Type::mesh);
  EXPECT_EQ(r.geometry.mesh.triangles.size(), 8u);  // two end triangles, three quads
  // the wedge's box 2 x 1 x 0.3, turned a quarter about z and moved to (5, 5, 0)
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const Vec3& v : r.geometry.mesh.vertices) {
    const Vec3 p = r.X_WS * v;
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  // (STL stores single-precision floats: 0.3 is 0.30000001)
  EXPECT_LT((lo - Vec3(4.5, 5, 0)).norm(), 1e-7) << lo.transpose();
  EXPECT_LT((hi - Vec3(5.5, 7, 0.3)).norm(), 1e-7) << hi.transpose();
  // model.config's highest version sdformat reads (1.9, model.sdf), not the older file
  EXPECT_NE(report_named(w, "ramp_1"), nullptr);
  EXPECT_EQ(report_named(w, "ramp_old_file_must_not_be_read"), nullptr);
  EXPECT_EQ(solid_named(w.spec, "ramp_1::link::collision").material, "ramp_1::link::visual");
  int exact = 0;
  for (const auto& m : w.meshes) exact += m.exact && m.collision && m.model == "ramp_1" && m.triangles == 8;
  EXPECT_EQ(exact, 1);
}

TEST(SdfWorld, LooseBoxKeepsItsMassAndInertia) {
  const WorldSpec& spec = test_world().spec;
  ASSERT_EQ(spec.bodies.size(), 1u);
  const BodySpec& b = spec.bodies.front();
  EXPECT_EQ(b.name, "crate::link");
  EXPECT_EQ(b.geometry.type, Geometry::Type::box);
  EXPECT_DOUBLE_EQ(b.mass, 2.0);
  // m/12 (b^2 + c^2) and so on for a 0.4 x 0.3 x 0.2 box
  EXPECT_NEAR(b.inertia.x(), 2.0 / 12 * (0.09 + 0.04), 1e-12);
  EXPECT_NEAR(b.inertia.y(), 2.0 / 12 * (0.16 + 0.04), 1e-12);
  EXPECT_NEAR(b.inertia.z(), 2.0 / 12 * (0.16 + 0.09), 1e-12);
  expect_pose(b.X_WB, Pose3{Vec3(5, 6, 1.25), Quat::Identity()});
}

TEST(SdfWorld, VictimModelIsAVictimWithItsOwnBody) {
  const WorldSpec& spec = test_world().spec;
  ASSERT_EQ(spec.victims.size(), 1u);
  const VictimSpec& v = spec.victims.front();
  EXPECT_EQ(v.name, "victim_1");
  EXPECT_FALSE(v.figure);
  EXPECT_NEAR(v.pose.x, -2, 1e-12);
  EXPECT_NEAR(v.pose.y, -3, 1e-12);
  EXPECT_NEAR(v.pose.yaw, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(v.skin_temperature, 307.15);
  EXPECT_NEAR(v.length, 1.6, 1e-9);
  EXPECT_NEAR(v.width, 0.4, 1e-9);
  const SolidSpec& torso = solid_named(spec, "victim_1::body::torso");
  EXPECT_EQ(torso.victim, "victim_1");
  EXPECT_EQ(torso.material, "victim_1::body::clothes");
}

TEST(SdfWorld, RobotStartModel) {
  const WorldSpec& spec = test_world().spec;
  ASSERT_EQ(spec.robots.size(), 1u);
  const RobotPlacement& r = spec.robots.front();
  EXPECT_EQ(r.name, "robot");
  EXPECT_EQ(r.model, "rescue_robot");
  EXPECT_NEAR(r.start.x, 1, 1e-12);
  EXPECT_NEAR(r.start.y, -1, 1e-12);
  EXPECT_NEAR(r.start.yaw, 1, 1e-12);
  EXPECT_NEAR(r.height, 0.05, 1e-12);
  for (const auto& s : spec.solids) EXPECT_THAT(s.name, ::testing::Not(HasSubstr("robot_start")));
}

// A light on the link of a static model is a world light where the link puts it: a lamp post
// 2 m up at (3, 1), its spot pointing down the post's own -z, turned with the model.
TEST(SdfWorld, AStaticModelsLinkLightIsAWorldLight) {
  const SdfWorld w = parse_sdf_world(R"(<?xml version="1.0"?>
<sdf version="1.9"><world name="w">
  <model name="post"><static>true</static><pose>3 1 0 0 0 1.5707963267948966</pose>
    <link name="pole"><pose>0 0 2 0 0 0</pose>
      <collision name="c"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision>
      <light name="bulb" type="spot"><pose>0.5 0 0 0 0 0</pose><direction>1 0 -1</direction>
        <spot><inner_angle>0.2</inner_angle><outer_angle>0.6</outer_angle></spot></light>
    </link></model>
</world></sdf>)", "post.sdf", isolated());
  ASSERT_EQ(w.spec.lights.size(), 1u);
  const LightSpec& l = w.spec.lights[0];
  EXPECT_EQ(l.name, "bulb");
  EXPECT_LT((l.position - Vec3(3, 1.5, 2)).norm(), 1e-9);  // 0.5 m along the turned model's x: +y
  EXPECT_LT((l.direction - Vec3(0, 1, -1).normalized()).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(l.spot_angle, 0.3);
}

// `sun: false` on a Gazebo world drops its directional light named "sun" and keeps its lamps.
TEST(SdfWorld, NoSunDropsTheWorldsSunAndKeepsItsLamps) {
  WorldSpec spec = test_world().spec;
  spec.robots.clear();
  spec.sun = false;
  const World w = compile_world(spec, {});
  ASSERT_EQ(w.lights.size(), 2u);
  for (const auto& l : w.lights) EXPECT_NE(l.name, "sun");
  spec.sun = true;
  EXPECT_EQ(compile_world(spec, {}).lights.size(), 3u);
}

TEST(SdfWorld, Lights) {
  const WorldSpec& spec = test_world().spec;
  ASSERT_EQ(spec.lights.size(), 3u);
  const auto find = [&](const std::string& n) {
    for (const auto& l : spec.lights) {
      if (l.name == n) return l;
    }
    ADD_FAILURE() << "no light " << n;
    return LightSpec{};
  };
  const LightSpec sun = find("sun");
  EXPECT_EQ(sun.type, LightSpec::Type::directional);
  EXPECT_TRUE(sun.casts_shadows);
  EXPECT_LT((sun.direction - Vec3(-0.5, 0.1, -0.9).normalized()).norm(), 1e-9);
  const LightSpec lamp = find("lamp");
  EXPECT_EQ(lamp.type, LightSpec::Type::point);
  EXPECT_LT((lamp.position - Vec3(1, 2, 2.5)).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(lamp.range, 8);
  EXPECT_FALSE(lamp.casts_shadows);
  EXPECT_DOUBLE_EQ(lamp.intensity, 1.0);
  EXPECT_LT((lamp.color - Vec3(1, 0.9, 0.8)).norm(), 1e-6);
  // direction (1, 0, -1) in a frame turned a quarter about z
  const LightSpec spot = find("spot");
  EXPECT_EQ(spot.type, LightSpec::Type::spot);
  EXPECT_LT((spot.direction - Vec3(0, 1, -1).normalized()).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(spot.spot_angle, 0.5);
  EXPECT_DOUBLE_EQ(spot.intensity, 2.0);
}

TEST(SdfWorld, FloorCoversTheContentWithAMetreToSpare) {
  const WorldSpec& spec = test_world().spec;
  const Box2 b = spec.content_bounds();
  EXPECT_LT((spec.floor_min - (b.min - Vec2::Ones())).norm(), 1e-12);
  EXPECT_LT((spec.floor_max - (b.max + Vec2::Ones())).norm(), 1e-12);
  EXPECT_FALSE(validate(spec).has_errors()) << warnings(validate(spec));
}

TEST(SdfWorld, OnlySunAndGroundIsAnEmptyWorld) {
  const std::string text = R"(<?xml version="1.0"?>
<sdf version="1.9">
  <world name="bare">
    <include><uri>model://sun</uri></include>
    <include><uri>model://ground_plane</uri></include>
  </world>
</sdf>
)";
  const SdfWorld w = parse_sdf_world(text, "bare.sdf", isolated({}));
  EXPECT_TRUE(w.spec.solids.empty());
  EXPECT_EQ(w.spec.lights.size(), 1u);
  EXPECT_LT((w.spec.floor_max - w.spec.floor_min - Vec2(2, 2)).norm(), 1e-12);
  const Diagnostics d = validate(w.spec);
  EXPECT_TRUE(d.has_errors());
  EXPECT_THAT(warnings(d), HasSubstr("the world is empty"));
}

TEST(SdfWorld, UsersOwnGroundPlaneWins) {
  TempDir dir;
  dir.write("ground_plane/model.config", "<model><sdf version=\"1.9\">model.sdf</sdf></model>");
  dir.write("ground_plane/model.sdf", R"(<sdf version="1.9"><model name="my_ground"><static>true</static><link name="l">
    <collision name="c"><geometry><box><size>4 4 0.1</size></box></geometry></collision></link></model></sdf>)");
  const std::string text = R"(<sdf version="1.9"><world name="w"><include><uri>model://ground_plane</uri></include></world></sdf>)";
  const SdfWorld w = parse_sdf_world(text, "w.sdf", isolated({dir.path()}));
  ASSERT_EQ(w.spec.solids.size(), 1u);
  EXPECT_EQ(w.spec.solids.front().name, "my_ground::l::c");
}

TEST(SdfWorld, GazeboResourcePathFindsModels) {
  const ScopedEnv env("GZ_SIM_RESOURCE_PATH", models_dir().string());
  SdfOptions o;
  o.resolver = ResourceResolver({}, true);
  const std::string text = R"(<sdf version="1.9"><world name="w"><include><uri>model://ramp</uri></include></world></sdf>)";
  const SdfWorld w = parse_sdf_world(text, "w.sdf", o);
  EXPECT_EQ(solid_named(w.spec, "ramp::link::collision").geometry.type, Geometry::Type::mesh);
}

TEST(SdfWorld, NestedModelsAreFlattenedWithScopedNames) {
  const std::string text = R"(<sdf version="1.9"><world name="w">
  <model name="outer">
    <static>true</static>
    <pose>1 0 0 0 0 1.5707963267948966</pose>
    <model name="inner">
      <pose>1 0 0.5 0 0 0</pose>
      <link name="l"><collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
    </model>
  </model>
</world></sdf>)";
  const SdfWorld w = parse_sdf_world(text, "nested.sdf", isolated({}));
  const SolidSpec& s = solid_named(w.spec, "outer::inner::l::c");
  expect_pose(s.X_WS, Pose3::from_rpy(Vec3(1, 1, 0.5), 0, 0, M_PI / 2));
  EXPECT_NE(report_named(w, "outer::inner"), nullptr);
}

TEST(SdfWorld, ScenarioIncludesAddModelsToAnotherWorld) {
  SdfWorld report;
  report.spec.materials = default_materials();
  SdfInclude ramp{"model://ramp", "ramp_9", Pose3::from_rpy(Vec3(1, 2, 0), 0, 0, 0), true, {"scenario.yaml", 3, "world.include[0]"}};
  SdfInclude robot{"model://skid_steer", "", Pose3{Vec3(0, 0, 0), Quat::Identity()}, true, {"scenario.yaml", 4, "world.include[1]"}};
  add_sdf_includes({ramp, robot}, isolated(), report);
  const SolidSpec& r = solid_named(report.spec, "ramp_9::link::collision");
  expect_pose(r.X_WS, Pose3{Vec3(1, 2, 0), Quat::Identity()});
  ASSERT_EQ(report.robots.count("skid_steer"), 1u);
  ASSERT_EQ(report.spec.robots.size(), 1u);
  EXPECT_EQ(report.spec.robots.front().model, "skid_steer");
  // the chassis (the root link) stands 0.1 m above the model's origin
  EXPECT_NEAR(report.spec.robots.front().height, 0.1, 1e-12);
  EXPECT_LE(report.spec.floor_min.x(), 0.0);
  EXPECT_GE(report.spec.floor_max.y(), 3.5);
}

TEST(SdfWorld, IsSdfPath) {
  EXPECT_TRUE(is_sdf_path("a/b.sdf"));
  EXPECT_TRUE(is_sdf_path("x.world"));
  EXPECT_FALSE(is_sdf_path("x.urdf"));
  EXPECT_FALSE(is_sdf_path("x.svg"));
}

}  // namespace
}  // namespace rescuesim
