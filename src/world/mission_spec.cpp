#include "world/mission_spec.h"

#include "core/error.h"

namespace rescuesim {

MissionRules mission_rules(const std::string& preset) {
  MissionRules r;
  r.preset = preset;
  if (preset == "robocup") return r;  // the struct's defaults are RoboCup's Virtual Robot rules
  if (preset == "subt") {
    // DARPA SubT (osrf/subt GameLogicPlugin): 5 m, no penalty, 40 reports in the default worlds
    r.report_radius_m = 5.0;
    r.false_report_penalty = 0.0;
    r.report_limit = 40;
    return r;
  }
  throw Error("unknown mission rules '" + preset + "': expected robocup or subt");
}

}  // namespace rescuesim
