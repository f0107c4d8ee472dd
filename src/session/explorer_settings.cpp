#include "session/explorer_settings.h"

#include "core/error.h"

namespace rescuesim {

autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller) {
  if (controller != "explorer" && controller != "wall_follower") {
    throw Error("builtin_explorer_config: controller '" + controller + "' is neither explorer nor wall_follower");
  }
  autonomy::ExplorerConfig ec;
  // the robot as a disc around base_link: half the diagonal of its footprint with wheels
  ec.robot_radius = 0.41;
  if (controller == "wall_follower") ec.frontier_trips = false;  // never plans: pure wall following
  return ec;
}

}  // namespace rescuesim
