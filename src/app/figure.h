#pragma once
/// The seed paper's Fig. 2 as a raster figure: a large main view of the robot on the left and,
/// clockwise from top right, the robot's colour camera, thermal camera, depth camera and laser
/// range finder — composed from images already rendered or published (no graphics here), for
/// `rescuesim snapshot`. The pieces (sensor messages as images, false colours, the laser plot,
/// the chase camera) are shared with `rescuesim view`. Messages become images with the decoders in
/// sensors/camera/camera.h.
///
/// Layout at width W (all integers; u = W / 1600, text scale S = max(1, round(2u))):
///   margin m = round(20u), gap g = round(12u), panel c × ch with c = round(0.2 W) and
///   ch = round(0.75 c), caption strip under every image cap = 28 S, title band
///   t = m + 7 (S + 1) + g. Panels sit in a 2 × 2 block at the right (laser | colour over
///   depth | thermal) starting at x = W − m − 2c − g, y = t; the main view fills the left, from
///   (m, t) to the gap before the panels, as tall as the block minus one caption strip. Height
///   H = t + 2 (ch + cap) + 2g. At the default W = 1600 the figure is 1600 × 669 px: main view
///   896 × 548 at (20, 53); panels 320 × 240 — laser at (928, 53), colour at (1260, 53), depth at
///   (928, 361), thermal at (1260, 361).

#include <string>

#include "msgs/messages.h"
#include "raycast/ray_scene.h"
#include "render/renderer.h"
#include "viz/canvas.h"
#include "world/robot_spec.h"

namespace rescuesim {

/// A rectangle of figure pixels: [x, x + w) × [y, y + h).
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
};

/// Where everything of a figure sits (see the formulas above).
struct FigureLayout {
  int width = 0, height = 0;  ///< px
  int text_scale = 2;         ///< captions are drawn with the 5 × 7 font at this scale
  int caption = 56;           ///< px of caption strip under each image
  PixelRect title;            ///< band across the top
  PixelRect main;             ///< the main view image
  PixelRect color, thermal, depth, laser;  ///< the four sensor panels' images
};

/// Smallest and largest figure width accepted (px).
inline constexpr int kFigureMinWidth = 640;
inline constexpr int kFigureMaxWidth = 4096;

/// The layout of a figure `width` px wide; throws Error outside [kFigureMinWidth, kFigureMaxWidth].
FigureLayout figure_layout(int width);

/// The sensors a figure shows: the first of each kind on a robot (null when it has none).
struct FigureSensors {
  const SensorSpec* laser = nullptr;
  const SensorSpec* color = nullptr;
  const SensorSpec* depth = nullptr;
  const SensorSpec* thermal = nullptr;
};
FigureSensors figure_sensors(const RobotSpec& robot);

/// Everything a figure shows. Images may be empty (width 0): their panel then says so.
struct FigureInputs {
  int width = 1600;                 ///< figure width (px); the height follows from the layout
  std::string title;                ///< the line at the top (scenario, seed, sim time, ...)
  ColorImage main;                  ///< main view; cropped to the panel's aspect and scaled to fit
  std::string main_caption;
  ColorImage color;                 ///< the robot's colour camera
  std::string color_caption;
  ThermalImage thermal;             ///< apparent temperature (K)
  double thermal_min = 288.15;      ///< K shown darkest (the camera's mono8 window)
  double thermal_max = 313.15;      ///< K shown brightest
  std::string thermal_caption;
  DepthImage depth;                 ///< optical-axis depth (m)
  double depth_min = 0.3;           ///< m: nearer is no return (black)
  double depth_max = 8.0;           ///< m: farther is no return (black)
  std::string depth_caption;
  msg::LaserScan scan;              ///< the last scan; no ranges = no data
  double laser_radius = 5.0;        ///< m from the centre to the panel's nearer edge
  std::string laser_caption;
};

/// Draws the figure (white background, captions under every image, colour bars in metres and
/// degrees Celsius).
Canvas compose_figure(const FigureInputs& inputs);

/// An RGB image as a canvas of the same size.
Canvas to_canvas(const ColorImage& image);

/// `src` cropped to the aspect of w × h about its centre and scaled to w × h: averaged over each
/// destination pixel's footprint when shrinking, bilinear when enlarging.
Canvas fit_canvas(const Canvas& src, int w, int h);

/// Iron false colour: black through purple, red and orange to pale yellow, for f in [0, 1].
Rgb8 iron_color(double f);
/// Depth false colour: red (near) through yellow, green and blue to indigo (far), f in [0, 1].
Rgb8 depth_color(double f);

/// A thermal image in iron colours, `t_min` .. `t_max` kelvin mapped to 0 .. 1 (clamped).
Canvas thermal_canvas(const ThermalImage& image, double t_min, double t_max);
/// A depth image in depth colours over [z_min, z_max] metres; black where there is no return
/// (infinite, or outside the range).
Canvas depth_canvas(const DepthImage& image, double z_min, double z_max);

/// A top-down plot of a scan, w × h px: the laser at the centre with x (forward) up, rings every
/// metre out to `radius` metres at the nearer edge (labelled with the 5 × 7 font at `text_scale`),
/// the swept free space shaded and returns as dots.
Canvas laser_canvas(const msg::LaserScan& scan, int w, int h, double radius, int text_scale = 1);

/// A camera at `p_WE` looking at `p_WT` (world frame, m; render/camera_model.h look_at) with the
/// intrinsics `k`, clipping at 0.05 and 60 m.
CameraView look_at_view(const Vec3& p_WE, const Vec3& p_WT, const Intrinsics& k);

/// render/camera_model.h clear_eye against a ray scene: walls, rubble, victims and other robots
/// hide; robot `ignore_robot` (an index into World::robots) does not. The chase camera's other
/// parts (chase_points, kChase*) are in render/camera_model.h.
Vec3 clear_eye(const RayScene& scene, const Vec3& p_WE, const Vec3& p_WT, const Vec3& p_WR, RobotIndex ignore_robot = {});

}  // namespace rescuesim
