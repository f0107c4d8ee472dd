#pragma once
/// Ultrasonic range finders: a cone of rays from the sensor's x axis, with the specular loss of
/// real sonar (no echo from surfaces met at grazing incidence). Ranges follow REP-117.

#include <vector>

#include "core/rng.h"
#include "core/sim_time.h"
#include "msgs/messages.h"
#include "raycast/ray_scene.h"
#include "world/sensor_spec.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// The cone's ray directions in the sensor frame (unit vectors): yaw and pitch on a
/// rays × rays grid over [−fov/2, fov/2], keeping those within fov/2 of the x axis, plus the
/// axis itself when the grid does not contain it.
void sonar_directions(const SonarSpec& sonar, std::vector<Vec3>& out);

/// One sonar reading: the nearest return among the cone's rays whose incidence (angle between
/// the ray and the surface normal; 0 = head-on) is at most max_incidence. None → +inf; below
/// min_range → -inf; otherwise with noise, clamped into [min_range, max_range] (see
/// range_reading in lidar.h). radiation_type ULTRASOUND, field_of_view = fov (rad). The robot
/// never hears its own links.
msg::Range sample_sonar(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                        SimTime stamp, Rng& rng);

}  // namespace rescuesim
