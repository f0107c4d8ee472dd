// Real Gazebo files read by the SDF importer: worlds from gazebosim/gz-sim (Fortress branch
// ign-gazebo6, Apache-2.0) and models from osrf/gazebo_models (CC-BY-3.0), kept unchanged in
// tests/data/thirdparty/gazebo (SOURCE.md names each file's origin and the commits). Every
// expected number is read off those files or computed by hand from them (the mesh counts with
// a short script over the OBJ and COLLADA text, see SOURCE.md), never from the importer.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "import/sdf/sdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using urdf_test::error_of;
using urdf_test::ScopedEnv;

fs::path gazebo_dir() { return fs::path(RESCUESIM_SOURCE_DIR) / "tests" / "data" / "thirdparty" / "gazebo"; }
fs::path world_file(const std::string& name) { return gazebo_dir() / "worlds" / (name + ".sdf"); }
fs::path models_dir() { return gazebo_dir() / "models"; }

/// Models found in the copied folder only (no Gazebo or ROS environment).
SdfOptions thirdparty_options() {
  SdfOptions o;
  o.resolver = ResourceResolver({models_dir()}, false);
  return o;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string warnings(const SdfWorld& w) {
  std::string out;
  for (const auto& d : w.diagnostics.items()) out += d.where.str() + ": " + d.message + "\n";
  return out;
}

/// The line (1-based) of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())), '\n'));
}

const BodySpec* body_named(const WorldSpec& spec, const std::string& name) {
  for (const auto& b : spec.bodies) {
    if (b.name == name) return &b;
  }
  ADD_FAILURE() << "no body " << name;
  return nullptr;
}

const SolidSpec* solid_named(const WorldSpec& spec, const std::string& name) {
  for (const auto& s : spec.solids) {
    if (s.name == name) return &s;
  }
  ADD_FAILURE() << "no solid " << name;
  return nullptr;
}

const SdfModelReport* report_named(const SdfWorld& w, const std::string& name) {
  for (const auto& m : w.models) {
    if (m.name == name) return &m;
  }
  ADD_FAILURE() << "no model report " << name;
  return nullptr;
}

void expect_vec(const Vec3& got, const Vec3& want, double tol, const std::string& what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << what << " [" << "xyz"[i] << "] got " << got.transpose();
}

/// Each extent of an approximation that lies inside the true shape: at most the true one and
/// at least 99.9% of it (the sampled hull keeps the poles and the equator).
void expect_inside_and_close(const Vec3& got, const Vec3& want, const std::string& what) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(got[i], want[i] + 1e-9) << what << " [" << "xyz"[i] << "] got " << got.transpose();
    EXPECT_GE(got[i], 0.999 * want[i]) << what << " [" << "xyz"[i] << "] got " << got.transpose();
  }
}

bool same_rotation(const Quat& a, const Quat& b, double tol = 1e-9) { return a.angularDistance(b) < tol; }

/// Lowest and highest corner of a geometry's triangles placed at X_WG.
std::pair<Vec3, Vec3> world_bounds(const Geometry& g, const Pose3& X_WG) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& v : mesh_of(g, 24).vertices) {
    const Vec3 w = X_WG * v;
    lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
  }
  return {lo, hi};
}

// --- examples/worlds/shapes.sdf ------------------------------------------------------------

TEST(SdfThirdPartyShapes, ModelsBecomeFloorAndFiveLooseBodies) {
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  EXPECT_EQ(w.sdf_version, "1.6");
  EXPECT_EQ(w.spec.name, "shapes");
  // six <model>s: ground_plane (static, a plane z = 0 facing up) and five non-static shapes
  // without joints; plus one <light>
  ASSERT_EQ(w.models.size(), 7u);
  EXPECT_EQ(report_named(w, "ground_plane")->becomes, "floor");
  EXPECT_TRUE(report_named(w, "ground_plane")->is_static);
  for (const char* m : {"box", "cylinder", "sphere", "capsule", "ellipsoid"}) {
    const SdfModelReport* r = report_named(w, m);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->becomes, "rigid body") << m;
    EXPECT_FALSE(r->is_static) << m;
    EXPECT_EQ(r->links, 1) << m;
    EXPECT_EQ(r->joints, 0) << m;
    EXPECT_EQ(r->collisions, 1) << m;
    EXPECT_EQ(r->visuals, 1) << m;
  }
  EXPECT_EQ(report_named(w, "sun")->becomes, "light");
  EXPECT_TRUE(w.spec.solids.empty()) << "the ground plane is the floor, not a solid";
  EXPECT_EQ(w.spec.bodies.size(), 5u);
  EXPECT_TRUE(w.robots.empty());
  EXPECT_TRUE(w.spec.robots.empty());
  EXPECT_TRUE(w.meshes.empty());
}

TEST(SdfThirdPartyShapes, NoPhysicsOrGravityElementKeepsRescuesimsDefaults) {
  // shapes.sdf has neither <physics> nor <gravity>: WorldSpec::physics_dt stays 0 ("the
  // scenario's") and gravity rescuesim's 9.81, not sdformat's filled-in defaults (1 ms, 9.8)
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  const std::string text = slurp(world_file("shapes"));
  ASSERT_EQ(text.find("<physics"), std::string::npos);
  ASSERT_EQ(text.find("<gravity"), std::string::npos);
  EXPECT_EQ(w.spec.physics_dt, 0.0);
  EXPECT_DOUBLE_EQ(w.spec.gravity, 9.81);
}

TEST(SdfThirdPartyShapes, PrimitivesKeepTheirSizePoseAndInertial) {
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  // <model name="box"><pose>0 0 0.5 0 0 0</pose>, <box><size>1 1 1</size>, mass 1, ixx=iyy=izz 0.16666
  const BodySpec* box = body_named(w.spec, "box::box_link");
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->geometry.type, Geometry::Type::box);
  expect_vec(box->geometry.size, {1, 1, 1}, 1e-12, "box size");
  expect_vec(box->X_WB.p, {0, 0, 0.5}, 1e-12, "box position");
  EXPECT_TRUE(same_rotation(box->X_WB.q, Quat::Identity()));
  EXPECT_DOUBLE_EQ(box->mass, 1.0);
  expect_vec(box->inertia, {0.16666, 0.16666, 0.16666}, 1e-12, "box inertia");

  // <pose>0 -1.5 0.5 0 0 0</pose>, radius 0.5, length 1: (diameter, diameter, length)
  const BodySpec* cyl = body_named(w.spec, "cylinder::cylinder_link");
  ASSERT_NE(cyl, nullptr);
  EXPECT_EQ(cyl->geometry.type, Geometry::Type::cylinder);
  expect_vec(cyl->geometry.size, {1, 1, 1}, 1e-12, "cylinder size");
  expect_vec(cyl->X_WB.p, {0, -1.5, 0.5}, 1e-12, "cylinder position");
  EXPECT_TRUE(same_rotation(cyl->X_WB.q, Quat::Identity()));
  EXPECT_DOUBLE_EQ(cyl->mass, 1.0);
  expect_vec(cyl->inertia, {0.1458, 0.1458, 0.125}, 1e-12, "cylinder inertia");

  // <pose>0 1.5 0.5 0 0 0</pose>, radius 0.5
  const BodySpec* sph = body_named(w.spec, "sphere::sphere_link");
  ASSERT_NE(sph, nullptr);
  EXPECT_EQ(sph->geometry.type, Geometry::Type::sphere);
  expect_vec(sph->geometry.size, {1, 1, 1}, 1e-12, "sphere size");
  expect_vec(sph->X_WB.p, {0, 1.5, 0.5}, 1e-12, "sphere position");
  expect_vec(sph->inertia, {0.1, 0.1, 0.1}, 1e-12, "sphere inertia");
}

TEST(SdfThirdPartyShapes, CapsuleAndEllipsoidBecomeConvexShapes) {
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  // Geometry has no capsule or ellipsoid: both become convex hulls of points sampled on the
  // round surface (poles and equator included), kept as they are for a loose body of one shape,
  // so each extent is the true one.
  // capsule: <pose>0 -3.0 0.5 0 0 0</pose>, radius 0.2, length 0.6 -> 0.4 x 0.4 x (0.6 + 2 x 0.2)
  const BodySpec* cap = body_named(w.spec, "capsule::capsule_link");
  ASSERT_NE(cap, nullptr);
  EXPECT_EQ(cap->geometry.type, Geometry::Type::convex);
  expect_inside_and_close(cap->geometry.size, {0.4, 0.4, 1.0}, "capsule extent");
  expect_vec(cap->X_WB.p, {0, -3.0, 0.5}, 1e-12, "capsule position");
  EXPECT_TRUE(same_rotation(cap->X_WB.q, Quat::Identity()));
  EXPECT_DOUBLE_EQ(cap->mass, 1.0);
  expect_vec(cap->inertia, {0.074154, 0.074154, 0.018769}, 1e-12, "capsule inertia");
  // centred on the body frame: the file puts the shape at the link origin
  const auto [cap_lo, cap_hi] = world_bounds(cap->geometry, cap->X_WB);
  expect_vec(0.5 * (cap_lo + cap_hi), {0, -3.0, 0.5}, 0.005, "capsule centre");

  // ellipsoid: <pose>0 3.0 0.5 0 0 0</pose>, radii 0.2 0.3 0.5 -> 0.4 x 0.6 x 1.0
  const BodySpec* ell = body_named(w.spec, "ellipsoid::ellipsoid_link");
  ASSERT_NE(ell, nullptr);
  EXPECT_EQ(ell->geometry.type, Geometry::Type::convex);
  expect_vec(ell->X_WB.p, {0, 3.0, 0.5}, 1e-12, "ellipsoid position");
  // the inertia is diagonal with distinct moments: the principal axes are the link's own
  EXPECT_TRUE(same_rotation(ell->X_WB.q, Quat::Identity()));
  expect_vec(ell->inertia, {0.068, 0.058, 0.026}, 1e-12, "ellipsoid inertia");
  const auto [ell_lo, ell_hi] = world_bounds(ell->geometry, ell->X_WB);
  expect_inside_and_close(ell_hi - ell_lo, {0.4, 0.6, 1.0}, "ellipsoid extent in the world");
  expect_vec(0.5 * (ell_lo + ell_hi), {0, 3.0, 0.5}, 0.005, "ellipsoid centre");
}

TEST(SdfThirdPartyShapes, VisualColoursBecomeMaterials) {
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  // each <visual><material><diffuse>
  const std::vector<std::pair<std::string, Vec3>> want{{"box::box_link", {1, 0, 0}},         {"cylinder::cylinder_link", {0, 1, 0}},
                                                       {"sphere::sphere_link", {0, 0, 1}},   {"capsule::capsule_link", {1, 1, 0}},
                                                       {"ellipsoid::ellipsoid_link", {1, 0, 1}}};
  for (const auto& [name, color] : want) {
    const BodySpec* b = body_named(w.spec, name);
    ASSERT_NE(b, nullptr);
    const MaterialSpec* m = w.spec.find_material(b->material);
    ASSERT_NE(m, nullptr) << name << " material " << b->material;
    expect_vec(m->color, color, 1e-12, name + " colour");
  }
}

TEST(SdfThirdPartyShapes, TheSunIsADirectionalLight) {
  const SdfWorld w = load_sdf_world(world_file("shapes"), thirdparty_options());
  ASSERT_EQ(w.spec.lights.size(), 1u);
  const LightSpec& l = w.spec.lights[0];
  EXPECT_EQ(l.name, "sun");
  EXPECT_EQ(l.type, LightSpec::Type::directional);
  expect_vec(l.position, {0, 0, 10}, 1e-12, "sun position");
  // <direction>-0.5 0.1 -0.9</direction>, normalised (the light's pose has no rotation)
  expect_vec(l.direction, Vec3(-0.5, 0.1, -0.9).normalized(), 1e-9, "sun direction");
  expect_vec(l.color, {0.8, 0.8, 0.8}, 1e-6, "sun colour");  // <diffuse>, stored as float by sdformat
  EXPECT_DOUBLE_EQ(l.range, 1000.0);
  EXPECT_TRUE(l.casts_shadows);
  EXPECT_DOUBLE_EQ(l.intensity, 1.0);
}

// --- examples/worlds/lights.sdf ------------------------------------------------------------

// The world's three lights are kept; the point light on the loose sphere's link cannot follow the
// sphere (only robots' lamps move with their links), so it is left out, loudly, naming it.
TEST(SdfThirdPartyLights, WorldLightsKeptAndALooseBodysLinkLightNamed) {
  const SdfWorld w = load_sdf_world(world_file("lights"), thirdparty_options());
  ASSERT_EQ(w.spec.lights.size(), 3u);
  EXPECT_EQ(w.spec.lights[2].name, "spot");
  EXPECT_EQ(w.spec.lights[2].type, LightSpec::Type::spot);
  EXPECT_DOUBLE_EQ(w.spec.lights[2].spot_angle, 0.25);  // half of <outer_angle>0.5
  bool named = false;
  for (const auto& d : w.diagnostics.items()) {
    named = named || (d.message.find("light 'link_light_point' on the loose body 'sphere::sphere_link' is left out") != std::string::npos &&
                      d.where.line == 217);
  }
  EXPECT_TRUE(named);
}

// --- examples/worlds/diff_drive.sdf -------------------------------------------------------

TEST(SdfThirdPartyDiffDrive, TwoVehiclesBecomeRobotsWithThePluginsDrive) {
  SdfWorld w;
  ASSERT_NO_THROW(w = load_sdf_world(world_file("diff_drive"), thirdparty_options())) << "gz-sim's own diff-drive example must load";
  ASSERT_EQ(w.robots.size(), 2u);
  for (const char* name : {"vehicle_blue", "vehicle_green"}) {
    ASSERT_TRUE(w.robots.count(name)) << name;
    const RobotSpec& r = w.robots.at(name);
    // <plugin filename="ignition-gazebo-diff-drive-system">: <left_joint>left_wheel_joint,
    // <right_joint>right_wheel_joint, <wheel_separation>1.25, <wheel_radius>0.3
    EXPECT_EQ(r.drive.left_wheels, std::vector<std::string>{"left_wheel_joint"}) << name;
    EXPECT_EQ(r.drive.right_wheels, std::vector<std::string>{"right_wheel_joint"}) << name;
    EXPECT_DOUBLE_EQ(r.drive.wheel_radius, 0.3) << name;
    EXPECT_DOUBLE_EQ(r.drive.track_width, 1.25) << name;
    // both wheels are rolled -1.5707 about x, so +z of the joint is +y of the chassis: a positive
    // wheel speed rolls the vehicle forward on both sides
    EXPECT_EQ(wheel_sign(r.drive.left_signs, 0), 1.0) << name;
    EXPECT_EQ(wheel_sign(r.drive.right_signs, 0), 1.0) << name;
    // chassis, two wheels and the caster; the chassis is the base
    ASSERT_FALSE(r.links.empty());
    EXPECT_EQ(r.links[0].name, "chassis") << name;
    EXPECT_GE(r.link_index("left_wheel"), 0) << name;
    EXPECT_GE(r.link_index("right_wheel"), 0) << name;
    EXPECT_DOUBLE_EQ(r.links[0].mass, 1.14395) << name;
    // every link is kept: chassis 1.14395 + two wheels of 2 + caster 1 (<inertial><mass>)
    EXPECT_EQ(r.links.size(), 4u) << name;
    EXPECT_NEAR(r.total_mass(), 6.14395, 1e-9) << name;
    ASSERT_GE(r.joint_index("left_wheel_joint"), 0) << name;
    const JointSpec& lw = r.joints[static_cast<std::size_t>(r.joint_index("left_wheel_joint"))];
    EXPECT_EQ(lw.parent, "chassis");
    EXPECT_EQ(lw.child, "left_wheel");
    // left_wheel's pose in the model minus chassis's: (0.554283 + 0.151427, 0.625029, -0.025 - 0.175)
    expect_vec(lw.X_PJ.p, {0.70571, 0.625029, -0.2}, 1e-9, std::string(name) + " left wheel joint");
    EXPECT_TRUE(std::count(w.plugins_honoured.begin(), w.plugins_honoured.end(), std::string(name) + "::ignition-gazebo-diff-drive-system"))
        << name;
  }
}

TEST(SdfThirdPartyDiffDrive, RobotsStartWhereTheirChassisIsAndTheStepIsKept) {
  SdfWorld w;
  ASSERT_NO_THROW(w = load_sdf_world(world_file("diff_drive"), thirdparty_options()));
  // model pose (0, +-2, 0.325) + chassis link pose (-0.151427, 0, 0.175)
  ASSERT_EQ(w.spec.robots.size(), 2u);
  for (const auto& p : w.spec.robots) {
    const double y = p.name == "vehicle_blue" ? 2.0 : -2.0;
    EXPECT_EQ(p.model, p.name);
    EXPECT_NEAR(p.start.x, -0.151427, 1e-9) << p.name;
    EXPECT_NEAR(p.start.y, y, 1e-9) << p.name;
    EXPECT_NEAR(p.start.yaw, 0.0, 1e-9) << p.name;
    EXPECT_NEAR(p.height, 0.5, 1e-9) << p.name;
  }
  EXPECT_DOUBLE_EQ(w.spec.physics_dt, 0.001);  // <max_step_size>0.001</max_step_size>
  // the three world systems are rescuesim's own work: listed, not warned about
  for (const char* s : {"world::ignition-gazebo-physics-system", "world::ignition-gazebo-user-commands-system",
                        "world::ignition-gazebo-scene-broadcaster-system"}) {
    EXPECT_TRUE(std::count(w.plugins_ignored.begin(), w.plugins_ignored.end(), std::string(s))) << s;
  }
  for (const auto& d : w.diagnostics.items()) EXPECT_THAT(d.message, ::testing::Not(HasSubstr("world plugin"))) << d.where.str();
  EXPECT_TRUE(w.spec.solids.empty());
  EXPECT_TRUE(w.spec.bodies.empty());
}

// --- test/worlds/office.sdf + models/building_L1 (OBJ meshes) -------------------------------

TEST(SdfThirdPartyOffice, StaticBuildingKeepsItsObjMeshesExact) {
  const SdfWorld w = load_sdf_world(world_file("office"), thirdparty_options());
  EXPECT_EQ(w.sdf_version, "1.7");
  EXPECT_EQ(w.spec.name, "office_world");
  EXPECT_DOUBLE_EQ(w.spec.physics_dt, 0.01);
  const SdfModelReport* rep = report_named(w, "building_L1");
  ASSERT_NE(rep, nullptr);
  EXPECT_EQ(rep->becomes, "static geometry");
  EXPECT_TRUE(rep->is_static);
  EXPECT_EQ(rep->links, 2);
  EXPECT_EQ(rep->collisions, 2);
  EXPECT_EQ(rep->visuals, 2);
  ASSERT_EQ(w.spec.solids.size(), 2u);
  EXPECT_TRUE(w.spec.bodies.empty());

  // floor_1.obj: 36 vertices, 32 triangular faces; x 2.277641406067981..23.683364858074697,
  // y -12.004054854196562..-1.1435613801846989, z -0.1..0 (<include><pose>0 0 0.0 0 0 0)
  const SolidSpec* floor = solid_named(w.spec, "building_L1::floor_1::collision");
  ASSERT_NE(floor, nullptr);
  EXPECT_EQ(floor->geometry.type, Geometry::Type::mesh);
  EXPECT_EQ(floor->geometry.mesh.triangles.size(), 32u);
  EXPECT_TRUE(floor->X_WS.p.isZero(1e-12));
  EXPECT_TRUE(same_rotation(floor->X_WS.q, Quat::Identity()));
  const auto [flo, fhi] = world_bounds(floor->geometry, floor->X_WS);
  expect_vec(flo, {2.277641406067981, -12.004054854196562, -0.1}, 1e-6, "floor_1 low corner");
  expect_vec(fhi, {23.683364858074697, -1.1435613801846989, 0.0}, 1e-6, "floor_1 high corner");

  // wall_1.obj: 248 vertices, 310 triangular faces, z 0..2.5
  const SolidSpec* wall = solid_named(w.spec, "building_L1::wall_1::collision");
  ASSERT_NE(wall, nullptr);
  EXPECT_EQ(wall->geometry.type, Geometry::Type::mesh);
  EXPECT_EQ(wall->geometry.mesh.triangles.size(), 310u);
  const auto [wlo, whi] = world_bounds(wall->geometry, wall->X_WS);
  expect_vec(wlo, {2.2105, -12.0579, 0.0}, 1e-6, "wall_1 low corner");
  expect_vec(whi, {23.741, -1.0763, 2.5}, 1e-6, "wall_1 high corner");

  // what the importer reports of the two collision meshes
  int found = 0;
  for (const auto& m : w.meshes) {
    if (!m.collision) continue;
    ++found;
    EXPECT_TRUE(m.exact) << m.uri;
    EXPECT_EQ(m.model, "building_L1");
    if (m.link == "floor_1") {
      EXPECT_EQ(m.uri, "model://building_L1/meshes/floor_1.obj");
      EXPECT_EQ(fs::weakly_canonical(m.file), fs::weakly_canonical(models_dir() / "building_L1" / "meshes" / "floor_1.obj"));
      EXPECT_EQ(m.triangles, 32);
    } else {
      EXPECT_EQ(m.link, "wall_1");
      EXPECT_EQ(m.triangles, 310);
    }
  }
  EXPECT_EQ(found, 2);
}

TEST(SdfThirdPartyOffice, WorldPluginsAndLight) {
  const SdfWorld w = load_sdf_world(world_file("office"), thirdparty_options());
  // user commands and scene broadcaster are rescuesim's own work; the COLLADA exporter is not
  for (const char* s : {"world::libignition-gazebo-user-commands-system.so", "world::libignition-gazebo-scene-broadcaster-system.so",
                        "world::ignition-gazebo-collada-world-exporter-system"}) {
    EXPECT_TRUE(std::count(w.plugins_ignored.begin(), w.plugins_ignored.end(), std::string(s))) << s;
  }
  int exporter_warnings = 0;
  for (const auto& d : w.diagnostics.items()) exporter_warnings += d.message.find("collada-world-exporter") != std::string::npos;
  EXPECT_EQ(exporter_warnings, 1) << warnings(w);
  ASSERT_EQ(w.spec.lights.size(), 1u);
  EXPECT_EQ(w.spec.lights[0].name, "sun");
  expect_vec(w.spec.lights[0].color, {1, 1, 1}, 1e-12, "office sun colour");
}

TEST(SdfThirdPartyOffice, ModelUriResolvesThroughGazeboResourcePaths) {
  const ScopedEnv ign("IGN_GAZEBO_RESOURCE_PATH", std::nullopt), classic("GAZEBO_MODEL_PATH", std::nullopt);
  SdfOptions env_only;  // no folders of its own: the environment's
  {
    const ScopedEnv gz("GZ_SIM_RESOURCE_PATH", "/nonexistent-rescuesim-folder:" + models_dir().string());
    const SdfWorld w = load_sdf_world(world_file("office"), env_only);
    EXPECT_EQ(w.spec.solids.size(), 2u);
  }
  {
    // Fortress's name for the same variable
    const ScopedEnv gz("GZ_SIM_RESOURCE_PATH", std::nullopt);
    const ScopedEnv fortress("IGN_GAZEBO_RESOURCE_PATH", models_dir().string());
    const SdfWorld w = load_sdf_world(world_file("office"), env_only);
    EXPECT_EQ(w.spec.solids.size(), 2u);
  }
  {
    // nowhere: an Error naming the URI and the file that asked for it
    const ScopedEnv gz("GZ_SIM_RESOURCE_PATH", std::nullopt);
    SdfOptions nowhere;
    nowhere.resolver = ResourceResolver({}, false);
    const Error e = error_of([&] { load_sdf_world(world_file("office"), nowhere); });
    EXPECT_THAT(e.what(), HasSubstr("model://building_L1"));
    EXPECT_THAT(e.where().file, HasSubstr("office.sdf")) << e.what();
  }
}

// --- osrf/gazebo_models: nist_simple_ramp_120 (static COLLADA) ------------------------------

TEST(SdfThirdPartyRamp, StaticModelFileKeepsTheColladaMeshExact) {
  const fs::path file = models_dir() / "nist_simple_ramp_120" / "model.sdf";
  const SdfWorld w = load_sdf_world(file, thirdparty_options());
  EXPECT_EQ(w.sdf_version, "1.5");
  ASSERT_EQ(w.spec.solids.size(), 1u);
  const SolidSpec& s = w.spec.solids[0];
  EXPECT_EQ(s.name, "nist_simple_ramp_120::nist_simple_ramp_120_link::collision");
  EXPECT_EQ(s.geometry.type, Geometry::Type::mesh);
  // one <polylist> of 12 triangles over 8 positions
  EXPECT_EQ(s.geometry.mesh.triangles.size(), 12u);
  EXPECT_TRUE(s.X_WS.p.isZero(1e-12));
  // positions span x -0.5900002..0.5900003, y -0.5900004..0.5900003, z -1.19209e-7..1.2 (1 m unit)
  expect_vec(s.geometry.size, {1.1800005, 1.1800007, 1.2000001192}, 1e-6, "ramp extent");
  // the 1.2 m high edge is at file y = -0.59; the node's <rotate>0 0 1 -180</rotate> puts it at +0.59
  int high = 0;
  for (const Vec3& v : s.geometry.mesh.vertices) {
    if (v.z() > 1.19) {
      ++high;
      EXPECT_NEAR(v.y(), 0.59, 1e-6) << "a vertex of the ramp's top edge: " << v.transpose();
    } else if (v.z() < 0.03) {
      EXPECT_NEAR(v.y(), -0.59, 1e-6) << "a vertex of the ramp's foot: " << v.transpose();
    }
  }
  EXPECT_GE(high, 2);
  ASSERT_EQ(w.meshes.size(), 1u);
  EXPECT_EQ(w.meshes[0].triangles, 12);
  EXPECT_TRUE(w.meshes[0].exact);
  EXPECT_TRUE(w.meshes[0].collision);
  EXPECT_EQ(report_named(w, "nist_simple_ramp_120")->becomes, "static geometry");
  // its COLLADA names ../materials/textures/plywood256x256.png: found beside the model and drawn
  // on the exact mesh, with texture coordinates for every one of its 12 triangles
  EXPECT_EQ(w.meshes[0].texture, "../materials/textures/plywood256x256.png");
  EXPECT_TRUE(w.meshes[0].texture_drawn);
  ASSERT_NE(s.geometry.image, nullptr);
  EXPECT_TRUE(s.geometry.image->file.ends_with("nist_simple_ramp_120/materials/textures/plywood256x256.png")) << s.geometry.image->file;
  EXPECT_EQ(s.geometry.image->corner_uvs.size(), 12u);
  for (const auto& corners : s.geometry.image->corner_uvs) {
    for (const Vec2& uv : corners) EXPECT_TRUE(uv.allFinite());
  }
}

TEST(SdfThirdPartyRamp, IncludedByUriAtAPose) {
  SdfWorld w;
  SdfInclude inc;
  inc.uri = "model://nist_simple_ramp_120";  // model.config: model.sdf for SDF 1.5, the highest listed
  inc.name = "ramp";
  inc.pose = Pose3::from_rpy({3, -2, 0}, 0, 0, M_PI / 2);
  inc.has_pose = true;
  add_sdf_includes({inc}, thirdparty_options(), w);
  ASSERT_EQ(w.spec.solids.size(), 1u);
  const SolidSpec& s = w.spec.solids[0];
  EXPECT_EQ(s.name, "ramp::nist_simple_ramp_120_link::collision");
  expect_vec(s.X_WS.p, {3, -2, 0}, 1e-12, "ramp position");
  EXPECT_TRUE(same_rotation(s.X_WS.q, inc.pose.q));
  // turned 90 degrees left, the high edge (model +y) faces world -x: x = 3 - 0.59
  for (const Vec3& v : s.geometry.mesh.vertices) {
    const Vec3 p = s.X_WS * v;
    if (p.z() > 1.19) {
      EXPECT_NEAR(p.x(), 3 - 0.59, 1e-6) << p.transpose();
    }
  }
}

// --- osrf/gazebo_models: construction_cone (non-static, inch COLLADA, scale 10) -------------

TEST(SdfThirdPartyCone, LooseConeIsAConvexHullOfItsScaledMesh) {
  SdfWorld w;
  SdfInclude inc;
  inc.uri = "model://construction_cone";
  inc.pose = Pose3{{1, 1, 0}, Quat::Identity()};
  inc.has_pose = true;
  add_sdf_includes({inc}, thirdparty_options(), w);
  ASSERT_EQ(w.spec.bodies.size(), 1u);
  const BodySpec& b = w.spec.bodies[0];
  EXPECT_EQ(b.name, "Construction Cone::link");  // the model's own name (with its space)
  EXPECT_EQ(b.geometry.type, Geometry::Type::convex);
  // positions: x, y +-0.99 in, z 0..4.286964 in; x 0.0254 m/in x 10 (<scale>) = 0.254
  const auto [lo, hi] = world_bounds(b.geometry, b.X_WB);
  expect_vec(lo, {1 - 0.25146, 1 - 0.25146, 0.0}, 0.01, "cone low corner");
  expect_vec(hi, {1 + 0.25146, 1 + 0.25146, 1.08888886}, 0.01, "cone high corner");
  EXPECT_GT(b.mass, 0.0);
  // no <inertial>: a density estimate, said so
  bool said = false;
  for (const auto& d : w.diagnostics.items()) said |= d.message.find("no <inertial>") != std::string::npos;
  EXPECT_TRUE(said) << warnings(w);
  // one <triangles count="166">, loaded whole, then hulled (not exact: the cone moves)
  ASSERT_EQ(w.meshes.size(), 1u);
  EXPECT_EQ(w.meshes[0].triangles, 166);
  EXPECT_FALSE(w.meshes[0].exact);
  EXPECT_TRUE(w.meshes[0].collision);
  EXPECT_EQ(w.meshes[0].uri, "model://construction_cone/meshes/construction_cone.dae");
}

// --- examples/worlds/import_mesh.sdf (a Fuel URI) ------------------------------------------

TEST(SdfThirdPartyFuel, FuelUriIsAnErrorNamingIt) {
  const fs::path file = world_file("import_mesh");
  const std::string uri = "https://fuel.gazebosim.org/1.0/openrobotics/models/Electrical Box";
  const Error e = error_of([&] { load_sdf_world(file, thirdparty_options()); });
  EXPECT_THAT(e.what(), HasSubstr(uri));
  EXPECT_THAT(e.where().file, HasSubstr("import_mesh.sdf")) << e.what();
  // it says what to do instead of where a URL is not
  EXPECT_THAT(e.what(), HasSubstr("does not download models from Gazebo Fuel"));
  EXPECT_THAT(e.what(), Not(HasSubstr("searched")));
  // the <include> (or its <uri>) is where the problem is
  const std::string text = slurp(file);
  EXPECT_GE(e.where().line, line_of(text, "<include>")) << e.what();
  EXPECT_LE(e.where().line, line_of(text, "<uri>https://")) << e.what();
}

}  // namespace
}  // namespace rescuesim
