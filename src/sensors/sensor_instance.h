#pragma once
/// SensorInstance: one sensor of one robot as the simulation schedules it — where its state
/// lives, the topics it publishes on, its period and its spec framed for the samplers. Here
/// rather than in sim/ so that sensor code (the camera service among it) can take one without
/// including the simulation.

#include <string>

#include "core/sim_time.h"
#include "bus/topic_id.h"
#include "world/world.h"

namespace rescuesim {

/// A sensor of a robot, as the simulation schedules it.
struct SensorInstance {
  RobotIndex robot{0};
  int index = 0;                       ///< into the robot's spec.sensors
  int slot = 0;                        ///< into State::sensors
  TopicId topic = kNoTopic;            ///< Bus topic of the main output
  TopicId info_topic = kNoTopic;       ///< cameras: camera_info
  TopicId extra_topic = kNoTopic;      ///< the kind's extra output (SensorSpec::extra_topic): depth points, thermal image_mono8
  std::string frame_id;                ///< header frame of its messages, namespaced; cameras: the optical frame
  SimTime period;
  /// the robot's spec of this sensor with frame_id set to the one above, made once at set-up for
  /// the samplers
  SensorSpec spec;
};

}  // namespace rescuesim
