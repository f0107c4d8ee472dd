#include "sensors/contact.h"

namespace rescuesim {

msg::Contacts sample_contacts(const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp) {
  msg::Contacts c;
  c.header = {stamp, spec.frame_id};
  c.touching = state.robot(robot).touching;
  return c;
}

}  // namespace rescuesim
