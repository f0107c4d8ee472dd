// RunControl's entities: what a run has (robots, victims, rubble, walls), their states and
// bounds, teleports, named poses (see run_control.h); spawning is in run_control_spawn.cpp.

#include "session/run_control.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <regex>

#include "session/session.h"

namespace rescuesim {

using namespace control;

namespace {

/// Every corner of a shape's bounding box, or its vertices, in the frame `X` puts it in.
void add_points(const Geometry& g, const Pose3& X, Vec3& lo, Vec3& hi) {
  const auto take = [&](const Vec3& p) {
    const Vec3 w = X.p + X.q * p;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  };
  if ((g.type == Geometry::Type::convex || g.type == Geometry::Type::mesh) && !g.mesh.vertices.empty()) {
    for (const Vec3& v : g.mesh.vertices) take(v);
    return;
  }
  const Vec3 h = g.size / 2;
  for (int i = 0; i < 8; ++i) take(Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
}

}  // namespace

std::string RunControl::pose_problem(const Pose3& X) {
  if (!X.p.allFinite()) return "the position is not finite";
  const Eigen::Vector4d q(X.q.x(), X.q.y(), X.q.z(), X.q.w());
  if (!q.allFinite()) return "the orientation is not finite";
  // ROS tools write quaternions with a few digits; 1e-3 accepts those and refuses real mistakes
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    return "the orientation quaternion is not a unit quaternion (norm " + std::to_string(q.norm()) + ")";
  }
  return "";
}

const RunControl::Entity* RunControl::find(const std::string& name) const {
  for (const Entity& e : entities_) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

Result RunControl::entities(const EntityFilters& filters, std::vector<std::string>& names) const {
  names.clear();
  if (!filters.tags.tags.empty())
    return Result::fail(code::kFeatureUnsupported, "entities carry no tags in rescuesim: filter by name, category or bounds");
  std::optional<std::regex> re;
  if (!filters.filter.empty()) {
    try {
      re.emplace(filters.filter, std::regex::extended | std::regex::nosubs);
    } catch (const std::regex_error& e) {
      return Result::fail(code::kOperationFailed,
                          "the filter '" + filters.filter + "' is no POSIX extended regular expression: " + e.what());
    }
  }
  const Bounds& b = filters.bounds;
  if (b.type == Bounds::kSphere && b.points.size() != 2)
    return Result::fail(code::kOperationFailed, "a SPHERE bounds filter needs 2 points (centre, then radius in x)");
  if (b.type == Bounds::kBox && b.points.size() != 2)
    return Result::fail(code::kOperationFailed, "a BOX bounds filter needs 2 points (two corners)");
  if (b.type == Bounds::kConvexHull)
    return Result::fail(code::kFeatureUnsupported, "CONVEX_HULL bounds filters are not supported: use a sphere or a box");
  if (b.type > Bounds::kSphere) return Result::fail(code::kOperationFailed, "unknown bounds type " + std::to_string(b.type));
  for (const Entity& e : entities_) {
    if (re && !std::regex_search(e.name, *re)) continue;
    if (!filters.categories.empty()) {
      EntityInfo info;
      entity_info(e.name, info);
      if (std::find(filters.categories.begin(), filters.categories.end(), info.category) == filters.categories.end()) continue;
    }
    if (b.type != Bounds::kEmpty) {
      EntityState st;
      entity_state(e.name, st);
      const Vec3& p = st.pose.p;
      if (b.type == Bounds::kSphere && (p - b.points[0]).norm() > b.points[1].x()) continue;
      if (b.type == Bounds::kBox) {
        const Vec3 lo = b.points[0].cwiseMin(b.points[1]), hi = b.points[0].cwiseMax(b.points[1]);
        if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
      }
    }
    names.push_back(e.name);
  }
  return Result::ok();
}

Result RunControl::entity_state(const std::string& name, EntityState& out) const {
  const Entity* e = find(name);
  if (!e) return Result::fail(code::kNotFound, "no entity named '" + name + "'");
  const Simulation& sim = session_.sim();
  const State& s = sim.state();
  out = EntityState{};
  out.stamp_ns = s.time.ns;
  switch (e->kind) {
    case Entity::Kind::robot: {
      const RobotState& r = s.robots[e->index];
      out.pose = r.base.X_WB;
      out.linear = r.base.v_WB;
      out.angular = r.base.w_WB;
      // the acceleration of the last step (the robot keeps its base velocity one step back)
      out.linear_acc = (r.base.v_WB - r.prev_v_WB) / sim.dt();
      break;
    }
    case Entity::Kind::rubble: {
      const BodyState& b = s.dynamics[e->index];
      out.pose = b.X_WB;
      out.linear = b.v_WB;
      out.angular = b.w_WB;
      break;
    }
    case Entity::Kind::victim: {
      const Victim& v = sim.world().victims[e->index];
      out.pose = Pose3::from_pose2(v.pose, 0.0);
      break;
    }
    case Entity::Kind::fixed: out.pose = sim.world().statics[e->index].X_WO; break;
  }
  return Result::ok();
}

Result RunControl::set_entity_state(const std::string& name, const EntityState& target, bool set_pose, bool set_twist,
                                    bool set_acceleration) {
  const Entity* e = find(name);
  if (!e) return Result::fail(code::kNotFound, "no entity named '" + name + "'");
  if (set_acceleration)
    return Result::fail(code::kFeatureUnsupported, "accelerations cannot be set: forces make them; set the pose and the twist");
  if (!target.frame_id.empty() && target.frame_id != "world" && target.frame_id != "map") {
    return Result::fail(
        code::kOperationFailed,
        "frame '" + target.frame_id + "' is not supported: give the state in the world frame (frame_id empty, 'world' or 'map')");
  }
  if (set_pose) {
    if (const std::string why = pose_problem(target.pose); !why.empty()) return Result::fail(code::kInvalidPose, name + ": " + why);
  }
  if (set_twist && !(target.linear.allFinite() && target.angular.allFinite())) {
    return Result::fail(code::kInvalidPose, name + ": the twist is not finite");
  }
  if (e->kind == Entity::Kind::victim || e->kind == Entity::Kind::fixed) {
    return Result::fail(code::kOperationFailed, "'" + name + "' is fixed in the world (" +
                                                    (e->kind == Entity::Kind::victim ? "a victim" : "a wall or obstacle") +
                                                    ") and cannot be moved");
  }
  Simulation& sim = session_.sim();
  State s = sim.state();
  Pose3 X = target.pose;
  X.q.normalize();
  if (e->kind == Entity::Kind::robot) {
    RobotState& r = s.robots[e->index];
    if (set_pose) {
      // the whole robot moves rigidly: every link by the base's displacement
      const Pose3 delta = X * r.base.X_WB.inverse();
      for (Pose3& L : r.X_WL) L = delta * L;
      r.base.X_WB = X;
      if (!set_twist) {  // the velocities turn with the robot
        r.base.v_WB = delta.q * r.base.v_WB;
        r.base.w_WB = delta.q * r.base.w_WB;
      }
    }
    if (set_twist) {
      r.base.v_WB = target.linear;
      r.base.w_WB = target.angular;
    }
    r.prev_v_WB = r.base.v_WB;
    // wheel odometry does not see a teleport (a kidnapped robot): /odom goes on from where it was,
    // ground truth jumps
  } else {
    BodyState& b = s.dynamics[e->index];
    if (set_pose) b.X_WB = X;
    if (set_twist) {
      b.v_WB = target.linear;
      b.w_WB = target.angular;
    }
    b.sleep = BodyState::Sleep::awake;
    b.still_time = 0;
  }
  sim.restore(s);
  return Result::ok();
}

Result RunControl::entity_info(const std::string& name, EntityInfo& out) const {
  const Entity* e = find(name);
  if (!e) return Result::fail(code::kNotFound, "no entity named '" + name + "'");
  const World& w = session_.sim().world();
  out = EntityInfo{};
  switch (e->kind) {
    case Entity::Kind::robot:
      out.category = category::kRobot;
      out.description =
          "robot '" + name + "'" + (w.robots[e->index].spec.model.empty() ? "" : " (model " + w.robots[e->index].spec.model + ")");
      break;
    case Entity::Kind::victim: out.category = category::kHuman; out.description = "victim"; break;
    case Entity::Kind::rubble: out.category = category::kDynamicObject; out.description = "loose body (rubble)"; break;
    case Entity::Kind::fixed: {
      out.category = category::kStaticObject;
      static const char* kinds[] = {"floor", "wall", "obstacle", "raised area", "ramp", "victim", "rubble", "robot"};
      out.description = kinds[static_cast<int>(w.statics[e->index].kind)];
      break;
    }
  }
  return Result::ok();
}

Result RunControl::entity_bounds(const std::string& name, Bounds& out) const {
  const Entity* e = find(name);
  if (!e) return Result::fail(code::kNotFound, "no entity named '" + name + "'");
  const Simulation& sim = session_.sim();
  const World& w = sim.world();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  switch (e->kind) {
    case Entity::Kind::robot: {
      // every collision shape of every link, in the base frame, as the joints stand now
      const RobotState& r = sim.state().robots[e->index];
      const Pose3 X_BW = r.base.X_WB.inverse();
      const RobotSpec& spec = w.robots[e->index].spec;
      for (std::size_t l = 0; l < spec.links.size() && l < r.X_WL.size(); ++l) {
        for (const LinkShape& sh : spec.links[l].shapes) add_points(sh.geometry, X_BW * r.X_WL[l] * sh.X_LG, lo, hi);
      }
      break;
    }
    case Entity::Kind::rubble: add_points(w.dynamics[e->index].geometry, Pose3{}, lo, hi); break;
    case Entity::Kind::fixed: add_points(w.statics[e->index].geometry, Pose3{}, lo, hi); break;
    case Entity::Kind::victim: {
      const Pose3 X_VW = Pose3::from_pose2(w.victims[e->index].pose, 0.0).inverse();
      for (int part : w.victims[e->index].parts) {
        const StaticObject& s = w.statics[static_cast<std::size_t>(part)];
        add_points(s.geometry, X_VW * s.X_WO, lo, hi);
      }
      break;
    }
  }
  out = Bounds{};
  if (!lo.allFinite()) return Result::ok();  // no shapes: EMPTY
  out.type = Bounds::kBox;
  out.points = {lo, hi};
  return Result::ok();
}

Result RunControl::named_poses(const TagsFilter& tags, std::vector<NamedPose>& out) const {
  out.clear();
  for (const RobotInstance& r : session_.sim().world().robots) {
    NamedPose p;
    p.name = r.name + "_start";
    p.description = "where robot '" + r.name + "' starts";
    p.tags = {"start", "robot"};
    p.pose = r.X_W_start;
    bool keep = true;
    if (!tags.tags.empty()) {
      const auto has = [&](const std::string& t) { return std::find(p.tags.begin(), p.tags.end(), t) != p.tags.end(); };
      const bool any = std::any_of(tags.tags.begin(), tags.tags.end(), has);
      const bool all = std::all_of(tags.tags.begin(), tags.tags.end(), has);
      keep = tags.filter_mode == 1 ? all : any;
    }
    if (keep) out.push_back(std::move(p));
  }
  return Result::ok();
}

Result RunControl::named_pose_bounds(const std::string& name, Bounds&) const {
  return Result::fail(code::kFeatureUnsupported, "named poses have no bounds in rescuesim ('" + name + "')");
}

}  // namespace rescuesim
