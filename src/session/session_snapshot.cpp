// Session::snapshot and restore: the simulation's State, plus what a run keeps beside it.

#include <any>
#include <optional>

#include "sensors/camera/render_camera_service.h"
#include "session/session.h"

namespace rescuesim {

/// The part of a run outside State.
struct SessionExtras {
  RenderCameraService::InFlight cameras;  // frames sampled, not yet delivered
  std::string stop_reason;
  std::vector<std::any> systems;  // each run system's memory, in Session::systems_ order
};

SessionSnapshot Session::snapshot() {
  auto extras = std::make_shared<SessionExtras>();
  if (cameras_) extras->cameras = cameras_->in_flight();
  extras->stop_reason = stop_reason_;
  for (const RunSystem* system : systems_) extras->systems.push_back(system->save());
  return SessionSnapshot{sim_->snapshot(), std::move(extras)};
}

void Session::restore(const SessionSnapshot& snapshot) {
  const SessionExtras& x = *snapshot.extras;
  // a snapshot from before anything was spawned: what was spawned goes first, so that the
  // renderer is made again for the snapshot's world before its frames in flight come back
  if (snapshot.state.robots.size() == sim_->base_robots() && snapshot.state.dynamics.size() == sim_->base_bodies()) {
    sim_->remove_spawned();
  }
  // frames in flight first: none of them may be delivered into the restored state
  if (cameras_) cameras_->restore(x.cameras);
  sim_->restore(snapshot.state);
  // commands queued now (bridges' too) are dropped: outside input is not part of a snapshot; the
  // systems queue theirs again as they load their memory (the built-in controllers' for the next step)
  sim_->discard_commands();
  stop_reason_ = x.stop_reason;
  // a system added after the snapshot keeps its memory
  for (std::size_t k = 0; k < systems_.size() && k < x.systems.size(); ++k) systems_[k]->load(x.systems[k], *sim_);
}

}  // namespace rescuesim
