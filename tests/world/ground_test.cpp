// Ground materials per area (docs/terrain.md, "Ground materials"): floor patches drawn in an SVG
// (data-kind="ground") or listed in a scenario (world.ground), compiled into the World with their
// materials, written back the same, and refused with the file, line and element when a material
// is unknown or missing, a footprint has no area, or two patches overlap.

#include <gtest/gtest.h>

#include <cmath>

#include "import/scenario/scenario.h"
#include "import/svg/svg_world.h"
#include "robots/rescue_robot.h"
#include "world/world.h"

namespace rescuesim {
namespace {

/// A drawing 10 m x 5 m at 100 units per metre: world (x, y) = (u / 100, (500 - v) / 100). A
/// wall keeps the world from being empty.
SvgLoadResult load(const std::string& body) {
  return load_svg_world_from_string("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10m\" height=\"5m\" viewBox=\"0 0 1000 500\">\n" +
                                        body +
                                        "\n<line x1=\"0\" y1=\"0\" x2=\"1000\" y2=\"0\" stroke=\"#000\" stroke-width=\"5\"/>\n</svg>\n",
                                    "ground.svg");
}

std::string load_error(const std::string& body) {
  try {
    load(body);
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

/// Every diagnostic, one per line.
std::string format(const Diagnostics& d) {
  std::string out;
  for (const auto& item : d.items()) out += item.str() + "\n";
  return out;
}

std::string problems(const std::string& body) { return format(validate(load(body).world)); }

TEST(Ground, BuiltInMaterialsHaveTheirRubberFrictions) {
  // the coefficient against rubber (robot_wheel, 1.0): Bullet multiplies the two
  const std::vector<MaterialSpec> m = default_materials();
  const auto find = [&](const std::string& name) {
    for (const auto& x : m) {
      if (x.name == name) return x;
    }
    ADD_FAILURE() << name;
    return MaterialSpec{};
  };
  EXPECT_DOUBLE_EQ(find("robot_wheel").friction, 1.0);
  EXPECT_DOUBLE_EQ(find("concrete").friction, 0.8);
  EXPECT_DOUBLE_EQ(find("wood").friction, 0.6);
  EXPECT_DOUBLE_EQ(find("sand").friction, 0.4);
  EXPECT_DOUBLE_EQ(find("wet_tiles").friction, 0.25);
  EXPECT_EQ(find("sand").texture, "concrete");
  EXPECT_EQ(find("wet_tiles").texture, "tiles");
  EXPECT_LT(find("wet_tiles").roughness, find("floor").roughness);  // a wet sheen
  EXPECT_EQ(m[7].name, "robot_body");  // the older materials keep their places
}

TEST(Ground, SvgAreasBecomeFloorPatchesAndWriteBackTheSame) {
  const auto r = load(R"svg(
  <rect x="100" y="100" width="200" height="100" data-kind="ground" data-material="sand" id="pit"/>
  <polygon points="300,100 500,100 400,200" data-kind="ground" data-material="wet_tiles"/>)svg");
  ASSERT_EQ(r.world.ground.size(), 2u);
  const GroundAreaSpec& pit = r.world.ground[0];
  EXPECT_EQ(pit.name, "pit");
  EXPECT_EQ(pit.material, "sand");
  EXPECT_NEAR(signed_area(pit.outline), 2.0, 1e-9);  // 2 x 1 m, counter-clockwise
  EXPECT_NEAR(bounds(pit.outline).min.x(), 1.0, 1e-9);
  EXPECT_NEAR(bounds(pit.outline).min.y(), 3.0, 1e-9);  // 5 - 200 / 100
  EXPECT_EQ(r.world.ground[1].name, "wet_tiles_2");
  EXPECT_NEAR(signed_area(r.world.ground[1].outline), 1.0, 1e-9);  // base 2 m, height 1 m
  EXPECT_FALSE(validate(r.world).has_errors());
  // patches edge to edge (the rect's east edge and the triangle's west corner) do not overlap

  const World w = compile_world(r.world, builtin_models());
  ASSERT_EQ(w.ground.size(), 2u);
  EXPECT_EQ(w.materials[static_cast<std::size_t>(w.ground[0].material)].name, "sand");
  EXPECT_EQ(w.statics.size(), compile_world(load("").world, builtin_models()).statics.size());  // no solids

  const auto again = load_svg_world_from_string(world_to_svg(r.world), "again.svg");
  ASSERT_EQ(again.world.ground.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again.world.ground[i].name, r.world.ground[i].name);
    EXPECT_EQ(again.world.ground[i].material, r.world.ground[i].material);
    EXPECT_NEAR(signed_area(again.world.ground[i].outline), signed_area(r.world.ground[i].outline), 1e-6);
  }
}

// A fill pattern named after a ground material makes a ground area without data-kind, as a
// drawing program paints floor patches: url(#sand) for the four ground materials, url(#ground-NAME)
// for any material (here from a group's fill). Other patterns keep their fallback colour's
// meaning; a ground- pattern naming no material is an error at the element.
TEST(Ground, FillPatternsNamedAfterAMaterialAreGroundAreas) {
  const auto r = load(R"svg(
  <defs><pattern id="sand" width="10" height="10" patternUnits="userSpaceOnUse"><circle cx="5" cy="5" r="2" fill="#c2b280"/></pattern>
        <pattern id="ground-wood" width="10" height="10"/><pattern id="hatch" width="10" height="10"/></defs>
  <rect id="dune" x="100" y="100" width="200" height="100" fill="url(#sand)"/>
  <g fill="url(#ground-wood) #a0522d"><rect x="400" y="100" width="100" height="100"/></g>
  <rect x="600" y="100" width="100" height="100" fill="url(#hatch) #000"/>)svg");
  ASSERT_EQ(r.world.ground.size(), 2u);
  EXPECT_EQ(r.world.ground[0].name, "dune");
  EXPECT_EQ(r.world.ground[0].material, "sand");
  EXPECT_NEAR(signed_area(r.world.ground[0].outline), 2.0, 1e-9);
  EXPECT_EQ(r.world.ground[1].material, "wood");
  EXPECT_NEAR(signed_area(r.world.ground[1].outline), 1.0, 1e-9);
  // the hatched black rect is a wall block, as its fallback colour says
  EXPECT_EQ(r.world.blocks.size(), 1u);
  const std::string e = load_error(R"svg(<rect x="100" y="100" width="200" height="100" fill="url(#ground-lava)"/>)svg");
  EXPECT_NE(e.find("ground.svg:2: <rect> attribute fill"), std::string::npos) << e;
  EXPECT_NE(e.find("fill pattern '#ground-lava' names unknown material 'lava'"), std::string::npos) << e;
}

TEST(Ground, AnUnknownMaterialNamesTheElementAndTheKnownOnes) {
  const std::string e = load_error(R"svg(<rect x="100" y="100" width="200" height="100" data-kind="ground" data-material="lava"/>)svg");
  EXPECT_NE(e.find("ground.svg:2"), std::string::npos) << e;
  EXPECT_NE(e.find("data-material"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown material 'lava'"), std::string::npos) << e;
  EXPECT_NE(e.find("wet_tiles"), std::string::npos) << e;
}

TEST(Ground, AnAreaWithoutMaterialIsAnError) {
  const std::string e = load_error(R"svg(<rect x="100" y="100" width="200" height="100" data-kind="ground"/>)svg");
  EXPECT_NE(e.find("ground.svg:2: <rect>"), std::string::npos) << e;
  EXPECT_NE(e.find("a ground area needs data-material"), std::string::npos) << e;
}

TEST(Ground, AFootprintWithoutAreaIsAnError) {
  const std::string line = load_error(R"svg(<polyline points="100,100 300,100 500,100" data-kind="ground" data-material="sand"/>)svg");
  EXPECT_NE(line.find("ground.svg:2"), std::string::npos) << line;
  EXPECT_NE(line.find("needs a footprint with an area"), std::string::npos) << line;
  // a rect of negative width is an error of the drawing (one of zero width, which SVG does not
  // draw, is left out with a warning, as for any rect)
  const std::string negative =
      load_error(R"svg(<rect x="100" y="100" width="-200" height="100" data-kind="ground" data-material="sand"/>)svg");
  EXPECT_NE(negative.find("ground.svg:2"), std::string::npos) << negative;
  EXPECT_NE(negative.find("negative width or height"), std::string::npos) << negative;
  // a spec built in code: validation names it
  WorldSpec w = load("").world;
  w.ground.push_back({"thin", {{0, 0}, {1, 0}, {2, 0}}, "sand", {}});
  const std::string d = format(validate(w));
  EXPECT_NE(d.find("ground area 'thin'"), std::string::npos) << d;
  EXPECT_NE(d.find("footprint has no area"), std::string::npos) << d;
}

TEST(Ground, OverlappingAreasAreAnErrorNamingBoth) {
  const std::string e = problems(R"svg(
  <rect x="100" y="100" width="200" height="100" data-kind="ground" data-material="sand" id="a"/>
  <rect x="250" y="150" width="200" height="100" data-kind="ground" data-material="wood" id="b"/>)svg");
  EXPECT_NE(e.find("ground.svg:4: <rect id=\"b\">"), std::string::npos) << e;
  EXPECT_NE(e.find("overlaps ground area 'a' (line 3)"), std::string::npos) << e;
  // side by side is fine
  EXPECT_EQ(problems(R"svg(
  <rect x="100" y="100" width="200" height="100" data-kind="ground" data-material="sand"/>
  <rect x="300" y="100" width="200" height="100" data-kind="ground" data-material="wood"/>)svg"),
            "");
}

const char* kMaze = "world:\n  maze:\n    cols: 4\n    rows: 4\n  ground:\n";

TEST(Ground, AScenarioListsAreasForAnyWorld) {
  const Scenario s = parse_scenario(std::string(kMaze) +
                                        "    - material: wet_tiles\n"
                                        "      name: spill\n"
                                        "      outline: [[1, 1], [1, 2], [3, 2], [3, 1]]\n"  // clockwise: turned round
                                        "    - material: sand\n"
                                        "      outline: [[0, 0], [1, 0], [0, 1]]\n",
                                    "s.yaml", builtin_models());
  const WorldSpec w = build_world(s);
  ASSERT_EQ(w.ground.size(), 2u);
  EXPECT_EQ(w.ground[0].name, "spill");
  EXPECT_EQ(w.ground[0].material, "wet_tiles");
  EXPECT_NEAR(signed_area(w.ground[0].outline), 2.0, 1e-12);
  EXPECT_EQ(w.ground[0].source.line, 6);
  EXPECT_EQ(w.ground[1].name, "sand_2");
  EXPECT_FALSE(validate(w).has_errors());
}

TEST(Ground, AScenarioAreaNeedsAKnownMaterial) {
  const auto error_of = [](const std::string& yaml) {
    try {
      parse_scenario(yaml, "s.yaml", builtin_models());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(parsed)");
  };
  const std::string unknown = error_of(std::string(kMaze) + "    - material: ice\n      outline: [[0, 0], [1, 0], [0, 1]]\n");
  EXPECT_NE(unknown.find("s.yaml:6"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("unknown material 'ice'"), std::string::npos) << unknown;
  const std::string missing = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n");
  EXPECT_NE(missing.find("s.yaml:6"), std::string::npos) << missing;
  EXPECT_NE(missing.find("needs a material"), std::string::npos) << missing;
  const std::string two = error_of(std::string(kMaze) + "    - material: sand\n      outline: [[0, 0], [1, 0]]\n");
  EXPECT_NE(two.find("expected at least 3"), std::string::npos) << two;
}

}  // namespace
}  // namespace rescuesim
