#pragma once
/// The built-in team (docs/missions.md, "The built-in team"), a RunSystem (sim/run_system.h) that
/// runs after the mission's own step, for the robots the built-in controllers drive:
///   reports    a robot that has seen a victim reports it where it believes it is (its odometry
///              pose, placed at its start, plus the victim's offset), at the referee's report
///              rate, whenever it is in radio contact; a victim a teammate said it found is left
///              to the teammate;
///   returning  out of contact with reports to make, it drives back towards the base after a
///              grace period, and explores on once they are made;
///   relays     it drops a relay where its route to the base grows weak;
///   talk       every few seconds it tells each teammate, by datagram through the mission's radio
///              (team/team_datagrams.h), where it is, which frontier it drives to and the victims
///              it found, where its camera looked and what its laser mapped; what a robot heard
///              (and only that) becomes its explorer's claims and team knowledge, so trips spread;
///   base map   the base keeps the newest map that got through from each robot and submits the
///              team's map to the referee's map scoring.
/// Its memory is one TeamMember per robot plus the base's few fields; `visit_fields` below is
/// their one field list, and save()/load() copy through it (world/field_copy.h), so a field is
/// added in one place and one left out of the list fails the restore tests.

#include <any>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/pose.h"
#include "core/sim_time.h"
#include "msgs/messages.h"
#include "sim/run_system.h"
#include "team/team_datagrams.h"
#include "world/state.h"

namespace rescuesim {

class Mission;
class BuiltinControllers;

/// A victim report a built-in robot has still to make.
struct PendingReport {
  VictimIndex victim;
  Vec3 p_W = Vec3::Zero();            ///< where the robot believes the victim is
  std::optional<msg::Image> picture;  ///< its thermal camera's frame when it saw the victim (cameras rendering)
};

/// What a teammate last said over the radio, world frame.
struct TeamClaim {
  Vec2 at = Vec2::Zero();     ///< where it was
  std::optional<Vec2> going;  ///< the frontier it was driving to, if any
  SimTime stamp;              ///< when it was sent
  std::vector<Vec2> victims;  ///< where it believes the victims it found lie
};

/// One robot's team memory.
struct TeamMember {
  std::vector<PendingReport> pending;           ///< oldest first
  std::vector<bool> known;                      ///< per victim: queued or reported already, or a teammate's
  std::vector<Vec2> found_W;                    ///< where it believes the victims it reports lie (told to teammates)
  SimTime next_report;                          ///< no report before this
  SimTime lost_contact{-1};                     ///< when it last lost contact (-1: in contact)
  bool returning = false;                       ///< driving back towards the base to report
  std::vector<std::optional<TeamClaim>> heard;  ///< per teammate: what it last said
  SimTime next_share, next_seen, next_map;      ///< when it next tells where it is, looked, mapped
  std::optional<MapSquares> base_map;           ///< its newest map that got through to the base
};

/// The team's whole memory.
struct TeamMemory {
  std::vector<TeamMember> members;  ///< per robot (the scenario's)
  std::uint64_t relay_check = 0;    ///< link update the relay rule last looked at (it changes only with the links)
  bool base_map_new = false;        ///< a map reached the base since its last submission
  SimTime next_base_map;            ///< the base's next submission, at the earliest
};

/// The one field list of a robot's team memory (the visitor protocol of world/state.h).
template <StatePart<TeamMember> M, class V>
void visit_fields(M& m, V& v) {
  v("pending", m.pending);
  v("known", m.known);
  v("found_W", m.found_W);
  v("next_report", m.next_report);
  v("lost_contact", m.lost_contact);
  v("returning", m.returning);
  v("heard", m.heard);
  v("next_share", m.next_share);
  v("next_seen", m.next_seen);
  v("next_map", m.next_map);
  v("base_map", m.base_map);
}

template <StatePart<TeamMemory> M, class V>
void visit_fields(M& m, V& v) {
  v.items("members", m.members, [](auto& w, auto& member) { visit_fields(member, w); });
  v("relay_check", m.relay_check);
  v("base_map_new", m.base_map_new);
  v("next_base_map", m.next_base_map);
}

class BuiltinTeam final : public RunSystem {
 public:
  /// Robot `robot`'s last thermal frame as a report's picture, or nothing (no camera renders).
  using Picture = std::function<std::optional<msg::Image>(RobotIndex robot)>;

  /// The team of the robots `controllers` drive, `robots` robots and `victims` victims in all.
  BuiltinTeam(Mission& mission, BuiltinControllers& controllers, std::size_t robots, std::size_t victims, Picture picture);

  std::string_view system_name() const override { return "team"; }
  /// After the mission's step: reports, returns and relays, then the team's talk, then the base.
  void post_step(Simulation& sim) override;
  std::any save() const override;
  void load(const std::any& memory, Simulation& sim) override;

  const TeamMemory& memory() const { return memory_; }

 private:
  /// Victims seen become reports; reports are made in contact; out of contact a robot returns;
  /// a weak route gets a relay.
  void report_and_relay(const Simulation& sim);
  /// What each robot heard since the last step becomes its knowledge of its teammates.
  void hear();
  /// Each robot tells its teammates (and the base) what is due; what it heard becomes its claims.
  void talk(const Simulation& sim);
  /// The base's side: the maps that got through, and the team's map to the referee.
  void base_map_step(SimTime now);

  Mission& mission_;
  BuiltinControllers& controllers_;
  Picture picture_;
  TeamMemory memory_;
};

}  // namespace rescuesim
