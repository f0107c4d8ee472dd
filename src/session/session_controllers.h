#pragma once
// Internal to src/session: the built-in controllers of a run.

#include <memory>
#include <vector>

#include "autonomy/explorer.h"
#include "session/session.h"

namespace rescuesim {

/// The built-in controllers, one per robot that asked for one, fed from the Bus.
struct Session::Controllers {
  std::vector<std::unique_ptr<autonomy::Explorer>> explorers;  // per robot, null when none
  std::vector<Pose2> X_WO;                                     // per robot: odom frame in the world (its start pose)
};

}  // namespace rescuesim
