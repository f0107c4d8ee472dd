// A URDF robot whose chassis collides through an STL mesh (written here, byte by byte): the
// mesh becomes one convex hull, the chassis comes to rest on its lowest hull point, level, and
// on four wheels the robot climbs a ramp onto a platform. Expected heights are read off the
// mesh and the URDF by hand.

#include "physics/physics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "import/urdf/urdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim {
namespace {

using urdf_test::TempDir;

/// The chassis, seen from the side (x forward, z up), 0.3 m wide (y = +-0.15): a box 0.4 long
/// and 0.1 tall (x -0.2..0.2, z -0.03..0.07) joined at the front with a wedge whose top runs
/// on to x = 0.3 and whose face slopes back down to the bottom edge at x = 0.2.
/// Volume: box 0.4 x 0.3 x 0.1 = 0.012 plus wedge 0.1 x 0.1 / 2 x 0.3 = 0.0015 m^3.
constexpr double kMeshBottom = -0.03;    ///< lowest vertex z in the mesh frame (m)
constexpr double kCollisionZ = 0.01;     ///< <collision><origin z> of the mesh on the chassis link (m)
constexpr double kVolume = 0.0135;       ///< m^3
TriangleMesh chassis_mesh() { return urdf_test::xz_prism({{-0.2, kMeshBottom}, {0.2, kMeshBottom}, {0.3, 0.07}, {-0.2, 0.07}}, 0.15); }

/// The chassis link (4 kg, centre of mass off-centre) with the mesh as visual and collision.
const char* kChassisLink = R"(  <link name="chassis">
    <inertial>
      <origin xyz="0.02 0 0.02"/>
      <mass value="4"/>
      <inertia ixx="0.033" ixy="0" ixz="0" iyy="0.057" iyz="0" izz="0.083"/>
    </inertial>
    <visual><geometry><mesh filename="chassis.stl"/></geometry></visual>
    <collision>
      <origin xyz="0 0 0.01"/>
      <geometry><mesh filename="chassis.stl"/></geometry>
    </collision>
  </link>
)";

/// Four wheels of radius 0.08 (0.3 kg, solid-cylinder inertia) at x = +-0.15, y = +-0.18,
/// z = 0 on the chassis, on continuous joints lf, lr, rf, rr whose axes point along +y.
std::string four_wheels() {
  struct Wheel {
    const char* name;
    double x, y;
  };
  std::string out;
  for (const Wheel& w : {Wheel{"lf", 0.15, 0.18}, Wheel{"lr", -0.15, 0.18}, Wheel{"rf", 0.15, -0.18}, Wheel{"rr", -0.15, -0.18}}) {
    const std::string n = w.name;
    out += "  <link name=\"" + n +
           "_wheel\">\n"
           "    <inertial><mass value=\"0.3\"/><inertia ixx=\"0.00052\" ixy=\"0\" ixz=\"0\" iyy=\"0.00052\" iyz=\"0\" "
           "izz=\"0.00096\"/></inertial>\n"
           "    <collision><geometry><cylinder radius=\"0.08\" length=\"0.04\"/></geometry></collision>\n"
           "  </link>\n"
           "  <joint name=\"" +
           n +
           "\" type=\"continuous\">\n"
           "    <parent link=\"chassis\"/><child link=\"" +
           n +
           "_wheel\"/>\n"
           "    <origin xyz=\"" +
           std::to_string(w.x) + " " + std::to_string(w.y) +
           " 0\" rpy=\"-1.5707963 0 0\"/>\n"
           "    <axis xyz=\"0 0 1\"/>\n"
           "    <limit effort=\"10\" velocity=\"20\"/>\n"
           "  </joint>\n";
  }
  return out;
}

constexpr double kWheelRadius = 0.08;

/// Writes the chassis STL and a URDF of the chassis (and wheels) beside it, and loads it.
UrdfRobot load_robot(const TempDir& dir, bool wheels) {
  dir.write("chassis.stl", urdf_test::binary_stl(chassis_mesh()));
  const auto file =
      dir.write("robot.urdf", std::string("<robot name=\"crawler\">\n") + kChassisLink + (wheels ? four_wheels() : "") + "</robot>\n");
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  return load_urdf(file, o);
}

/// A floor from (-3, -3) to (5, 3) with the robot at the origin facing +x; `platform` adds a
/// raised area 0.1 m high from x = 1.5 to 3 (y = -1..1) with a 0.6 m ramp up to it along -x.
World make_world(const RobotSpec& robot, bool platform) {
  WorldSpec w;
  w.floor_min = {-3, -3};
  w.floor_max = {5, 3};
  w.materials = default_materials();
  if (platform) {
    RaisedAreaSpec r;
    r.outline = {{1.5, -1}, {3, -1}, {3, 1}, {1.5, 1}};
    r.height = 0.1;
    r.ramp_edges = {3};  // (1.5, 1) -> (1.5, -1): its outward side is -x
    r.ramp_length = 0.6;
    w.raised_areas.push_back(r);
  }
  RobotPlacement p;
  p.name = "crawler";
  p.model = "crawler";
  w.robots.push_back(p);
  return compile_world(w, {{"crawler", robot}});
}

/// Roll and pitch (rad) of a pose: the tilt of its z axis about x and y.
double roll_of(const Pose3& X) {
  const Eigen::Matrix3d R = X.q.toRotationMatrix();
  return std::atan2(R(2, 1), R(2, 2));
}
double pitch_of(const Pose3& X) {
  const Eigen::Matrix3d R = X.q.toRotationMatrix();
  return std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
}

constexpr double kHalfDegree = 0.5 * M_PI / 180;

TEST(MeshRobot, CollisionMeshBecomesOneConvexHull) {
  TempDir dir;
  const UrdfRobot u = load_robot(dir, false);
  ASSERT_EQ(u.meshes.size(), 2u);  // the visual and the collision
  const UrdfMeshReport* collision = nullptr;
  for (const auto& m : u.meshes) {
    EXPECT_EQ(m.triangles, 12) << m.uri;  // a four-sided prism: 2 x 2 cap triangles + 4 x 2 side triangles
    if (m.collision) collision = &m;
  }
  ASSERT_NE(collision, nullptr);
  EXPECT_EQ(collision->pieces, 1);
  EXPECT_LE(collision->hull_vertices, 64);
  EXPECT_EQ(collision->hull_vertices, 8);  // the prism is convex: its hull is its own 8 corners
  EXPECT_NEAR(collision->mesh_volume, kVolume, 1e-9);
  EXPECT_NEAR(collision->hull_volume, kVolume, 1e-9);
}

TEST(MeshRobot, ChassisRestsLevelOnItsLowestHullPoint) {
  TempDir dir;
  const UrdfRobot u = load_robot(dir, false);
  const World world = make_world(u.spec, false);
  Physics physics(world);
  State s;
  physics.init_state(s);
  const int steps = static_cast<int>(std::lround(2.0 / physics.dt()));
  for (int i = 0; i < steps; ++i) physics.step(s);
  const Pose3& X_WB = s.robots[0].base.X_WB;
  // the lowest point of the hull is the mesh bottom, moved up by the collision origin; resting
  // contacts settle within micrometres, so 1 mm is room enough (a collision margin added
  // outside the hull would show here as a robot floating by that margin)
  EXPECT_NEAR(X_WB.p.z(), -(kMeshBottom + kCollisionZ), 0.001);
  EXPECT_NEAR(roll_of(X_WB), 0.0, kHalfDegree);
  EXPECT_NEAR(pitch_of(X_WB), 0.0, kHalfDegree);
  // and it stays where it was put
  EXPECT_LT(X_WB.p.head<2>().norm(), 0.005);
  EXPECT_LT(s.robots[0].base.v_WB.norm(), 1e-3);
  EXPECT_EQ(s.trouble.nan_poses + s.trouble.escaped, 0) << s.trouble.first;
}

TEST(MeshRobot, WheeledMeshRobotClimbsARampOntoAPlatform) {
  TempDir dir;
  UrdfRobot u = load_robot(dir, true);
  configure_diff_drive(u.spec, {"lf", "lr"}, {"rf", "rr"}, 0, 0, {});
  ASSERT_NEAR(u.spec.drive.wheel_radius, kWheelRadius, 1e-9);
  ASSERT_NEAR(u.spec.drive.track_width, 0.36, 1e-9);
  const World world = make_world(u.spec, true);
  const RobotSpec& spec = world.robots[0].spec;
  Physics physics(world);
  State s;
  physics.init_state(s);
  const double dt = physics.dt();
  auto run = [&](double seconds, double speed, double stop_at_x) {
    for (int i = 0; i < static_cast<int>(std::lround(seconds / dt)); ++i) {
      if (s.robots[0].base.X_WB.p.x() > stop_at_x) return;
      for (const auto* side : {&spec.drive.left_wheels, &spec.drive.right_wheels}) {
        for (const auto& name : *side) s.robots[0].joint_target[static_cast<std::size_t>(spec.joint_index(name))] = speed / kWheelRadius;
      }
      physics.step(s);
    }
  };

  // settle on the flat floor: the chassis rides on its wheels, the link origin at wheel height
  run(0.5, 0.0, 1e9);
  const double z_flat = s.robots[0].base.X_WB.p.z();
  EXPECT_NEAR(z_flat, kWheelRadius, 0.003);

  // drive forward at 0.3 m/s up the 0.6 m ramp (x 0.9..1.5) until the centre is 0.7 m onto the
  // platform, then stop and let it settle
  const double platform = 0.1;
  run(20.0, 0.3, 2.2);
  EXPECT_GT(s.robots[0].base.X_WB.p.x(), 2.2) << "did not get up the ramp; z = " << s.robots[0].base.X_WB.p.z();
  run(1.0, 0.0, 1e9);

  const Pose3& X_WB = s.robots[0].base.X_WB;
  EXPECT_GT(X_WB.p.z() - z_flat, 0.8 * platform);
  EXPECT_NEAR(X_WB.p.z() - z_flat, platform, 0.005);  // all four wheels on the platform top
  // on the platform (x 1.5..3, y -1..1) with its wheels inside the edges
  EXPECT_GT(X_WB.p.x() - 0.23, 1.5);
  EXPECT_LT(X_WB.p.x() + 0.3, 3.0);
  EXPECT_LT(std::abs(X_WB.p.y()), 0.5);
  EXPECT_NEAR(roll_of(X_WB), 0.0, kHalfDegree);
  EXPECT_NEAR(pitch_of(X_WB), 0.0, kHalfDegree);
  EXPECT_EQ(s.trouble.nan_poses + s.trouble.escaped, 0) << s.trouble.first;
}

}  // namespace
}  // namespace rescuesim
