#include "viz/world_plot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace rescuesim {
namespace {

constexpr Rgb8 kBlack{0, 0, 0};
constexpr Rgb8 kRed{214, 39, 40};
constexpr Rgb8 kBlue{31, 119, 180};
constexpr Rgb8 kGreen{44, 160, 44};
constexpr Rgb8 kOrange{255, 127, 14};
constexpr Rgb8 kFloor{250, 250, 250};

// a 6 x 5 m room: one wall, a victim, a raised square with a ramp, rubble and a robot
WorldSpec small_world() {
  WorldSpec w;
  w.name = "small";
  w.floor_min = {0, 0};
  w.floor_max = {6, 5};
  WallSpec wall;
  wall.a = {1, 1};
  wall.b = {4, 1};
  wall.thickness = 0.1;
  w.walls.push_back(wall);
  VictimSpec v;
  v.name = "v1";
  v.pose = {2, 3, 0};
  w.victims.push_back(v);
  RaisedAreaSpec r;
  r.outline = {{4.5, 2.5}, {5.5, 2.5}, {5.5, 3.5}, {4.5, 3.5}};
  r.ramp_edges = {0};  // the south edge
  w.raised_areas.push_back(r);
  RubbleSpec box;
  box.pose = {1, 4.2, 0.5};
  box.size = {0.4, 0.3, 0.2};
  w.rubble.push_back(box);
  RubbleSpec can;
  can.shape = RubbleSpec::Shape::cylinder;
  can.pose = {2, 4.2, 0};
  can.size = {0.4, 0.4, 0.3};
  w.rubble.push_back(can);
  RobotPlacement robot;
  robot.start = {5, 1, 0};
  w.robots.push_back(robot);
  return w;
}

Rgb8 at_world(const Canvas& c, const PlotFrame& f, Vec2 p) {
  const Vec2 px = f.to_px(p);
  return c.at(static_cast<int>(std::floor(px.x())), static_cast<int>(std::floor(px.y())));
}

// A floor patch is drawn in its material's colour at 70 % over the floor: sand (0.82, 0.72,
// 0.52) x 255 = (209, 184, 133), over the floor's 250: 0.7 x 209 + 0.3 x 250 = 221.3, and so on.
TEST(WorldPlot, AGroundAreaHasItsMaterialsColour) {
  WorldSpec w = small_world();
  w.materials = default_materials();
  w.ground.push_back({"pit", {{0.5, 1.5}, {1.5, 1.5}, {1.5, 2.5}, {0.5, 2.5}}, "sand", {}});
  WorldPlotOptions o;
  o.grid = false;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas c = plot_world(w, o);
  const Rgb8 sand = at_world(c, f, {1.02, 2.03});
  EXPECT_NEAR(sand.r, 0.7 * 209 + 0.3 * 250, 1.5);
  EXPECT_NEAR(sand.g, 0.7 * 184 + 0.3 * 250, 1.5);
  EXPECT_NEAR(sand.b, 0.7 * 133 + 0.3 * 250, 1.5);
  EXPECT_EQ(at_world(c, f, {3.02, 2.03}), kFloor);  // beside it, the floor
}

TEST(WorldPlot, ObjectsHaveTheirColours) {
  const WorldSpec w = small_world();
  WorldPlotOptions o;
  o.title = "small world";
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas c = plot_world(w, o);
  EXPECT_EQ(at_world(c, f, {2.5, 1}), kBlack);            // wall centre
  EXPECT_EQ(at_world(c, f, {2, 3}), kBlue);               // victim centre
  EXPECT_EQ(at_world(c, f, {5.1, 3.1}), kRed);            // raised platform
  const Rgb8 ramp = at_world(c, f, {5.1, 2.25});          // its ramp: lighter red
  EXPECT_GT(ramp.r, ramp.g);
  EXPECT_GT(ramp.g, kRed.g);
  EXPECT_EQ(at_world(c, f, {1, 4.2}), kOrange);           // rubble box
  EXPECT_EQ(at_world(c, f, {2, 4.2}), kOrange);           // rubble cylinder
  EXPECT_EQ(at_world(c, f, {4.85, 1}), kGreen);           // robot start, behind its heading
  EXPECT_EQ(at_world(c, f, {0.5, 4.5}), kFloor);          // empty floor between grid lines
  EXPECT_EQ(at_world(c, f, {3.5, 2.5}), kFloor);
}

TEST(WorldPlot, SmokeIsATranslucentGreyOverWhatLiesBeneath) {
  // smoke of 1 /m covers 60 % in grey (110, 110, 110): over the floor (250) that is
  // 250 + 0.6 * (110 - 250) = 166; over the victim the blue still shows through
  WorldSpec w = small_world();
  MediumSpec m;
  m.name = "smoke";
  m.density = 1.0;
  m.outline = {{1.5, 1.5}, {3.5, 1.5}, {3.5, 3.5}, {1.5, 3.5}};
  w.media.push_back(m);
  WorldPlotOptions o;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas c = plot_world(w, o);
  const Rgb8 grey = at_world(c, f, {3.2, 2.2});
  EXPECT_EQ(grey.r, grey.g);
  EXPECT_EQ(grey.g, grey.b);
  EXPECT_NEAR(grey.r, 166, 2);
  const Rgb8 victim = at_world(c, f, {2, 3});
  EXPECT_NE(victim, kBlue);
  EXPECT_GT(victim.b, victim.r + 20);
  EXPECT_EQ(at_world(c, f, {0.5, 4.5}), kFloor);  // outside it, the floor as before
}

TEST(WorldPlot, VictimHeadDotIsAtTheHeadEnd) {
  WorldSpec w = small_world();
  w.victims[0].pose.yaw = M_PI / 2;  // head to the north
  WorldPlotOptions o;
  o.legend = false;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas c = plot_world(w, o);
  EXPECT_EQ(at_world(c, f, {2, 3.68}), (Rgb8{255, 255, 255}));
  EXPECT_EQ(at_world(c, f, {2, 2.32}), kBlue);
}

TEST(WorldPlot, GridIsLightAndOptional) {
  const WorldSpec w = small_world();
  WorldPlotOptions o;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas with = plot_world(w, o);
  const Rgb8 line = at_world(with, f, {3.0, 4.5});  // on the x = 3 m grid line
  EXPECT_TRUE(line.r == line.g && line.g == line.b) << int(line.r);
  EXPECT_LT(line.r, 250);
  EXPECT_GT(line.r, 200);
  o.grid = false;
  const Canvas without = plot_world(w, o);
  EXPECT_EQ(at_world(without, f, {3.0, 4.5}), kFloor);
}

TEST(WorldPlot, CanvasMatchesFrameAndDrawWorldComposes) {
  const WorldSpec w = small_world();
  WorldPlotOptions o;
  o.legend = false;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas plotted = plot_world(w, o);
  EXPECT_EQ(plotted.width(), f.width());
  EXPECT_EQ(plotted.height(), f.height());
  // with no title or legend the plot is exactly the map drawn into a blank canvas
  Canvas composed(f.width(), f.height());
  draw_world(composed, f, w);
  EXPECT_EQ(composed.pixels(), plotted.pixels());
}

TEST(WorldPlot, TitleAndLegendGetTheirOwnRoom) {
  const WorldSpec w = small_world();
  WorldPlotOptions bare;
  bare.legend = false;
  WorldPlotOptions full;
  full.title = "Title";
  const PlotFrame fb = plot_frame_for(w, bare), ff = plot_frame_for(w, full);
  EXPECT_EQ(fb.px_per_m, 50);
  EXPECT_EQ(ff.px_per_m, 50);
  EXPECT_GT(ff.height(), fb.height() + 14);
  // the floor's north-west corner moves down below the title, and nothing is drawn in the
  // title band except the title's own dark pixels
  EXPECT_GT(ff.to_px({0, 5}).y(), fb.to_px({0, 5}).y() + 7);
  const Canvas c = plot_world(w, full);
  int title_px = 0;
  for (int y = 0; y < static_cast<int>(ff.to_px({0, 5}).y()) - 1; ++y) {
    for (int x = 0; x < c.width(); ++x) title_px += c.at(x, y).r < 128;
  }
  EXPECT_GT(title_px, 20);
  // the legend row under the map has the five colours
  int seen = 0;
  for (const Rgb8& col : {kBlack, kRed, kBlue, kOrange, kGreen}) {
    bool found = false;
    for (int y = static_cast<int>(ff.to_px({0, 0}).y()) + 2; y < c.height() && !found; ++y) {
      for (int x = 0; x < c.width() && !found; ++x) found = c.at(x, y) == col;
    }
    seen += found;
  }
  EXPECT_EQ(seen, 5);
}

TEST(WorldPlot, LegendWidensNarrowWorldsEvenly) {
  WorldSpec w;
  w.floor_min = {0, 0};
  w.floor_max = {2, 2};
  WorldPlotOptions o;
  const PlotFrame f = plot_frame_for(w, o);
  EXPECT_GT(f.width(), 2 * 50 + 2 * f.margin);
  // the floor is centred
  const double left = f.to_px({0, 0}).x(), right = f.width() - f.to_px({2, 0}).x();
  EXPECT_NEAR(left, right, 1.0);
}

TEST(WorldPlot, MaxSizeCapsTheLargerSide) {
  WorldSpec w;
  w.floor_min = {-10, 0};
  w.floor_max = {90, 40};
  for (bool extras : {false, true}) {
    WorldPlotOptions o;
    o.max_size_px = 1000;
    o.legend = extras;
    o.title = extras ? "capped" : "";
    const PlotFrame f = plot_frame_for(w, o);
    EXPECT_LT(f.px_per_m, 10.0);
    EXPECT_LE(f.width(), 1000);
    EXPECT_GE(f.width(), 990);
    EXPECT_LE(f.height(), 1000);
    const Canvas c = plot_world(w, o);
    EXPECT_EQ(c.width(), f.width());
  }
  // a tall world is capped on its height
  w.floor_max = {0, 300};
  WorldPlotOptions o;
  o.title = "tall";
  const PlotFrame f = plot_frame_for(w, o);
  EXPECT_LE(f.height(), 2000);
  EXPECT_GE(f.height(), 1990);
  // a small world keeps the requested resolution
  EXPECT_EQ(plot_frame_for(small_world()).px_per_m, 50);
}

TEST(WorldPlot, BadInputThrows) {
  const WorldSpec w = small_world();
  WorldPlotOptions o;
  o.px_per_m = 0;
  EXPECT_THROW(plot_frame_for(w, o), Error);
  o.px_per_m = std::nan("");
  EXPECT_THROW(plot_world(w, o), Error);
  o = {};
  o.max_size_px = 5;
  EXPECT_THROW(plot_world(w, o), Error);
  WorldSpec empty = w;
  empty.floor_max = empty.floor_min;
  EXPECT_THROW(plot_world(empty), Error);
}

TEST(WorldPlot, HostileGeometryDoesNotCrash) {
  WorldSpec w = small_world();
  WallSpec bad;
  bad.a = {std::nan(""), 1};
  bad.b = {1e200, -1e200};
  w.walls.push_back(bad);
  BlockSpec empty_block;
  w.blocks.push_back(empty_block);
  w.raised_areas[0].ramp_edges = {-1, 7, 2};
  const Canvas c = plot_world(w);
  EXPECT_GT(c.width(), 0);
  // a floor so far out that x + 1 == x in doubles still plots (and its grid terminates)
  WorldSpec far;
  far.floor_min = {1e17, 1e17};
  far.floor_max = {1e17 + 1e3, 1e17 + 1e3};
  EXPECT_LE(plot_world(far).width(), 2000);
}

TEST(WorldPlot, LegendWrapsOnSmallImages) {
  // at 250 px the legend does not fit one line; it wraps and stays inside the image
  const WorldSpec w = small_world();
  WorldPlotOptions o;
  o.max_size_px = 250;
  const PlotFrame f = plot_frame_for(w, o);
  const Canvas c = plot_world(w, o);
  EXPECT_LE(c.width(), 250);
  EXPECT_LE(c.height(), 250);
  const int map_bottom = static_cast<int>(f.to_px({0, 0}).y()) + 4;
  int rows_with_ink = 0;
  for (int y = map_bottom; y < c.height(); ++y) {
    bool ink = false;
    for (int x = 0; x < c.width(); ++x) ink = ink || c.at(x, y).r < 128;
    rows_with_ink += ink;
  }
  EXPECT_GT(rows_with_ink, 7 + 4);  // more than one line of 7 px text
}

}  // namespace
}  // namespace rescuesim
