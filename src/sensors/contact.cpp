#include "sensors/contact.h"

namespace rescuesim {

msg::Contacts sample_contacts(const State& state, int robot, const SensorSpec& spec, SimTime stamp) {
  msg::Contacts c;
  c.header = {stamp, spec.frame_id};
  c.touching = state.robots[static_cast<std::size_t>(robot)].touching;
  return c;
}

}  // namespace rescuesim
