#pragma once
/// CameraService: the interface through which the simulation has its camera sensors rendered.
/// The interface lives in rs_sensors (no OpenGL); the implementation that renders,
/// RenderCameraService in sensors/camera/render_camera_service.h, is in rs_sensors_camera, the
/// only target that links the renderer — so the simulation and everything that runs without
/// cameras never link EGL/epoxy/GLFW.

#include <functional>

#include "core/sim_time.h"
#include "msgs/messages.h"
#include "sensors/sensor_instance.h"
#include "bus/topic_id.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// Renders camera sensors. The simulation hands it each camera sample as it falls due and,
/// after every step, asks it to deliver finished frames; an implementation may render on
/// another thread meanwhile (RenderCameraService does), as long as what it delivers at a given
/// step never depends on thread timing.
class CameraService {
 public:
  virtual ~CameraService() = default;
  /// A camera is due at `state.time`: take what it needs from `state` and start its frame;
  /// draw any randomness from `slot.rng` now, on the simulation thread.
  virtual void sample(const World& world, const State& state, const SensorInstance& sensor, SensorSlot& slot) = 0;
  /// Publishes, in sample order, every frame due for delivery at or before `now` (waiting for
  /// it if it is not finished), and may record victims it saw in `state.victims` (thermal
  /// frames; see ThermalImageDetector in sensors/victim_detector.h).
  virtual void deliver(const World& world, State& state, SimTime now, const std::function<void(TopicId, msg::Message)>& publish) = 0;
};

}  // namespace rescuesim
