#pragma once
/// RobotSpec: a robot described as data — links with mass and shapes, joints with limits and
/// actuation, a drive, and sensors with their mount frames. The built-in rescue robot
/// (src/robots) is one; URDF models (import/urdf) produce the same structure. Frames: each
/// link's frame is its joint frame; X_PJ places a joint in its parent link's frame.

#include <string>
#include <vector>

#include "core/pose.h"
#include "world/geometry.h"
#include "world/sensor_spec.h"
#include "world/world_spec.h"

namespace rescuesim {

/// One shape of a link, for collision and looks.
struct LinkShape {
  Geometry geometry;
  Pose3 X_LG;                 ///< shape frame in the link frame
  std::string material;       ///< a world material name, or one of the robot's own
  bool collides = true;
  bool visible = true;        ///< drawn by the renderer (a URDF's collision shapes are not)
  /// A track's belt runs over this shape: its surface moves around the shape's z axis (a
  /// cylinder's axis, an extrusion's direction) at belt_radius × the velocity of the joint
  /// `belt_joint` (the drive sprocket), so what it touches is pushed as by a conveyor (see
  /// docs/terrain.md, "The tracked robot"). Empty: a plain surface.
  std::string belt_joint{};
  double belt_radius = 0.0;   ///< m: the sprocket's pitch radius
};

/// A rigid link.
struct LinkSpec {
  std::string name;
  double mass = 1.0;          ///< kg
  Vec3 inertia{0.01, 0.01, 0.01};  ///< principal moments about the centre of mass (kg m^2)
  Vec3 com = Vec3::Zero();    ///< centre of mass in the link frame (m)
  std::vector<LinkShape> shapes;
  /// Friction scale along the link's own x, y, z axes (anisotropic friction): skid-steer
  /// wheels slide sideways more easily than they roll, which lets the robot turn in place.
  Vec3 friction_scale = Vec3::Ones();
  /// Principal axes of inertia in the link frame: `inertia` holds the moments about these axes
  /// (a URDF inertial's rotation and off-diagonal terms end up here).
  Quat inertia_axes = Quat::Identity();
};

/// A joint between a parent link and a child link.
struct JointSpec {
  enum class Type { revolute, continuous, prismatic, fixed };
  enum class Control { none, velocity, position };
  std::string name;
  Type type = Type::revolute;
  std::string parent, child;  ///< link names
  Pose3 X_PJ;                 ///< joint (= child link) frame in the parent link frame at q = 0
  Vec3 axis = Vec3::UnitZ();  ///< rotation (or, prismatic, translation) axis in the joint frame
  double lower = -M_PI, upper = M_PI;  ///< position limits (rad; prismatic: m), revolute and prismatic only
  double max_effort = 10.0;   ///< N m (prismatic: N)
  double max_velocity = 2.0;  ///< rad/s (prismatic: m/s)
  double damping = 0.0;       ///< viscous joint damping (N m s/rad; prismatic: N s/m)
  double friction = 0.0;      ///< Coulomb joint friction (N m; prismatic: N), on joints without a controller
  /// Mimic: when `mimic` names another joint, this one is driven to multiplier × q(mimic) + offset.
  std::string mimic;
  double mimic_multiplier = 1.0, mimic_offset = 0.0;
  Control control = Control::none;
  double kp = 8.0;            ///< position gain (1/s): joint speed = kp × position error, within max_velocity
  double initial = 0.0;       ///< starting position (rad)
  /// A position joint behind a self-locking gear (a worm drive, as on most pan-tilt heads): once
  /// it stands at its target (within kSelfLockTolerance, below kSelfLockSpeed) the gear holds it
  /// rigid and its motor carries no load, until the target moves away. In the physics a held
  /// joint is a fixed joint: no motor or limit rows, one degree of freedom fewer (docs/physics.md).
  bool self_locking = false;
};

/// How close to its target (rad; prismatic: m) a self-locking joint must stand to be held.
inline constexpr double kSelfLockTolerance = 0.01;
/// How slowly (rad/s; prismatic: m/s) it must move to be held.
inline constexpr double kSelfLockSpeed = 0.01;

/// How cmd_vel becomes wheel velocities.
struct DriveSpec {
  std::vector<std::string> left_wheels, right_wheels;  ///< joint names
  /// Per wheel (same order), +1 when a positive joint velocity drives the robot forward, -1 when
  /// the joint axis points the other way; empty means every wheel is +1.
  std::vector<double> left_signs, right_signs;
  double wheel_radius = 0.1;        ///< m
  double track_width = 0.5;         ///< m, between left and right wheel centres
  /// Skid-steer slip factor: the effective track is track_width × this (like
  /// diff_drive_controller's wheel_separation_multiplier); used by the controller and odometry.
  double track_multiplier = 1.0;
  double max_linear = 1.0;          ///< m/s
  double max_angular = 2.0;         ///< rad/s
  double max_linear_accel = 2.5;    ///< m/s^2
  double max_angular_accel = 6.0;   ///< rad/s^2
  double command_timeout = 0.5;     ///< s without cmd_vel before the robot stops
  /// Yaw-rate feedback from the chassis gyro (proportional, and integral in 1/s): skid-steer turning
  /// depends on how the wheels slide, so the controller trims the wheel speed difference until
  /// the chassis turns at the commanded rate. Zero gains give a purely open-loop drive.
  double yaw_rate_kp = 3.0, yaw_rate_ki = 20.0;
  /// At rest (no command in force and both set points at zero) the drive holds its wheels at the
  /// angles where they stopped, like a motor brake: each wheel turns at brake_gain × its angle
  /// error (1/s). A velocity motor alone lets a standing robot creep (0.7 mm/s) and its
  /// odometry turn. 0: no brake.
  double brake_gain = 20.0;
};

/// A lamp on a robot link: a spot light shining along its frame's x axis, with a soft-edged
/// cone and a range. Intensity is in the renderer's units: a surface d metres away facing the
/// lamp is lit like one facing the default sun when intensity / d^2 = 1.
struct RobotLightSpec {
  std::string name;
  std::string link = "base_link";   ///< the link it is fixed to
  Pose3 X_LF;                       ///< the lamp's frame in the link (x: where it shines)
  Vec3 color{1.0, 0.95, 0.85};      ///< linear colour (a warm white LED)
  double intensity = 8.0;
  double range = 12.0;              ///< m: the light fades smoothly to nothing here
  double cone = 0.45;               ///< rad: half-angle of the cone's edge
  double inner_cone = 0.3;          ///< rad: half-angle of the fully lit core
};

/// A whole robot model.
struct RobotSpec {
  std::string model;                 ///< e.g. "rescue_robot"
  std::vector<LinkSpec> links;       ///< links[0] is the base (chassis)
  std::vector<JointSpec> joints;     ///< in tree order: a joint's parent appears before its child
  DriveSpec drive;
  std::vector<std::string> head_joints;  ///< joints driven by /head/command, in message order
  /// Position joints driven by /flippers/command (std_msgs/Float64MultiArray, rad), in message
  /// order: a tracked robot's flippers. They are also joint_command joints.
  std::vector<std::string> flipper_joints;
  /// Lamps on the robot's links, switched together over /lights (std_msgs/Bool).
  std::vector<RobotLightSpec> lights;
  bool lights_on = false;  ///< whether the lamps are on at the start
  std::vector<SensorSpec> sensors;
  /// The robot's own materials (a URDF's <material>s and mesh colours), added to the world's
  /// when it is compiled; names are prefixed with the model name to keep them apart.
  std::vector<MaterialSpec> materials;
  /// The description as loaded (a URDF's text, placeholders filled), for /robot_description;
  /// empty for built-in models.
  std::string description;
  std::string source_file;           ///< where the description came from ("" for built-in models)

  /// Index of a link or joint by name, or -1.
  int link_index(const std::string& name) const;
  int joint_index(const std::string& name) const;
  /// The sensor with this name, or nullptr.
  const SensorSpec* find_sensor(const std::string& name) const;
  SensorSpec* find_sensor(const std::string& name);
  /// Total mass (kg).
  double total_mass() const;
};

/// The motion of a joint at position q: a rotation about its axis (revolute, continuous), a
/// translation along it (prismatic), or nothing (fixed).
Pose3 joint_motion(const JointSpec& j, double q);

/// Poses of every link in the base link's frame for joint positions `q` (one per joint, in
/// joint order; fixed joints ignore theirs): X_BL = X_BP * X_PJ * rotation(axis, q).
std::vector<Pose3> link_poses(const RobotSpec& robot, const std::vector<double>& q);

/// The inertia tensor of a link about its centre of mass, in the link frame (kg m^2).
Eigen::Matrix3d inertia_tensor(const LinkSpec& link);
/// Sets a link's principal moments and axes from an inertia tensor in the link frame.
void set_inertia_tensor(LinkSpec& link, const Eigen::Matrix3d& I_L);

/// The sign of wheel `i` of a drive side (see DriveSpec::left_signs).
double wheel_sign(const std::vector<double>& signs, std::size_t i);

/// Joint positions at the start (each joint's `initial`).
std::vector<double> initial_positions(const RobotSpec& robot);

}  // namespace rescuesim
