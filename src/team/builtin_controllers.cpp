#include "team/builtin_controllers.h"

#include <algorithm>

#include "core/parallel.h"
#include "sim/run_outputs.h"
#include "sim/simulation.h"
#include "viz/canvas.h"

namespace rescuesim {

/// What save() copies: each explorer whole, and the commands queued for the next step.
struct BuiltinControllers::Memory {
  std::vector<std::optional<autonomy::Explorer>> explorers;
  std::vector<std::optional<msg::Twist>> queued;
  std::vector<std::optional<double>> queued_look;
};

BuiltinControllers::BuiltinControllers(std::size_t robots) : robots_(robots) {}

void BuiltinControllers::attach(Simulation& sim, RobotIndex robot, std::unique_ptr<autonomy::Explorer> explorer, const Pose2& X_WO, Pan pan,
                                const std::vector<std::string>& topics) {
  const auto r = robot.slot();
  robots_[r].explorer = std::move(explorer);
  robots_[r].X_WO = X_WO;
  robots_[r].pan = std::move(pan);
  // what the explorer hears waits in its inbox until the step is over (post_step)
  for (const std::string& topic : topics) {
    sim.bus().subscribe(topic, [this, r](const Topic&, const msg::Message& m) { robots_[r].inbox.push_back(m); });
  }
}

bool BuiltinControllers::any() const {
  return std::any_of(robots_.begin(), robots_.end(), [](const Robot& r) { return r.explorer != nullptr; });
}

void BuiltinControllers::pre_step(Simulation&) {
  // what the controllers queue during this step is for the next one
  for (Robot& r : robots_) {
    r.queued.reset();
    r.queued_look.reset();
  }
}

void BuiltinControllers::command_look(Simulation& sim, std::size_t robot, double yaw) {
  Pan& pan = robots_[robot].pan;
  const RobotIndex ri = RobotIndex::at(robot);
  if (pan.in_head >= 0) {
    pan.head[static_cast<std::size_t>(pan.in_head)] = yaw;
    sim.command_head(ri, pan.head);
  } else {
    pan.joint.position[0] = yaw;
    sim.command_joints(ri, pan.joint);
  }
  robots_[robot].queued_look = yaw;
}

void BuiltinControllers::post_step(Simulation& sim) {
  std::vector<std::size_t> busy;
  for (std::size_t r = 0; r < robots_.size(); ++r) {
    if (!robots_[r].inbox.empty()) busy.push_back(r);
  }
  // each robot's explorer hears its own messages in the order they were published, on a worker
  // thread (explorers share nothing); what they ask for is then commanded in robot order
  struct Asked {
    msg::Twist cmd;
    std::optional<double> look;
  };
  std::vector<std::vector<Asked>> asked(busy.size());
  parallel_for(busy.size(), [&](std::size_t i) {
    Robot& robot = robots_[busy[i]];
    autonomy::Explorer& ex = *robot.explorer;
    for (const msg::Message& m : robot.inbox) {
      if (const auto* odom = std::get_if<msg::Odometry>(&m)) {
        ex.on_odometry(*odom);
      } else if (const auto* joints = std::get_if<msg::JointState>(&m)) {
        ex.on_joint_state(*joints);
      } else if (const auto* scan = std::get_if<msg::LaserScan>(&m)) {
        ex.on_scan(*scan);
        const msg::Twist cmd = ex.command(scan->header.stamp);
        asked[i].push_back({cmd, ex.look_command(scan->header.stamp)});
      }
    }
    robot.inbox.clear();
  });
  for (std::size_t i = 0; i < busy.size(); ++i) {
    const std::size_t r = busy[i];
    for (const Asked& a : asked[i]) {
      sim.command_velocity(RobotIndex::at(r), a.cmd);
      robots_[r].queued = a.cmd;
      if (a.look) command_look(sim, r, *a.look);
    }
  }
}

std::any BuiltinControllers::save() const {
  Memory m;
  for (const Robot& r : robots_) {
    m.explorers.push_back(r.explorer ? std::optional<autonomy::Explorer>(*r.explorer) : std::nullopt);
    m.queued.push_back(r.queued);
    m.queued_look.push_back(r.queued_look);
  }
  return m;
}

void BuiltinControllers::load(const std::any& memory, Simulation& sim) {
  const Memory& m = std::any_cast<const Memory&>(memory);
  for (std::size_t r = 0; r < robots_.size() && r < m.queued.size(); ++r) {
    robots_[r].queued = m.queued[r];
    if (m.queued[r]) sim.command_velocity(RobotIndex::at(r), *m.queued[r]);
  }
  for (std::size_t r = 0; r < robots_.size() && r < m.queued_look.size(); ++r) {
    robots_[r].queued_look = m.queued_look[r];
    if (m.queued_look[r]) command_look(sim, r, *m.queued_look[r]);
  }
  for (std::size_t r = 0; r < robots_.size() && r < m.explorers.size(); ++r) {
    if (robots_[r].explorer && m.explorers[r]) *robots_[r].explorer = *m.explorers[r];
  }
}

void BuiltinControllers::write_outputs(const Simulation& sim, RunOutputs& out) const {
  for (const Robot& robot : robots_) {
    const autonomy::Explorer* ex = robot.explorer.get();
    if (!ex) continue;
    const msg::OccupancyGrid map = ex->map(sim.time());
    const Pose2 X_WM = robot.X_WO;             // the map frame starts on the odom frame
    const Pose2 X_MG = map.origin.to_pose2();  // the grid's corner in the map frame
    for (std::uint32_t y = 0; y < map.height; ++y) {
      for (std::uint32_t x = 0; x < map.width; ++x) {
        const std::int8_t v = map.data[y * map.width + x];
        if (v < 65) continue;
        const Vec2 p_W = (X_WM * X_MG).transform({(x + 0.5) * map.resolution, (y + 0.5) * map.resolution});
        out.overview.fill_circle(out.frame.to_px(p_W), std::max(1.0, 0.5 * map.resolution * out.frame.px_per_m), {90, 110, 200}, 0.6);
      }
    }
  }
}

}  // namespace rescuesim
