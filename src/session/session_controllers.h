#pragma once
// Internal to src/session: the built-in controllers of a run.

#include <memory>
#include <optional>
#include <vector>

#include "autonomy/explorer.h"
#include "mission/datagram_json.h"
#include "session/session.h"

namespace rescuesim {

/// A victim report a built-in controller has still to make (see Session::Controllers::pending).
struct PendingReport {
  int victim = -1;
  Vec3 p_W = Vec3::Zero();  ///< where the robot believes the victim is
  std::optional<msg::Image> picture;  ///< its thermal camera's frame when it saw the victim (cameras rendering)
};

/// What a teammate last said over the radio (Session::mission_step's team rule), world frame.
struct TeamClaim {
  Vec2 at = Vec2::Zero();        ///< where it was
  std::optional<Vec2> going;     ///< the frontier it was driving to, if any
  SimTime stamp;                 ///< when it was sent
  std::vector<Vec2> victims;     ///< where it believes the victims it found lie
};

/// The built-in controllers, one per robot that asked for one, fed from the Bus.
struct Session::Controllers {
  std::vector<std::unique_ptr<autonomy::Explorer>> explorers;  // per robot, null when none
  /// Per robot: the odometry, joint states and scans its explorer subscribed to, as published
  /// during the step being taken; Session::run_controllers hands them over once it is done.
  std::vector<std::vector<msg::Message>> inbox;
  std::vector<Pose2> X_WO;                                     // per robot: odom frame in the world (its start pose)
  /// Per robot: the cmd_vel its controller queued during the step that ran last, which the next
  /// step applies; a snapshot carries it, since the Simulation's command queue is not State.
  std::vector<std::optional<msg::Twist>> queued;
  /// Per robot: how its explorer's camera swing is commanded (ExplorerLookConfig::yaw_joint),
  /// and the yaw it queued during the last step (carried by snapshots like `queued`).
  struct Pan {
    msg::JointState joint;      ///< the yaw joint alone, when it is not a head joint
    std::vector<double> head;   ///< every head joint's target, when it is one (the others at their start)
    int in_head = -1;           ///< its index among the head joints, or -1
  };
  std::vector<Pan> pans;
  std::vector<std::optional<double>> queued_look;

  /// With a mission: what the built-in controllers report. A robot that has seen a victim
  /// reports it where it believes it is (its odometry pose, placed at its start, plus the
  /// victim's offset from it), at the referee's report rate, whenever it is in radio contact.
  /// Out of contact with reports to make, it drives back towards the base after a grace
  /// period, and explores on once they are made; it drops a relay where its link to the base
  /// grows weak (Session::mission_step has the rule).
  std::vector<std::vector<PendingReport>> pending;  // per robot, oldest first
  std::vector<std::vector<bool>> known;             // per robot, per victim: queued or reported already, or a teammate's
  std::vector<std::vector<Vec2>> found_W;           // per robot: where it believes the victims it reports lie (told to teammates)
  std::vector<SimTime> next_report;                 // per robot: not before this
  std::vector<SimTime> lost_contact;                // per robot: when it last lost contact (-1: in contact)
  std::vector<std::uint8_t> returning;              // per robot: driving back towards the base to report
  std::uint64_t relay_check = 0;                    // link update the relay rule last looked at (it changes only with the links)
  /// The team rule: every kShareEvery each built-in robot tells each built-in teammate, by
  /// datagram through the mission's radio, where it is and which frontier it is driving to;
  /// what a robot has heard (and only that: a teammate out of radio contact goes unheard) and
  /// is younger than kClaimAge becomes its explorer's claims, so frontier trips spread out.
  std::vector<std::vector<std::optional<TeamClaim>>> heard;  // per robot, per teammate
  std::vector<SimTime> next_share;                           // per robot
  /// Every kSeenEvery each built-in robot also tells them where its own camera has looked
  /// (squares of the world); a teammate's explorer then leaves that ground to it
  /// (Explorer::add_team_seen). A robot out of contact catches up with the next one it hears.
  std::vector<SimTime> next_seen;                            // per robot
  /// And every kMapEvery what its laser has mapped (squares of the world, free or occupied); a
  /// teammate's explorer then takes no trip to a frontier already mapped beyond
  /// (Explorer::add_team_map).
  std::vector<SimTime> next_map;                             // per robot
  /// The base station's side (Session::base_map_step): each built-in robot sends its map to the
  /// base too; the base keeps the newest that got through from each and, every kBaseMapEvery
  /// when something new came, submits the team's map to the referee's map scoring (a square
  /// is what the robots' newest maps say, occupied over free over unknown).
  std::vector<std::optional<MapSquares>> base_maps;          // per robot
  bool base_map_new = false;                                 // a map came since the last submission
  SimTime next_base_map;
};

}  // namespace rescuesim
