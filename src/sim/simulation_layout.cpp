// Robots and loose bodies added and removed while the simulation runs (SpawnEntity,
// DeleteEntity, a reset of spawned entities): each change is a new version of the World, a
// physics engine and a ray scene built from it, and the State carried over (see simulation.h).

#include <algorithm>
#include <string>

#include "core/error.h"
#include "sim/simulation.h"

namespace rescuesim {

namespace {

/// old index -> new index for `count` robots when `removed` goes (or none, when it is invalid).
IndexedVector<RobotTag, RobotIndex> map_without(std::size_t count, RobotIndex removed = {}) {
  IndexedVector<RobotTag, RobotIndex> map(count);
  for (RobotIndex r : map.indices()) {
    if (!removed.valid() || r < removed) {
      map[r] = r;
    } else if (r > removed) {
      map[r] = RobotIndex(r.value() - 1);  // moves down one; `removed` itself stays invalid (gone)
    }
  }
  return map;
}

}  // namespace

RobotIndex Simulation::add_robot(RobotInstance robot) {
  RS_DEMAND(robot.spawned && !robot.ns.empty(), "Simulation::add_robot: a spawned robot with a namespace");
  RS_DEMAND(!robot_index(robot.name).valid(), "Simulation::add_robot: the name is in use");
  auto next = std::make_unique<World>(world());
  next->robots.push_back(std::move(robot));
  add_robot_materials(*next);
  State next_state = state_;
  // at rest at its start, as a fresh world would have it
  RobotState rs = initial_state(*next).robots.back();
  rs.odom = Pose2{};
  next_state.robots.push_back(std::move(rs));
  const RobotIndex index = RobotIndex::at(next->robots.size() - 1);
  rebuild(std::move(next), std::move(next_state), map_without(state_.robots.size()));
  return index;
}

std::size_t Simulation::add_body(DynamicObject body) {
  RS_DEMAND(body.spawned, "Simulation::add_body: a spawned body");
  auto next = std::make_unique<World>(world());
  next->dynamics.push_back(std::move(body));
  State next_state = state_;
  next_state.dynamics.push_back(initial_state(*next).dynamics.back());
  const std::size_t index = next->dynamics.size() - 1;
  rebuild(std::move(next), std::move(next_state), map_without(state_.robots.size()));
  return index;
}

void Simulation::remove_robot(RobotIndex robot) {
  RS_DEMAND(world().has_robot(robot) && world().robot(robot).spawned, "Simulation::remove_robot: a spawned robot");
  auto next = std::make_unique<World>(world());
  next->robots.erase(next->robots.begin() + robot.value());
  State next_state = state_;
  next_state.robots.erase(next_state.robots.begin() + robot.value());
  for (VictimState& v : next_state.victims) {
    if (robot.slot() < v.seen_at.size()) v.seen_at.erase(v.seen_at.begin() + robot.value());
  }
  rebuild(std::move(next), std::move(next_state), map_without(state_.robots.size(), robot));
}

void Simulation::remove_body(std::size_t body) {
  RS_DEMAND(body < world().dynamics.size() && world().dynamics[body].spawned, "Simulation::remove_body: a spawned body");
  auto next = std::make_unique<World>(world());
  next->dynamics.erase(next->dynamics.begin() + static_cast<long>(body));
  State next_state = state_;
  next_state.dynamics.erase(next_state.dynamics.begin() + static_cast<long>(body));
  rebuild(std::move(next), std::move(next_state), map_without(state_.robots.size()));
}

void Simulation::remove_spawned() {
  if (world().robots.size() == base_robots_ && world().dynamics.size() == base_dynamics_) return;
  // back to the world as it was made (spawned things come after the scenario's own)
  State next_state = state_;
  next_state.robots.resize(base_robots_);
  next_state.dynamics.resize(base_dynamics_);
  for (VictimState& v : next_state.victims) {
    if (v.seen_at.size() > base_robots_) v.seen_at.resize(base_robots_);
  }
  RobotMap map = map_without(state_.robots.size());
  for (RobotIndex r : map.indices()) {
    if (r.slot() >= base_robots_) map[r] = RobotIndex();
  }
  adopt(worlds_.front().get(), std::move(next_state), map);
}

void Simulation::rebuild(std::unique_ptr<const World> next, State next_state, const RobotMap& robot_map) {
  worlds_.push_back(std::move(next));
  adopt(worlds_.back().get(), std::move(next_state), robot_map);
}

void Simulation::switch_world(const World* next, const RobotMap& robot_map) {
  // commands already queued follow their robots (or go with them), under the lock bridges
  // submit under, so none lands on the wrong robot
  std::lock_guard lock(commands_mutex_);
  world_.store(next, std::memory_order_release);
  std::vector<Command> kept;
  for (Command& c : commands_) {
    if (!robot_map.contains(c.robot) || !robot_map[c.robot].valid()) continue;
    c.robot = robot_map[c.robot];
    kept.push_back(std::move(c));
  }
  commands_ = std::move(kept);
}

void Simulation::adopt(const World* next, State next_state, const RobotMap& robot_map) {
  // the engines first (they may throw on a bad model: nothing has changed yet then)
  auto physics = std::make_unique<Physics>(*next, options_.physics);
  auto rays = std::make_unique<RayScene>(*next);
  // topics of robots that go are retired; the others are advertised again below (with their
  // robots' new indices)
  for (const Topic& t : bus_.topics()) {
    if (t.retired || !t.robot.valid()) continue;
    if (robot_map.contains(t.robot) && !robot_map[t.robot].valid()) bus_.retire(t.id);
  }
  const std::vector<SensorInstance> old_sensors = sensors_;
  // frames in flight were rendered for the world now: out before it changes
  flush_cameras();
  switch_world(next, robot_map);
  if (world_changed_) world_changed_();
  physics_ = std::move(physics);
  rays_ = std::move(rays);
  rays_current_ = false;
  setup_robot_topics();
  // each sensor keeps its slot (RNG stream, schedule, memory); a new robot's sensors are due now
  std::vector<SensorSlot> slots;
  slots.reserve(sensors_.size());
  for (const SensorInstance& s : sensors_) {
    const auto old = std::find_if(old_sensors.begin(), old_sensors.end(), [&](const SensorInstance& o) {
      return robot_map.contains(o.robot) && robot_map[o.robot] == s.robot && o.index == s.index;
    });
    slots.push_back(old != old_sensors.end() ? next_state.sensors[static_cast<std::size_t>(old->slot)] : new_slot(s, state_.time));
  }
  next_state.sensors = std::move(slots);
  state_ = std::move(next_state);
  physics_->restore(state_);
  // what a new robot offers at once: its fixed frames and its description (latched)
  if (state_.schedule.started) {
    publish_tf_static();
    publish_descriptions();
  }
  bus_.layout_changed();
}

}  // namespace rescuesim
