// The SVG world loader against geometry worked out by hand: scale from units, the y flip,
// transforms, arcs, colour meanings, styles, clones, and errors that name the element.

#include <gtest/gtest.h>

#include <cmath>

#include "import/maze/maze.h"
#include "import/svg/svg_world.h"

namespace rescuesim {
namespace {

/// A drawing 10 m x 5 m at 100 units per metre: world (x, y) = (u / 100, (500 - v) / 100).
SvgLoadResult load(const std::string& body, const std::string& root_attrs = "width=\"10m\" height=\"5m\" viewBox=\"0 0 1000 500\"",
                   SvgLoadOptions o = {}) {
  return load_svg_world_from_string("<svg xmlns=\"http://www.w3.org/2000/svg\" " + root_attrs + ">\n" + body + "\n</svg>\n",
                                    "test.svg", o);
}

void expect_near(const Vec2& a, const Vec2& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
}

TEST(SvgWorld, PhysicalWidthSetsTheScaleAndYIsFlipped) {
  const auto r = load(R"svg(<line x1="100" y1="100" x2="300" y2="100" stroke="black" stroke-width="10"/>)svg");
  EXPECT_DOUBLE_EQ(r.metres_per_unit, 0.01);
  ASSERT_EQ(r.world.walls.size(), 1u);
  const auto& w = r.world.walls[0];
  // butt caps: the wall is exactly the segment, (1, 5 - 1) to (3, 4), 0.1 m thick
  expect_near(w.a, {1, 4});
  expect_near(w.b, {3, 4});
  EXPECT_NEAR(w.thickness, 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(w.height, 1.0);
  expect_near(r.world.floor_min, {0, 0});
  expect_near(r.world.floor_max, {10, 5});
}

TEST(SvgWorld, MillimetreDocumentsUseOneUnitPerMillimetre) {
  const auto r = load(R"svg(<line x1="10" y1="287" x2="110" y2="287" stroke="#000" stroke-width="2"/>)svg",
                      R"svg(width="210mm" height="297mm" viewBox="0 0 210 297")svg");
  ASSERT_EQ(r.world.walls.size(), 1u);
  expect_near(r.world.walls[0].a, {0.010, 0.010});
  expect_near(r.world.walls[0].b, {0.110, 0.010});
  EXPECT_NEAR(r.world.walls[0].thickness, 0.002, 1e-12);
}

TEST(SvgWorld, UnitlessDocumentsUseTheScaleSetting) {
  SvgLoadOptions o;
  o.units_per_metre = 50;
  const auto r = load(R"svg(<line x1="0" y1="50" x2="100" y2="50" stroke="black"/>)svg", R"svg(viewBox="0 0 200 100")svg", o);
  EXPECT_DOUBLE_EQ(r.metres_per_unit, 0.02);
  expect_near(r.world.floor_max, {4, 2});
  expect_near(r.world.walls[0].a, {0, 1});
  expect_near(r.world.walls[0].b, {2, 1});
}

TEST(SvgWorld, NestedTransformsCompose) {
  // rotate(90) maps (100, 0) to (0, 100); the translate then adds (100, 0):
  // the line runs from (100, 0) to (100, 100) in user units, i.e. (1, 5) to (1, 4) in metres
  const auto r = load(R"svg(<g transform="translate(100,0)"><g transform="rotate(90)">
      <line x1="0" y1="0" x2="100" y2="0" stroke="black" stroke-width="4"/></g></g>)svg");
  ASSERT_EQ(r.world.walls.size(), 1u);
  expect_near(r.world.walls[0].a, {1, 5});
  expect_near(r.world.walls[0].b, {1, 4});
  EXPECT_NEAR(r.world.walls[0].thickness, 0.04, 1e-12);
}

TEST(SvgWorld, ScaledGroupScalesStrokeWidth) {
  const auto r = load(R"svg(<g transform="scale(2)"><line x1="10" y1="10" x2="60" y2="10" stroke="black" stroke-width="3"/></g>)svg");
  ASSERT_EQ(r.world.walls.size(), 1u);
  expect_near(r.world.walls[0].a, {0.2, 4.8});
  expect_near(r.world.walls[0].b, {1.2, 4.8});
  EXPECT_NEAR(r.world.walls[0].thickness, 0.06, 1e-12);
}

TEST(SvgWorld, ArcWallFollowsTheCircle) {
  // a half circle of radius 100 around (200, 200), sweeping through (200, 100) at the top of the
  // page: world centre (2, 3), radius 1 m, passing (2, 4)
  const auto r = load(R"svg(<path d="M 100 200 A 100 100 0 0 1 300 200" fill="none" stroke="black" stroke-width="2"/>)svg");
  ASSERT_GT(r.world.walls.size(), 8u);
  double top = -1;
  for (const auto& w : r.world.walls) {
    // wall centre lines are chords of the circle, extended by half the stroke width at joints
    const Vec2 mid = 0.5 * (w.a + w.b);
    EXPECT_LE((mid - Vec2(2, 3)).norm(), 1.0 + 1e-9);
    EXPECT_GE((mid - Vec2(2, 3)).norm(), 1.0 - 0.005 - 1e-9);
    top = std::max(top, std::max(w.a.y(), w.b.y()));
  }
  EXPECT_NEAR(top, 4.0, 0.011);
}

TEST(SvgWorld, PolylineWallsOverlapAtCorners) {
  const auto r = load(R"svg(<polyline points="100,100 300,100 300,300" fill="none" stroke="black" stroke-width="10"/>)svg");
  ASSERT_EQ(r.world.walls.size(), 2u);
  // the first wall keeps its free end and extends 5 cm past the corner; the second starts 5 cm before it
  expect_near(r.world.walls[0].a, {1, 4});
  expect_near(r.world.walls[0].b, {3.05, 4});
  expect_near(r.world.walls[1].a, {3, 4.05});
  expect_near(r.world.walls[1].b, {3, 2});
}

TEST(SvgWorld, SquareCapsExtendTheEnds) {
  const auto r = load(R"svg(<line x1="100" y1="100" x2="300" y2="100" stroke="black" stroke-width="10" stroke-linecap="square"/>)svg");
  expect_near(r.world.walls[0].a, {0.95, 4});
  expect_near(r.world.walls[0].b, {3.05, 4});
}

TEST(SvgWorld, ClosedStrokedRectangleMakesFourWalls) {
  const auto r = load(R"svg(<rect x="0" y="0" width="1000" height="500" fill="none" stroke="black" stroke-width="10"/>)svg");
  EXPECT_EQ(r.world.walls.size(), 4u);
  EXPECT_TRUE(r.world.blocks.empty());
}

TEST(SvgWorld, FilledBlackShapeIsASolidBlock) {
  const auto r = load(R"svg(<rect x="100" y="100" width="200" height="100" data-height="0.5"/>)svg");  // default fill is black
  ASSERT_EQ(r.world.blocks.size(), 1u);
  const auto& b = r.world.blocks[0];
  EXPECT_NEAR(signed_area(b.outline), 2.0 * 1.0, 1e-9);  // counter-clockwise, 2 m x 1 m
  const Box2 box = bounds(b.outline);
  expect_near(box.min, {1, 3});
  expect_near(box.max, {3, 4});
  EXPECT_DOUBLE_EQ(b.height, 0.5);
  EXPECT_TRUE(r.world.walls.empty());
}

TEST(SvgWorld, RedFillWithInkscapesBlackStrokeIsOnlyARaisedArea) {
  const auto r = load(R"svg(<rect x="400" y="200" width="100" height="100" style="fill:#ff0000;stroke:#000000;stroke-width:1"/>)svg");
  EXPECT_TRUE(r.world.walls.empty());
  ASSERT_EQ(r.world.raised_areas.size(), 1u);
  const auto& ra = r.world.raised_areas[0];
  EXPECT_EQ(ra.ramp_edges.size(), 4u);  // default: ramps all round
  EXPECT_DOUBLE_EQ(ra.height, 0.12);
  EXPECT_NEAR(signed_area(ra.outline), 1.0, 1e-9);
}

TEST(SvgWorld, RampsOnNamedSidesPointOutward) {
  const auto r = load(R"svg(<rect x="400" y="200" width="100" height="100" fill="red" data-ramps="north, w" data-ramp-length="0.3"/>)svg");
  const auto& ra = r.world.raised_areas.at(0);
  ASSERT_EQ(ra.ramp_edges.size(), 2u);
  bool north = false, west = false;
  for (int e : ra.ramp_edges) {
    // the ramp is a quad whose far edge lies 0.3 m out from the platform edge
    const Box2 rb = bounds(WorldSpec::ramp_outline(ra, e));
    if (std::abs(rb.max.y() - 3.3) < 1e-9) north = true;  // platform top edge y = 3, ramp to 3.3
    if (std::abs(rb.min.x() - 3.7) < 1e-9) west = true;   // platform west edge x = 4, ramp to 3.7
  }
  EXPECT_TRUE(north);
  EXPECT_TRUE(west);
}

TEST(SvgWorld, ElongatedBlueShapeIsTheVictimsBody) {
  // a 1.5 m x 0.4 m rectangle rotated -30 deg on the page: +30 deg (counter-clockwise) in the world
  const auto r = load(
      R"svg(<rect x="425" y="230" width="150" height="40" fill="blue" transform="rotate(-30 500 250)"
                  data-posture="lying" data-temperature="37C"/>)svg");
  ASSERT_EQ(r.world.victims.size(), 1u);
  const auto& v = r.world.victims[0];
  expect_near(v.pose.position(), {5, 2.5}, 1e-9);
  EXPECT_NEAR(v.length, 1.5, 1e-9);
  EXPECT_NEAR(v.width, 0.4, 1e-9);
  EXPECT_NEAR(std::fmod(v.pose.yaw + 2 * M_PI, M_PI), M_PI / 6, 1e-9);
  EXPECT_NEAR(v.skin_temperature, 310.15, 1e-9);
  EXPECT_EQ(v.posture, VictimSpec::Posture::lying);
}

TEST(SvgWorld, SquareBlueMarkerGetsTheDefaultSize) {
  const auto r = load(R"svg(<circle cx="300" cy="300" r="20" fill="#2850c8" data-posture="sitting" id="anna"/>)svg");
  ASSERT_EQ(r.world.victims.size(), 1u);
  const auto& v = r.world.victims[0];
  expect_near(v.pose.position(), {3, 2});
  EXPECT_DOUBLE_EQ(v.length, 1.2);
  EXPECT_EQ(v.posture, VictimSpec::Posture::sitting);
  EXPECT_EQ(v.name, "anna");
}

TEST(SvgWorld, GreenCircleWithLineGivesStartAndHeading) {
  // the line goes up the page from the circle's centre: north, yaw = 90 deg
  const auto r = load(R"svg(<circle cx="100" cy="400" r="25" fill="green"/>
      <line x1="100" y1="400" x2="100" y2="340" stroke="#00ff00" stroke-width="4"/>)svg");
  ASSERT_EQ(r.world.robots.size(), 1u);
  expect_near(r.world.robots[0].start.position(), {1, 1});
  EXPECT_NEAR(r.world.robots[0].start.yaw, M_PI / 2, 1e-9);
  EXPECT_EQ(r.world.robots[0].name, "robot");
  EXPECT_EQ(r.world.robots[0].model, "rescue_robot");
}

TEST(SvgWorld, RubbleBoxAndCylinder) {
  const auto r = load(R"svg(<rect x="600" y="100" width="20" height="10" fill="orange" data-height="0.1"/>
      <circle cx="700" cy="100" r="10" fill="#ffd700" data-height="0.3" data-mass="5"/>)svg");
  ASSERT_EQ(r.world.rubble.size(), 2u);
  const auto& box = r.world.rubble[0];
  EXPECT_EQ(box.shape, RubbleSpec::Shape::box);
  expect_near(box.pose.position(), {6.1, 3.95});
  EXPECT_NEAR(box.size.x() * box.size.y(), 0.2 * 0.1, 1e-12);
  EXPECT_NEAR(box.mass, 0.2 * 0.1 * 0.1 * 400, 1e-9);  // volume x 400 kg/m^3
  const auto& cyl = r.world.rubble[1];
  EXPECT_EQ(cyl.shape, RubbleSpec::Shape::cylinder);
  EXPECT_NEAR(cyl.size.x(), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(cyl.mass, 5);
}

TEST(SvgWorld, UnknownColourWarnsNamingTheElement) {
  const auto r = load(R"svg(<rect id="mystery" x="10" y="10" width="50" height="50" fill="#808080"/>)svg");
  ASSERT_EQ(r.diagnostics.warning_count(), 1);
  const std::string msg = r.diagnostics.items()[0].str();
  EXPECT_NE(msg.find("<rect id=\"mystery\">"), std::string::npos) << msg;
  EXPECT_NE(msg.find("#808080"), std::string::npos) << msg;
  EXPECT_NE(msg.find("test.svg:2"), std::string::npos) << msg;
}

TEST(SvgWorld, WhiteBackgroundIsSilentlyIgnored) {
  const auto r = load(R"svg(<rect width="1000" height="500" fill="#ffffff"/>)svg");
  EXPECT_TRUE(r.diagnostics.items().empty());
  EXPECT_TRUE(r.world.blocks.empty());
}

TEST(SvgWorld, StyleSheetsClassesAndInheritance) {
  const auto r = load(R"svg(<style>.wall { stroke: #000; stroke-width: 6 } #v1 { fill: blue }</style>
      <g class="wall" fill="none"><line x1="0" y1="0" x2="100" y2="0"/><line x1="0" y1="100" x2="100" y2="100"/></g>
      <circle id="v1" cx="500" cy="250" r="10"/>)svg");
  EXPECT_EQ(r.world.walls.size(), 2u);
  EXPECT_NEAR(r.world.walls.at(0).thickness, 0.06, 1e-12);
  EXPECT_EQ(r.world.victims.size(), 1u);
}

TEST(SvgWorld, UseClonesAreDrawnAtTheirOffset) {
  const auto r = load(R"svg(<defs><line id="seg" x1="0" y1="0" x2="100" y2="0" stroke="black" stroke-width="5"/></defs>
      <use href="#seg" x="200" y="100"/><use xlink:href="#seg" x="200" y="200"/>)svg");
  ASSERT_EQ(r.world.walls.size(), 2u);
  expect_near(r.world.walls[0].a, {2, 4});
  expect_near(r.world.walls[1].a, {2, 3});
}

TEST(SvgWorld, HiddenElementsAreSkipped) {
  const auto r = load(R"svg(<g style="display:none"><line x1="0" y1="0" x2="100" y2="0" stroke="black"/></g>
      <line x1="0" y1="0" x2="100" y2="0" stroke="black" visibility="hidden"/>
      <line x1="0" y1="50" x2="100" y2="50" stroke="black"/>)svg");
  EXPECT_EQ(r.world.walls.size(), 1u);
}

TEST(SvgWorld, DataKindOverridesColour) {
  const auto r = load(R"svg(<rect x="100" y="100" width="50" height="50" fill="#808080" data-kind="rubble"/>)svg");
  EXPECT_EQ(r.world.rubble.size(), 1u);
  EXPECT_TRUE(r.diagnostics.items().empty());
}

TEST(SvgWorld, BadDataValueNamesTheAttribute) {
  try {
    load(R"svg(<rect id="r1" x="100" y="100" width="50" height="50" fill="red" data-height="tall"/>)svg");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("<rect id=\"r1\"> attribute data-height"), std::string::npos) << msg;
    EXPECT_EQ(e.where().line, 2);
  }
}

TEST(SvgWorld, BadTransformNamesTheAttribute) {
  try {
    load(R"svg(<line x1="0" y1="0" x2="1" y2="0" stroke="black" transform="rotate(30"/>)svg");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("attribute transform"), std::string::npos) << e.what();
  }
}

TEST(SvgWorld, SelfReferencingUseIsAnError) {
  EXPECT_THROW(load(R"svg(<g id="loop"><use href="#loop"/></g>)svg"), Error);
}

TEST(SvgWorld, MazeRoundTripPreservesEverything) {
  MazeOptions o;
  o.cols = 9;
  o.rows = 7;
  o.seed = 1234;
  o.loop_fraction = 0.2;
  o.victims = 4;
  o.rubble = 10;
  o.raised_fraction = 0.1;
  const WorldSpec before = maze_to_world(generate_maze(o));
  const std::string text = world_to_svg(before);
  const SvgLoadResult r = load_svg_world_from_string(text, "maze.svg");
  const WorldSpec& after = r.world;
  EXPECT_TRUE(r.diagnostics.items().empty());
  EXPECT_EQ(after.seed, before.seed);
  EXPECT_EQ(after.metadata, before.metadata);
  expect_near(after.floor_min, before.floor_min);
  expect_near(after.floor_max, before.floor_max);
  ASSERT_EQ(after.walls.size(), before.walls.size());
  for (std::size_t i = 0; i < before.walls.size(); ++i) {
    expect_near(after.walls[i].a, before.walls[i].a, 1e-9);
    expect_near(after.walls[i].b, before.walls[i].b, 1e-9);
    EXPECT_NEAR(after.walls[i].thickness, before.walls[i].thickness, 1e-12);
    EXPECT_NEAR(after.walls[i].height, before.walls[i].height, 1e-12);
  }
  ASSERT_EQ(after.raised_areas.size(), before.raised_areas.size());
  for (std::size_t i = 0; i < before.raised_areas.size(); ++i) {
    EXPECT_EQ(after.raised_areas[i].ramp_edges, before.raised_areas[i].ramp_edges);
    ASSERT_EQ(after.raised_areas[i].outline.size(), before.raised_areas[i].outline.size());
    for (std::size_t k = 0; k < before.raised_areas[i].outline.size(); ++k) {
      expect_near(after.raised_areas[i].outline[k], before.raised_areas[i].outline[k], 1e-9);
    }
  }
  ASSERT_EQ(after.victims.size(), before.victims.size());
  for (std::size_t i = 0; i < before.victims.size(); ++i) {
    // the file keeps a micrometre of precision
    expect_near(after.victims[i].pose.position(), before.victims[i].pose.position(), 1e-6);
    EXPECT_NEAR(wrap_angle(after.victims[i].pose.yaw - before.victims[i].pose.yaw), 0, 1e-6);
    EXPECT_NEAR(after.victims[i].length, before.victims[i].length, 1e-6);
    EXPECT_EQ(after.victims[i].name, before.victims[i].name);
  }
  ASSERT_EQ(after.rubble.size(), before.rubble.size());
  for (std::size_t i = 0; i < before.rubble.size(); ++i) {
    EXPECT_EQ(after.rubble[i].shape, before.rubble[i].shape);
    expect_near(after.rubble[i].pose.position(), before.rubble[i].pose.position(), 1e-6);
    EXPECT_NEAR(after.rubble[i].size.z(), before.rubble[i].size.z(), 1e-6);
    EXPECT_NEAR(after.rubble[i].mass, before.rubble[i].mass, 1e-4);
    EXPECT_NEAR(after.rubble[i].size.x() * after.rubble[i].size.y(), before.rubble[i].size.x() * before.rubble[i].size.y(), 1e-6);
  }
  ASSERT_EQ(after.robots.size(), 1u);
  expect_near(after.robots[0].start.position(), before.robots[0].start.position(), 1e-6);
  EXPECT_NEAR(after.robots[0].start.yaw, before.robots[0].start.yaw, 1e-6);
  // walls, raised areas and victims are axis-aligned in a maze, so their text survives exactly
  const std::string again = world_to_svg(after);
  EXPECT_EQ(again.substr(0, again.find("<g id=\"rubble\"")), text.substr(0, text.find("<g id=\"rubble\"")));
}

}  // namespace
}  // namespace rescuesim
