#include "team/builtin_team.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "mission/mission.h"
#include "sim/simulation.h"
#include "team/builtin_controllers.h"
#include "world/field_copy.h"

namespace rescuesim {

namespace {
// The built-in team's rules (docs/missions.md, "The built-in team")
constexpr double kReturnAfter = 10.0;   // s out of contact with reports to make before heading back
constexpr double kRelayMargin = 3.0;    // dB: drop a relay when the route's weakest link is this close to the threshold
constexpr double kRelaySpacing = 3.0;   // m: ... and no base or relay is nearer than this
constexpr double kShareEvery = 2.0;     // s between a built-in robot's team datagrams
constexpr double kClaimAge = 10.0;      // s a teammate's word counts for
constexpr double kSeenEvery = 6.0;      // s between a built-in robot's "where my camera looked" datagrams
constexpr double kSeenCell = 0.5;       // m, the squares that datagram is counted in (world frame)
constexpr int kSeenMinCells = 25;       // a square counts as seen when the camera looked at this many of its map cells
constexpr double kMapEvery = 6.0;       // s between a built-in robot's "what my laser mapped" datagrams
constexpr double kMapCell = 0.1;        // m, the squares that datagram is drawn in (world frame)
constexpr double kBaseMapEvery = 10.0;  // s between the base's submissions of the team's map

/// The squares (kSeenCell, world frame) where an explorer's own camera has looked, as a
/// "seen" datagram (mission/datagram_json); nothing when it has looked nowhere yet.
std::optional<std::vector<std::uint8_t>> seen_datagram(const autonomy::Explorer& ex, const Pose2& X_WM) {
  const autonomy::OccupancyMapper& map = ex.mapper();
  const auto box = map.observed_box();
  if (!box) return std::nullopt;
  std::map<std::pair<int, int>, int> counts;
  for (int y = box->first.y; y <= box->second.y; ++y) {
    for (int x = box->first.x; x <= box->second.x; ++x) {
      if (!ex.looked().looked_self({x, y})) continue;
      const Vec2 q = X_WM.transform(map.cell_to_world({x, y})) / kSeenCell;
      if (!(q.cwiseAbs().maxCoeff() < kMaxSeenSide)) continue;  // a map run far away says nothing
      ++counts[{static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))}];
    }
  }
  SeenSquares seen;
  seen.cell = kSeenCell;
  for (const auto& [ij, n] : counts) {
    if (n >= kSeenMinCells) seen.squares.push_back(ij);
  }
  if (seen.squares.empty()) return std::nullopt;
  return rescuesim::seen_datagram(seen);
}

/// What an explorer's laser has mapped, in kMapCell squares of the world, as a "map" datagram
/// (mission/datagram_json): a square holding an occupied cell is occupied, else one holding a
/// free cell is free. Nothing before its first scan. Map cells are half a square, so every
/// square the map covers holds a cell's centre, whatever the start's heading.
std::optional<std::vector<std::uint8_t>> map_datagram(const autonomy::Explorer& ex, const Pose2& X_WM) {
  const autonomy::OccupancyMapper& map = ex.mapper();
  const auto box = map.observed_box();
  if (!box) return std::nullopt;
  // the squares of the observed box's corners in the world
  Box2 world;
  const double r = map.resolution() / 2;
  using autonomy::Cell;
  for (const Cell& c : {box->first, box->second, Cell{box->first.x, box->second.y}, Cell{box->second.x, box->first.y}}) {
    for (const Vec2& d : {Vec2(-r, -r), Vec2(r, r), Vec2(-r, r), Vec2(r, -r)}) world.extend(X_WM.transform(map.cell_to_world(c) + d));
  }
  const Vec2 lo = (world.min / kMapCell).array().floor(), hi = (world.max / kMapCell).array().floor();
  if (!(lo.cwiseAbs().maxCoeff() <= kMaxSeenSide && hi.cwiseAbs().maxCoeff() <= kMaxSeenSide))
    return std::nullopt;  // a map run far away says nothing
  MapSquares out;
  out.cell = kMapCell;
  out.origin = {static_cast<int>(lo.x()), static_cast<int>(lo.y())};
  out.width = static_cast<int>(hi.x() - lo.x()) + 1;
  out.height = static_cast<int>(hi.y() - lo.y()) + 1;
  if (static_cast<long>(out.width) * out.height > kMaxMapSquares) return std::nullopt;
  out.states.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), MapSquares::unknown);
  for (int y = box->first.y; y <= box->second.y; ++y) {
    for (int x = box->first.x; x <= box->second.x; ++x) {
      const autonomy::CellState st = map.state({x, y});
      if (st == autonomy::CellState::unknown) continue;
      const Vec2 q = X_WM.transform(map.cell_to_world({x, y})) / kMapCell;
      const int i = std::clamp(static_cast<int>(std::floor(q.x())) - out.origin.first, 0, out.width - 1);
      const int j = std::clamp(static_cast<int>(std::floor(q.y())) - out.origin.second, 0, out.height - 1);
      std::uint8_t& v = out.states[static_cast<std::size_t>(j) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(i)];
      v = std::max<std::uint8_t>(v, st == autonomy::CellState::occupied ? MapSquares::occupied : MapSquares::free);
    }
  }
  return rescuesim::map_datagram(out);
}
}  // namespace

namespace {
/// The team's map from the robots' newest maps (kMapCell squares of the world, every map of that
/// cell): occupied where any says occupied, else free where any says free, else unknown; as a
/// nav_msgs/OccupancyGrid in the map frame (the world's). Nothing when there is no map yet.
std::optional<msg::OccupancyGrid> team_map(const std::vector<TeamMember>& members, SimTime stamp) {
  int i0 = std::numeric_limits<int>::max(), j0 = i0, i1 = std::numeric_limits<int>::min(), j1 = i1;
  for (const TeamMember& member : members) {
    const std::optional<MapSquares>& m = member.base_map;
    if (!m || m->cell != kMapCell) continue;
    i0 = std::min(i0, m->origin.first), j0 = std::min(j0, m->origin.second);
    i1 = std::max(i1, m->origin.first + m->width - 1), j1 = std::max(j1, m->origin.second + m->height - 1);
  }
  if (i0 > i1) return std::nullopt;
  const long w = static_cast<long>(i1) - i0 + 1, h = static_cast<long>(j1) - j0 + 1;
  if (w * h > 4 * kMaxMapSquares) return std::nullopt;  // (each map is within kMaxSeenSide; together they stay sane)
  std::vector<std::uint8_t> states(static_cast<std::size_t>(w * h), MapSquares::unknown);
  for (const TeamMember& member : members) {
    const std::optional<MapSquares>& m = member.base_map;
    if (!m || m->cell != kMapCell) continue;
    for (int j = 0; j < m->height; ++j) {
      for (int i = 0; i < m->width; ++i) {
        const std::size_t at = static_cast<std::size_t>((m->origin.second + j - j0) * w + (m->origin.first + i - i0));
        states[at] =
            std::max(states[at], m->states[static_cast<std::size_t>(j) * static_cast<std::size_t>(m->width) + static_cast<std::size_t>(i)]);
      }
    }
  }
  msg::OccupancyGrid g;
  g.header = {stamp, "map"};
  g.map_load_time = stamp;
  g.resolution = static_cast<float>(kMapCell);
  g.width = static_cast<std::uint32_t>(w);
  g.height = static_cast<std::uint32_t>(h);
  g.origin = Pose3::from_pose2({i0 * kMapCell, j0 * kMapCell, 0.0});
  g.data.resize(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    g.data[k] = states[k] == MapSquares::occupied ? std::int8_t{100} : (states[k] == MapSquares::free ? std::int8_t{0} : std::int8_t{-1});
  }
  return g;
}
}  // namespace

BuiltinTeam::BuiltinTeam(Mission& mission, BuiltinControllers& controllers, std::size_t robots, std::size_t victims, Picture picture)
    : mission_(mission), controllers_(controllers), picture_(std::move(picture)) {
  memory_.members.resize(robots);
  for (TeamMember& m : memory_.members) {
    m.known.assign(victims, false);
    m.heard.assign(robots, std::nullopt);
  }
}

void BuiltinTeam::post_step(Simulation& sim) {
  report_and_relay(sim);
  hear();
  talk(sim);
  // the base reads only what the built-in robots send it (a team driven from outside submits
  // its own map on /rescue/map)
  if (controllers_.any()) base_map_step(sim.state().time);
}

void BuiltinTeam::report_and_relay(const Simulation& sim) {
  const State& s = sim.state();
  const SimTime gap = SimTime::from_seconds(1.0 / mission_.spec().rules.report_rate_hz);
  const RadioNetwork& net = mission_.network();
  // the relay rule reads only the links, so it runs once per link update, not every step
  const bool links_new = net.update_count() != memory_.relay_check;
  memory_.relay_check = net.update_count();
  for (std::size_t r = 0; r < controllers_.size(); ++r) {
    autonomy::Explorer* ex = controllers_.explorer(r);
    if (!ex) continue;  // robots driven from outside report for themselves
    const RobotIndex ri = RobotIndex::at(r);
    const RobotState& rs = s.robots[r];
    for (std::size_t v = 0; v < s.victims.size(); ++v) {
      if (memory_.members[r].known[v] || !s.victims[v].seen_by_robot(r)) continue;
      // where the robot believes the victim is: its offset from the robot (the victim sensor),
      // placed at the robot's own pose estimate: odometry corrected by the explorer's scan
      // matching (X_MO), in its map frame, which starts on the odom frame at the start pose
      const Vec3 centre = sim.world().victims[v].centre;
      const Vec2 p_B = rs.base.X_WB.to_pose2().inverse().transform(centre.head<2>());
      const Vec2 p_W = (controllers_.X_WO(r) * ex->X_MO() * rs.odom).transform(p_B);
      memory_.members[r].known[v] = true;
      // a victim a teammate said it found (within the rules' radius of where this robot
      // believes it lies) is the teammate's to report; a report of it would be a duplicate
      bool teammates = false;
      for (const auto& h : memory_.members[r].heard) {
        if (!h) continue;
        for (const Vec2& q : h->victims) teammates = teammates || (q - p_W).norm() <= mission_.spec().rules.report_radius_m;
      }
      if (teammates) continue;
      memory_.members[r].found_W.push_back(p_W);
      memory_.members[r].pending.push_back(
          {VictimIndex::at(v), Vec3(p_W.x(), p_W.y(), centre.z()), picture_ ? picture_(ri) : std::nullopt});
    }
    const bool contact = mission_.in_contact(ri);
    if (contact) {
      memory_.members[r].lost_contact = SimTime{-1};
    } else if (memory_.members[r].lost_contact.ns < 0) {
      memory_.members[r].lost_contact = s.time;
    }
    if (!memory_.members[r].pending.empty() && contact && s.time >= memory_.members[r].next_report) {
      PendingReport& next = memory_.members[r].pending.front();
      if (next.picture) {
        mission_.report(ri, next.p_W, std::move(*next.picture));
      } else {
        mission_.report(ri, next.p_W);
      }
      memory_.members[r].pending.erase(memory_.members[r].pending.begin());
      memory_.members[r].next_report = s.time + gap;
    }
    // out of contact for a while with reports to make: back towards the (first) base, in the
    // explorer's map frame (placed at the start pose like the odom frame), until contact is back and the reports are made
    if (!memory_.members[r].returning && !memory_.members[r].pending.empty() && !contact &&
        (s.time - memory_.members[r].lost_contact).seconds() >= kReturnAfter) {
      const Vec3 base = net.node(mission_.base_nodes().front()).p_W;
      ex->set_goal(controllers_.X_WO(r).inverse().transform(base.head<2>()));
      memory_.members[r].returning = true;
    } else if (memory_.members[r].returning && contact && memory_.members[r].pending.empty()) {
      ex->clear_goal();
      memory_.members[r].returning = false;
    }
    // a relay where the link to the base grows weak, unless one is close by
    if (links_new && contact && net.relays_left(mission_.robot_node(ri)) > 0 && net.model().kind != RadioModelKind::ideal) {
      const RadioNodeIndex me = mission_.robot_node(ri);
      // the margin of the route to a base: its weakest link's, the best over the bases
      double margin = -std::numeric_limits<double>::infinity();
      for (RadioNodeIndex b : mission_.base_nodes()) {
        const std::vector<RadioNodeIndex> path = net.route(me, b);
        if (path.size() < 2) continue;
        double bottleneck = std::numeric_limits<double>::infinity();
        for (std::size_t k = 1; k < path.size(); ++k) bottleneck = std::min(bottleneck, net.link(path[k - 1], path[k]).margin_db);
        margin = std::max(margin, bottleneck);
      }
      bool near = false;
      for (RadioNodeIndex n : net.node_indices()) {
        if (net.node(n).kind == RadioNodeKind::robot) continue;
        near = near || (net.node(n).p_W - net.node(me).p_W).head<2>().norm() < kRelaySpacing;
      }
      if (margin < kRelayMargin && !near) mission_.drop_relay(ri);
    }
  }
}

void BuiltinTeam::hear() {
  const std::size_t n = controllers_.size();
  // what each built-in robot heard since the last step
  for (std::size_t r = 0; r < n; ++r) {
    if (!controllers_.explorer(r)) continue;
    for (const Datagram& d : mission_.take_inbox(RobotIndex::at(r))) {
      for (std::size_t k = 0; k < n; ++k) {
        if (k == r || mission_.robot_node(RobotIndex::at(k)) != d.from) continue;
        if (auto said = read_team_datagram(d.bytes))
          memory_.members[r].heard[k] = TeamClaim{said->at, said->going, d.sent, std::move(said->victims)};
        if (const auto seen = read_seen_datagram(d.bytes)) {
          // the centres of the squares the teammate's camera looked at, in this robot's map frame
          const Pose2 X_MW = controllers_.X_WO(r).inverse();
          std::vector<Vec2> centres_M;
          centres_M.reserve(seen->squares.size());
          for (const auto& [i, j] : seen->squares) centres_M.push_back(X_MW.transform(Vec2(i + 0.5, j + 0.5) * seen->cell));
          controllers_.explorer(r)->add_team_seen(centres_M, seen->cell);
        }
        if (const auto map = read_map_datagram(d.bytes)) {
          // the squares the teammate mapped, centred in this robot's map frame
          const Pose2 X_MW = controllers_.X_WO(r).inverse();
          std::vector<std::pair<Vec2, autonomy::CellState>> squares_M;
          for (int j = 0; j < map->height; ++j) {
            for (int i = 0; i < map->width; ++i) {
              const std::uint8_t v =
                  map->states[static_cast<std::size_t>(j) * static_cast<std::size_t>(map->width) + static_cast<std::size_t>(i)];
              if (v == MapSquares::unknown) continue;
              const Vec2 centre_W = Vec2(map->origin.first + i + 0.5, map->origin.second + j + 0.5) * map->cell;
              squares_M.emplace_back(X_MW.transform(centre_W),
                                     v == MapSquares::occupied ? autonomy::CellState::occupied : autonomy::CellState::free);
            }
          }
          controllers_.explorer(r)->add_team_map(squares_M, map->cell);
        }
      }
    }
  }
}

void BuiltinTeam::talk(const Simulation& sim) {
  const State& s = sim.state();
  const std::size_t n = controllers_.size();
  for (std::size_t r = 0; r < n; ++r) {
    autonomy::Explorer* ex = controllers_.explorer(r);
    if (!ex) continue;
    const RobotIndex ri = RobotIndex::at(r);
    // tell the teammates where it is and where it goes (its map frame placed at its start)
    if (s.time >= memory_.members[r].next_share) {
      memory_.members[r].next_share = s.time + SimTime::from_seconds(kShareEvery);
      const std::optional<Pose2> X_MB = ex->pose_in_map(s.time);
      if (X_MB) {
        const Vec2 at_W = controllers_.X_WO(r).transform(X_MB->position());
        const std::optional<Vec2> going = ex->frontier_target();
        const std::optional<Vec2> going_W = going ? std::optional<Vec2>(controllers_.X_WO(r).transform(*going)) : std::nullopt;
        const auto& found = memory_.members[r].found_W;  // (a world of more victims than a datagram names tells the first ones)
        const auto bytes = team_datagram(
            {at_W, going_W, {found.begin(), found.begin() + static_cast<std::ptrdiff_t>(std::min(found.size(), kMaxTeamVictims))}});
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && controllers_.explorer(k)) mission_.send(ri, sim.world().robots[k].name, bytes);
        }
      }
    }
    // and where its camera has looked, less often
    if (s.time >= memory_.members[r].next_seen) {
      // (nothing to say before its first look: it tries again at the next step)
      if (const auto bytes = seen_datagram(*ex, controllers_.X_WO(r))) {
        memory_.members[r].next_seen = s.time + SimTime::from_seconds(kSeenEvery);
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && controllers_.explorer(k)) mission_.send(ri, sim.world().robots[k].name, *bytes);
        }
      }
    }
    // and what its laser has mapped, as often, to the base too
    if (s.time >= memory_.members[r].next_map) {
      if (const auto bytes = map_datagram(*ex, controllers_.X_WO(r))) {
        memory_.members[r].next_map = s.time + SimTime::from_seconds(kMapEvery);
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && controllers_.explorer(k)) mission_.send(ri, sim.world().robots[k].name, *bytes);
        }
        mission_.send(ri, "base", *bytes);
      }
    }
    // what it heard lately becomes its claims, in its own map frame
    std::vector<Vec2> claims_M;
    const Pose2 X_MW = controllers_.X_WO(r).inverse();
    for (std::size_t k = 0; k < n; ++k) {
      const auto& h = memory_.members[r].heard[k];
      if (!h || (s.time - h->stamp).seconds() > kClaimAge) continue;
      claims_M.push_back(X_MW.transform(h->at));
      if (h->going) claims_M.push_back(X_MW.transform(*h->going));
    }
    ex->set_claims(std::move(claims_M));
  }
}

void BuiltinTeam::base_map_step(SimTime now) {
  for (std::size_t b = 0; b < mission_.base_nodes().size(); ++b) {
    for (const Datagram& d : mission_.take_base_inbox(b)) {
      for (std::size_t k = 0; k < controllers_.size(); ++k) {
        if (!controllers_.explorer(k) || mission_.robot_node(RobotIndex::at(k)) != d.from) continue;
        if (auto m = read_map_datagram(d.bytes)) {
          memory_.members[k].base_map = std::move(*m);
          memory_.base_map_new = true;
        }
      }
    }
  }
  if (!memory_.base_map_new || now < memory_.next_base_map) return;
  memory_.next_base_map = now + SimTime::from_seconds(kBaseMapEvery);
  memory_.base_map_new = false;
  if (const auto g = team_map(memory_.members, now)) mission_.score_map(*g);
}

std::any BuiltinTeam::save() const {
  TeamMemory saved;
  copy_fields(memory_, saved);
  return saved;
}

void BuiltinTeam::load(const std::any& memory, Simulation&) { copy_fields(std::any_cast<const TeamMemory&>(memory), memory_); }

}  // namespace rescuesim
