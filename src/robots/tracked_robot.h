#pragma once
/// The built-in tracked robot, as data.

#include "world/robot_spec.h"

namespace rescuesim {

/// A tracked response robot of the PackBot class: a chassis on two rubber tracks 0.68 m long
/// (0.34 m apart, 0.18 m high, over 0.09 m sprockets), two front flippers 0.35 m long that turn
/// about the front sprocket axis (/flippers/command), the rescue robot's 4-DOF sensor head and
/// sensors; about 28 kg, 0.54 m wide over the flippers. The tracks are belts: their surfaces
/// move at the sprockets' speed (LinkShape::belt_joint), not dozens of small wheels.
RobotSpec tracked_robot();

}  // namespace rescuesim
