// Session::snapshot and restore: the simulation's State, plus what a run keeps beside it.

#include <optional>

#include "sensors/camera/render_camera_service.h"
#include "session/session.h"
#include "session/session_controllers.h"

namespace rescuesim {

/// The part of a run outside State.
struct SessionExtras {
  RenderCameraService::InFlight cameras;                    // frames sampled, not yet delivered
  std::vector<std::optional<autonomy::Explorer>> explorers;  // per robot: its controller's memory
  std::vector<std::optional<msg::Twist>> queued;             // per robot: its controller's command for the next step
  std::vector<std::optional<double>> queued_look;            // per robot: its camera swing for the next step
  std::vector<TrajectoryPoint> trajectory;
  SimTime next_record, record_interval;
  std::vector<msg::LaserScan> last_scans;
  std::vector<std::uint8_t> visited_cells;
  std::string stop_reason;
  std::optional<Mission::Memory> mission;                    // referee and radio network
  std::vector<std::vector<PendingReport>> pending;            // the built-in controllers' reports
  std::vector<std::vector<bool>> known;
  std::vector<std::vector<Vec2>> found_W;
  std::vector<SimTime> next_report;
  std::vector<SimTime> lost_contact;
  std::vector<std::uint8_t> returning;
  std::vector<std::vector<std::optional<TeamClaim>>> heard;
  std::vector<SimTime> next_share;
  std::vector<SimTime> next_seen;
  std::vector<SimTime> next_map;
  std::vector<std::optional<MapSquares>> base_maps;
  bool base_map_new = false;
  SimTime next_base_map;
};

SessionSnapshot Session::snapshot() {
  auto extras = std::make_shared<SessionExtras>();
  if (cameras_) extras->cameras = cameras_->in_flight();
  for (const auto& ex : controllers_->explorers) {
    extras->explorers.push_back(ex ? std::optional<autonomy::Explorer>(*ex) : std::nullopt);
  }
  extras->queued = controllers_->queued;
  extras->queued_look = controllers_->queued_look;
  extras->trajectory = trajectory_;
  extras->next_record = next_record_;
  extras->record_interval = record_interval_;
  extras->last_scans = last_scans_;
  extras->visited_cells = visited_cells_;
  extras->stop_reason = stop_reason_;
  if (mission_) extras->mission = mission_->save();
  extras->pending = controllers_->pending;
  extras->known = controllers_->known;
  extras->found_W = controllers_->found_W;
  extras->next_report = controllers_->next_report;
  extras->lost_contact = controllers_->lost_contact;
  extras->returning = controllers_->returning;
  extras->heard = controllers_->heard;
  extras->next_share = controllers_->next_share;
  extras->next_seen = controllers_->next_seen;
  extras->next_map = controllers_->next_map;
  extras->base_maps = controllers_->base_maps;
  extras->base_map_new = controllers_->base_map_new;
  extras->next_base_map = controllers_->next_base_map;
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
  // the commands the controllers had queued at the snapshot replace whatever is queued now
  // (commands from bridges queued now are dropped too: outside input is not part of a snapshot)
  sim_->discard_commands();
  controllers_->queued = x.queued;
  for (std::size_t r = 0; r < controllers_->queued.size(); ++r) {
    if (controllers_->queued[r]) sim_->command_velocity(static_cast<int>(r), *controllers_->queued[r]);
  }
  for (std::size_t r = 0; r < x.queued_look.size() && r < controllers_->pans.size(); ++r) {
    if (x.queued_look[r]) command_look(static_cast<int>(r), *x.queued_look[r]);
  }
  // controllers are fed through the Bus by pointer: their objects stay, their memory goes back
  for (std::size_t r = 0; r < controllers_->explorers.size() && r < x.explorers.size(); ++r) {
    if (controllers_->explorers[r] && x.explorers[r]) *controllers_->explorers[r] = *x.explorers[r];
  }
  trajectory_ = x.trajectory;
  next_record_ = x.next_record;
  record_interval_ = x.record_interval;
  last_scans_ = x.last_scans;
  visited_cells_ = x.visited_cells;
  stop_reason_ = x.stop_reason;
  if (mission_ && x.mission) mission_->load(*x.mission);
  controllers_->pending = x.pending;
  controllers_->known = x.known;
  controllers_->found_W = x.found_W;
  controllers_->next_report = x.next_report;
  controllers_->lost_contact = x.lost_contact;
  controllers_->returning = x.returning;
  controllers_->heard = x.heard;
  controllers_->next_share = x.next_share;
  controllers_->next_seen = x.next_seen;
  controllers_->next_map = x.next_map;
  controllers_->base_maps = x.base_maps;
  controllers_->base_map_new = x.base_map_new;
  controllers_->next_base_map = x.next_base_map;
}

}  // namespace rescuesim
