#pragma once
// Test support: a small hand-built robot with one joint of every kind /joint_command must tell
// apart, and a URDF-like description text, in a 6 m room. Its root link is base_footprint (as
// many URDF robots have it), not base_link. Used by tests/sim and the bridge tests.
//
//   base_footprint (box 0.4 x 0.3 x 0.1 on the floor)
//     lift    prismatic along x, position-controlled, [-0.1, 0.2] m  -> lift_link
//       spin  revolute about z, velocity-controlled                  -> spin_link
//     wheel   continuous, velocity, the drive's only (left) wheel    -> wheel_link
//     pan     revolute, position, the head joint                     -> pan_link
//     flap    revolute, no controller (passive)                      -> flap_link
//     follow  revolute, mimics spin                                  -> follow_link
//     mount   fixed                                                  -> sensor_link

#include <map>
#include <string>

#include "world/robot_spec.h"
#include "world/world.h"

namespace rescuesim::testing {

/// The description the slider robot carries (what a URDF importer would keep as the text).
inline const char* kSliderDescription = R"(<?xml version="1.0"?>
<robot name="slider">
  <link name="base_footprint"/>
  <link name="lift_link"/>
  <joint name="lift" type="prismatic">
    <parent link="base_footprint"/><child link="lift_link"/>
    <origin xyz="0 0 0.2"/><axis xyz="1 0 0"/>
    <limit lower="-0.1" upper="0.2" effort="50" velocity="0.5"/>
  </joint>
</robot>
)";

inline RobotSpec slider_robot() {
  RobotSpec r;
  r.model = "slider";
  r.description = kSliderDescription;
  const auto link = [](const std::string& name, double mass, const Vec3& size, const Vec3& at) {
    LinkSpec l;
    l.name = name;
    l.mass = mass;
    l.inertia = mass / 12.0 * Vec3(size.y() * size.y() + size.z() * size.z(), size.x() * size.x() + size.z() * size.z(),
                                   size.x() * size.x() + size.y() * size.y());
    l.shapes.push_back({Geometry::box(size), Pose3{at, Quat::Identity()}, "robot_body", true});
    return l;
  };
  // the base rests on the floor; every other link sits well above it, small and light
  r.links.push_back(link("base_footprint", 5.0, Vec3(0.4, 0.3, 0.1), Vec3(0, 0, 0.05)));
  for (const char* name : {"lift_link", "spin_link", "wheel_link", "pan_link", "flap_link", "follow_link", "sensor_link"}) {
    r.links.push_back(link(name, 0.2, Vec3(0.04, 0.04, 0.04), Vec3::Zero()));
  }
  const auto joint = [](const std::string& name, JointSpec::Type type, const std::string& parent, const std::string& child,
                        const Vec3& at, const Vec3& axis, JointSpec::Control control) {
    JointSpec j;
    j.name = name;
    j.type = type;
    j.parent = parent;
    j.child = child;
    j.X_PJ = Pose3{at, Quat::Identity()};
    j.axis = axis;
    j.control = control;
    j.max_effort = 50;
    return j;
  };
  using T = JointSpec::Type;
  using C = JointSpec::Control;
  JointSpec lift = joint("lift", T::prismatic, "base_footprint", "lift_link", Vec3(0, 0, 0.2), Vec3::UnitX(), C::position);
  lift.lower = -0.1;
  lift.upper = 0.2;
  lift.max_velocity = 0.5;
  r.joints.push_back(lift);
  r.joints.push_back(joint("spin", T::revolute, "lift_link", "spin_link", Vec3(0, 0, 0.06), Vec3::UnitZ(), C::velocity));
  r.joints.push_back(joint("wheel", T::continuous, "base_footprint", "wheel_link", Vec3(-0.1, 0, 0.2), Vec3::UnitY(), C::velocity));
  r.joints.push_back(joint("pan", T::revolute, "base_footprint", "pan_link", Vec3(0.1, 0.1, 0.2), Vec3::UnitZ(), C::position));
  r.joints.push_back(joint("flap", T::revolute, "base_footprint", "flap_link", Vec3(-0.1, 0.1, 0.2), Vec3::UnitZ(), C::none));
  JointSpec follow = joint("follow", T::revolute, "base_footprint", "follow_link", Vec3(0.1, -0.1, 0.2), Vec3::UnitZ(), C::none);
  follow.mimic = "spin";
  r.joints.push_back(follow);
  r.joints.push_back(joint("mount", T::fixed, "base_footprint", "sensor_link", Vec3(-0.1, -0.1, 0.2), Vec3::UnitZ(), C::none));
  r.drive.left_wheels = {"wheel"};
  r.drive.yaw_rate_kp = r.drive.yaw_rate_ki = 0;  // a single wheel in the air: no feedback to speak of
  r.head_joints = {"pan"};
  SensorSpec odom;
  odom.name = "odometry";
  odom.type = SensorSpec::Type::odometry;
  odom.link = "base_footprint";
  odom.rate = 50;
  odom.topic = "odom";
  odom.frame_id = "odom";
  r.sensors.push_back(odom);
  SensorSpec joints;
  joints.name = "joint_states";
  joints.type = SensorSpec::Type::joint_states;
  joints.link = "base_footprint";
  joints.rate = 20;
  joints.topic = "joint_states";
  r.sensors.push_back(joints);
  return r;
}

/// A 6 m square room with walls, the slider robot (named `name`) at its centre.
inline WorldSpec slider_room(const std::string& name = "slider") {
  WorldSpec w;
  w.floor_min = {-3, -3};
  w.floor_max = {3, 3};
  w.materials = default_materials();
  w.walls = {{{-3, -3}, {3, -3}, 0.1, 1, "wall", {}},
             {{3, -3}, {3, 3}, 0.1, 1, "wall", {}},
             {{3, 3}, {-3, 3}, 0.1, 1, "wall", {}},
             {{-3, 3}, {-3, -3}, 0.1, 1, "wall", {}}};
  RobotPlacement p;
  p.name = name;
  p.model = "slider";
  w.robots.push_back(p);
  return w;
}

/// The slider room compiled.
inline World slider_world(const std::string& name = "slider") {
  return compile_world(slider_room(name), std::map<std::string, RobotSpec>{{"slider", slider_robot()}});
}

}  // namespace rescuesim::testing
