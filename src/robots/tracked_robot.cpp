#include "robots/tracked_robot.h"

#include <cmath>

#include "core/polygon.h"
#include "robots/robot_parts.h"

namespace rescuesim {

namespace {

using namespace robot_parts;
constexpr double deg = kDeg;

/// Lateral friction of a track relative to its longitudinal friction: a track's grousers bite
/// along its length and it slides sideways more easily, which lets it turn in place. A stated
/// choice, not a measurement: with 1.0 it still turns, but only with the yaw-rate loop's help.
constexpr double kTrackSideFriction = 0.5;

/// A belt's outline in the x-z plane: the convex hull of a circle of radius r0 at the origin and
/// one of radius r1 at (length, 0), as a solid `width` wide along y, its z axis (the belt's axis,
/// LinkShape::belt_joint) along the link's y axis.
LinkShape belt_shape(double r0, double r1, double length, double width, const Pose3& X_LC, const std::string& sprocket,
                     double sprocket_radius) {
  std::vector<Vec2> points;
  constexpr int kSegments = 16;  // per circle: a 16-gon's flats stand 2 % inside the round
  for (int i = 0; i < kSegments; ++i) {
    const double a = 2 * M_PI * i / kSegments;
    points.emplace_back(r0 * std::cos(a), r0 * std::sin(a));
    points.emplace_back(length + r1 * std::cos(a), r1 * std::sin(a));
  }
  // the extrusion runs along the shape's z axis, turned onto the link's y axis
  const TriangleMesh prism = extrude(convex_hull(points), -width / 2, width / 2);
  LinkShape sh = shape(Geometry::convex(prism), X_LC * at_rpy(0, 0, 0, -M_PI / 2, 0, 0), "robot_wheel");
  sh.belt_joint = sprocket;
  sh.belt_radius = sprocket_radius;
  return sh;
}

}  // namespace

RobotSpec tracked_robot() {
  RobotSpec r;
  r.model = "tracked_robot";

  // the belts run over sprockets of radius 0.09 m, 0.50 m apart (tracks 0.68 m long, as on a
  // PackBot); base_link sits on the sprocket axis, 0.09 m above the ground at rest
  const double sprocket_r = 0.09, half_pitch = 0.25, track_y = 0.17, track_w = 0.10, flipper_y = 0.245;

  const Vec3 body(0.60, 0.24, 0.14);
  // the batteries sit low in the front of the chassis: a centre of mass ahead of the middle and
  // low keeps the robot from rearing over backwards as its front climbs a step (the sensor
  // head's mast stands at the back)
  LinkSpec base{"base_link", 18.0, box_inertia(18.0, body), Vec3(0.08, 0, -0.03), {}, Vec3(1.0, kTrackSideFriction, 1.0)};
  base.shapes.push_back(shape(Geometry::box(body), at(0, 0, 0.02), "robot_body"));
  base.shapes.push_back(shape(Geometry::box({0.06, 0.10, 0.06}), at(0.24, 0, 0.12), "robot_sensor"));  // laser housing
  r.links.push_back(base);

  for (const char* side : {"left", "right"}) {
    const double sy = std::string(side) == "left" ? 1.0 : -1.0;
    const std::string sprocket_joint = std::string(side) + "_sprocket_joint";
    // the drive sprocket: a velocity-controlled joint whose speed the belts run at (it has no
    // shape of its own: its belt is the track's surface)
    LinkSpec sprocket{std::string(side) + "_sprocket", 0.3, Vec3(0.001, 0.0015, 0.001), Vec3::Zero(), {}};
    r.links.push_back(sprocket);
    JointSpec sj;
    sj.name = sprocket_joint;
    sj.type = JointSpec::Type::continuous;
    sj.parent = "base_link";
    sj.child = sprocket.name;
    sj.X_PJ = at(half_pitch, sy * track_y, 0);
    sj.axis = Vec3::UnitY();
    sj.max_effort = 20.0;
    sj.max_velocity = 15.0;
    sj.control = JointSpec::Control::velocity;
    r.joints.push_back(sj);
    (sy > 0 ? r.drive.left_wheels : r.drive.right_wheels).push_back(sj.name);

    // the track: a belt over both sprockets, fixed to the chassis
    LinkSpec track{std::string(side) + "_track", 2.0, box_inertia(2.0, {0.68, track_w, 0.18}), Vec3::Zero(), {},
                   Vec3(1.0, kTrackSideFriction, 1.0)};
    track.shapes.push_back(belt_shape(sprocket_r, sprocket_r, 2 * half_pitch, track_w, at(-half_pitch, 0, 0), sprocket_joint, sprocket_r));
    r.links.push_back(track);
    JointSpec tj;
    tj.name = track.name + "_joint";
    tj.type = JointSpec::Type::fixed;
    tj.parent = "base_link";
    tj.child = track.name;
    tj.X_PJ = at(0, sy * track_y, 0);
    r.joints.push_back(tj);

    // the flipper: a tapering arm on the front sprocket's axis with a belt of its own, driven
    // with the track; q = 0 points it forward, positive lowers its tip
    LinkSpec flipper{std::string(side) + "_flipper", 1.5, box_inertia(1.5, {0.40, 0.05, 0.12}), Vec3(0.14, 0, 0), {},
                     Vec3(1.0, kTrackSideFriction, 1.0)};
    flipper.shapes.push_back(belt_shape(sprocket_r, 0.05, 0.35, 0.05, {}, sprocket_joint, sprocket_r));
    r.links.push_back(flipper);
    JointSpec fj;
    fj.name = flipper.name + "_joint";
    fj.type = JointSpec::Type::revolute;
    fj.parent = "base_link";
    fj.child = flipper.name;
    fj.X_PJ = at(half_pitch, sy * flipper_y, 0);
    fj.axis = Vec3::UnitY();
    fj.lower = -170 * deg;
    fj.upper = 170 * deg;
    fj.max_effort = 80.0;
    fj.max_velocity = 1.5;
    fj.control = JointSpec::Control::position;
    fj.kp = 8.0;
    fj.initial = -170 * deg;  // stowed: folded back over the track, tips up, within its length
    r.joints.push_back(fj);
    r.flipper_joints.push_back(fj.name);
  }
  r.drive.wheel_radius = sprocket_r;
  r.drive.track_width = 2 * track_y;  // 0.34 m
  r.drive.track_multiplier = 1.5;
  r.drive.max_linear = 1.0;
  r.drive.max_angular = 1.5;

  add_sensor_head(r, "base_link", at(-0.18, 0, 0.09));
  add_sensors(r, at(0.24, 0, 0.14),
              {{"front_left", 0.28, 0.10, 25 * deg},
               {"front_right", 0.28, -0.10, -25 * deg},
               {"rear_left", -0.28, 0.10, 155 * deg},
               {"rear_right", -0.28, -0.10, -155 * deg}},
              0.02);
  return r;
}

}  // namespace rescuesim
