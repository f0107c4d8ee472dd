#pragma once
/// RunOutputs: what the systems of a run (sim/run_system.h) are handed when the run ends and
/// its files are written (Session::write_outputs). Each system writes its own files into `dir`
/// and draws its own layer on the overview picture, in the order the run lists its systems:
///
///   session       summary.json, world.svg, the world drawn on overview.png
///   controllers   each built-in explorer's map on the overview
///   recorder      trajectory.csv, each robot's path on the overview, sensors/laser*.png
///   mission       score.png, reports/ (the reports' pictures)
///   session       the victims (found: green ring, missed: red cross), overview.png, camera frames
///
/// Every file is written atomically (core/atomic_file.h, Canvas::write_png).

#include <filesystem>
#include <string>

namespace rescuesim {

class Canvas;
struct PlotFrame;

struct RunOutputs {
  std::filesystem::path dir;  ///< the output folder (made before; its sensors/ and reports/ too)
  std::string run_name;       ///< the scenario's name, for titles
  double sim_time = 0;        ///< s, when the run ended
  Canvas& overview;           ///< overview.png while it is drawn
  const PlotFrame& frame;     ///< world (m) -> overview pixels
};

}  // namespace rescuesim
