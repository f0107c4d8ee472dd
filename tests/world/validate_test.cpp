// validate() catches each class of impossible world and names the element concerned.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "world/world_spec.h"

namespace rescuesim {
namespace {

/// A valid 6 m x 4 m room: four walls, a robot in the middle, one victim.
WorldSpec room() {
  WorldSpec w;
  w.floor_max = {6, 4};
  w.materials = default_materials();
  const double t = 0.1;
  w.walls = {{{0, 0}, {6, 0}, t, 1, "wall", {"room.svg", 3, "<line id=\"s\">"}},
             {{6, 0}, {6, 4}, t, 1, "wall", {"room.svg", 4, "<line id=\"e\">"}},
             {{6, 4}, {0, 4}, t, 1, "wall", {"room.svg", 5, "<line id=\"n\">"}},
             {{0, 4}, {0, 0}, t, 1, "wall", {"room.svg", 6, "<line id=\"w\">"}}};
  RobotPlacement r;
  r.start = {3, 2, 0};
  w.robots.push_back(r);
  VictimSpec v;
  v.pose = {1.5, 1.0, 0};
  v.length = 1.2;
  w.victims.push_back(v);
  return w;
}

bool mentions(const Diagnostics& d, const std::string& text) {
  for (const auto& i : d.items()) {
    if (i.str().find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(Validate, AValidRoomHasNoProblems) {
  const Diagnostics d = validate(room());
  EXPECT_TRUE(d.items().empty()) << (d.items().empty() ? "" : d.items()[0].str());
}

TEST(Validate, EmptyWorldIsAnError) {
  WorldSpec w = room();
  w.walls.clear();
  w.victims.clear();
  const Diagnostics d = validate(w);
  EXPECT_TRUE(d.has_errors());
  EXPECT_TRUE(mentions(d, "empty"));
}

TEST(Validate, StartTooCloseToAWallNamesTheWall) {
  WorldSpec w = room();
  w.robots[0].start = {3, 0.3, 0};  // 0.25 m from the inner face of the south wall
  const Diagnostics d = validate(w);
  EXPECT_TRUE(d.has_errors());
  EXPECT_TRUE(mentions(d, "<line id=\"s\"> (line 3)")) << d.items()[0].str();
}

TEST(Validate, VictimInsideAWallIsAnError) {
  WorldSpec w = room();
  w.victims[0].pose = {6.0, 2.0, 0};
  const Diagnostics d = validate(w);
  EXPECT_TRUE(d.has_errors());
  EXPECT_TRUE(mentions(d, "victim lies inside <line id=\"e\">"));
}

TEST(Validate, NonPositiveSizesAreErrors) {
  WorldSpec w = room();
  w.walls[0].thickness = 0;
  w.walls[1].height = -1;
  w.victims[0].width = 0;
  const Diagnostics d = validate(w);
  EXPECT_EQ(d.error_count(), 3);
  EXPECT_TRUE(mentions(d, "thickness 0 m is not positive"));
  EXPECT_TRUE(mentions(d, "height -1 m is not positive"));
}

TEST(Validate, NanAnywhereIsAnError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WorldSpec w = room();
  w.walls[2].a.x() = nan;
  w.robots[0].start.yaw = nan;
  RubbleSpec r;
  r.pose = {2, 2, 0};
  r.mass = nan;
  w.rubble.push_back(r);
  const Diagnostics d = validate(w);
  EXPECT_EQ(d.error_count(), 3);
}

TEST(Validate, ObstacleMustBeASimplePolygon) {
  WorldSpec w = room();
  w.blocks.push_back({{{1, 1}, {2, 2}, {2, 1}, {1, 2}}, 1, "obstacle", {}});  // a bow tie
  const Diagnostics d = validate(w);
  EXPECT_TRUE(mentions(d, "crosses itself"));
}

TEST(Validate, RampOnAMissingEdgeIsAnError) {
  WorldSpec w = room();
  RaisedAreaSpec r;
  r.outline = {{4, 1}, {5, 1}, {5, 2}, {4, 2}};
  r.ramp_edges = {0, 4};
  w.raised_areas.push_back(r);
  EXPECT_TRUE(mentions(validate(w), "ramp on edge 4"));
}

TEST(Validate, UnknownMaterialIsAnError) {
  WorldSpec w = room();
  w.walls[0].material = "marble";
  EXPECT_TRUE(mentions(validate(w), "unknown material 'marble'"));
}

TEST(Validate, OutsideTheFloorIsAWarningNotAnError) {
  WorldSpec w = room();
  w.walls.push_back({{7, 1}, {8, 1}, 0.1, 1, "wall", {}});
  const Diagnostics d = validate(w);
  EXPECT_FALSE(d.has_errors());
  EXPECT_EQ(d.warning_count(), 1);
}

TEST(Validate, TwoRobotsOnTopOfEachOther) {
  WorldSpec w = room();
  RobotPlacement b;
  b.name = "robot2";
  b.start = {3.2, 2, 0};
  w.robots.push_back(b);
  EXPECT_TRUE(mentions(validate(w), "overlaps robot 'robot'"));
}

}  // namespace
}  // namespace rescuesim
