#pragma once
/// Top-down pictures of worlds, in the colours of the SVG convention: walls and obstacles
/// black, raised areas red with lighter ramps, victims blue, rubble orange, robot starts green
/// with a heading tick. The run overview draws its path and map on top of this.

#include "viz/canvas.h"
#include "world/world_spec.h"

namespace rescuesim {

struct WorldPlotOptions {
  double px_per_m = 50;     ///< resolution
  int max_size_px = 2000;   ///< the larger side is capped at this (resolution lowered to fit)
  bool grid = true;         ///< light 1 m grid
  bool legend = true;       ///< a legend line and scale bar under the map
  std::string title;        ///< drawn above the map when not empty
};

/// A plot frame fitting the world's floor with the options' resolution and cap.
PlotFrame plot_frame_for(const WorldSpec& world, const WorldPlotOptions& options = {});

/// Draws the world on a new canvas sized by `plot_frame_for`.
Canvas plot_world(const WorldSpec& world, const WorldPlotOptions& options = {});

/// Draws the world into an existing canvas through `frame` (for composing overviews).
void draw_world(Canvas& canvas, const PlotFrame& frame, const WorldSpec& world);

}  // namespace rescuesim
