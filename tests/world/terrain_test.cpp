// Test-method terrain (world/terrain.h) against dimensions worked out by hand: stepfield posts,
// stair treads from the slope, crossing-ramp rises, gap decks; read from SVG, written back, and
// refused with a message naming the element when it cannot be built.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "import/svg/svg_world.h"
#include "world/terrain.h"

namespace rescuesim {
namespace {

using Kind = TerrainSpec::Kind;

TerrainSpec element(Kind kind, double length, double width) {
  TerrainSpec t = TerrainSpec::defaults(kind);
  t.name = std::string(1, 't');  // (not = "t": GCC 12 warns falsely of an overflow there, -Wstringop-overflow)
  t.length = length;
  t.width = width;
  return t;
}

/// Height of a solid's top: a box's centre plus half its height, a wedge's highest vertex.
double top(const TerrainSolid& s) {
  if (s.geometry.type == Geometry::Type::box) return s.X_WS.p.z() + 0.5 * s.geometry.size.z();
  double z = 0;
  for (const Vec3& v : s.geometry.mesh.vertices) z = std::max(z, (s.X_WS * v).z());
  return z;
}

TEST(Terrain, AStepfieldIsAGridOfPostsOneToFourHalfPostsHigh) {
  TerrainSpec t = element(Kind::stepfield, 1.2, 0.6);  // 12 x 6 posts of 10 cm
  const auto solids = terrain_solids(t);
  ASSERT_EQ(solids.size(), 72u);
  std::set<long> heights;
  for (const auto& s : solids) {
    EXPECT_EQ(s.geometry.type, Geometry::Type::box);
    EXPECT_NEAR(s.geometry.size.x(), 0.1, 1e-12);
    EXPECT_NEAR(s.geometry.size.y(), 0.1, 1e-12);
    heights.insert(std::lround(top(s) * 1000));
    EXPECT_NEAR(s.X_WS.p.z(), 0.5 * top(s), 1e-12);  // standing on the floor
  }
  EXPECT_EQ(heights, (std::set<long>{50, 100, 150, 200}));
  // the first post's centre: half a post in from the footprint's corner (-0.6, -0.3)
  EXPECT_NEAR(solids[0].X_WS.p.x(), -0.55, 1e-12);
  EXPECT_NEAR(solids[0].X_WS.p.y(), -0.25, 1e-12);
  // the seed decides the heights: the same seed the same field, another seed another
  EXPECT_EQ(stepfield_heights(t, 12, 6), stepfield_heights(t, 12, 6));
  TerrainSpec other = t;
  other.seed = 2;
  EXPECT_NE(stepfield_heights(other, 12, 6), stepfield_heights(t, 12, 6));
  // full-cubic: whole posts, 10-40 cm
  t.half_cubic = false;
  for (double h : stepfield_heights(t, 12, 6)) EXPECT_TRUE(h == 0.1 || h == 0.2 || h == 0.30000000000000004 || h == 0.4) << h;
}

TEST(Terrain, StairsTreadsFollowFromTheSlopeAndTheRiser) {
  TerrainSpec t = element(Kind::stairs, 2.4, 1.2);  // 40 deg, 20 cm risers, 0.8 m rise: 4 risers
  const auto solids = terrain_solids(t);
  ASSERT_EQ(solids.size(), 4u);  // three steps and the landing
  const double tread = 0.2 / std::tan(40 * M_PI / 180);  // 0.238 m
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(top(solids[static_cast<std::size_t>(k)]), 0.2 * (k + 1), 1e-12);
    EXPECT_NEAR(solids[static_cast<std::size_t>(k)].geometry.size.x(), tread, 1e-12);
    EXPECT_NEAR(solids[static_cast<std::size_t>(k)].X_WS.p.x(), -1.2 + (k + 0.5) * tread, 1e-12);
  }
  EXPECT_NEAR(top(solids[3]), 0.8, 1e-12);
  EXPECT_NEAR(solids[3].X_WS.p.x() - 0.5 * solids[3].geometry.size.x(), -1.2 + 3 * tread,
              1e-12);  // the landing starts after the third tread
  EXPECT_NEAR(solids[3].X_WS.p.x() + 0.5 * solids[3].geometry.size.x(), 1.2, 1e-12);
}

TEST(Terrain, CrossingRampsRiseTheirWidthTimesTanFifteenDegreesAlternatingPitchAndRoll) {
  TerrainSpec t = element(Kind::crossing_ramps, 3.6, 1.2);
  t.pose = {10, 5, M_PI / 2};  // travel north: the element's +x is the world's +y
  const auto solids = terrain_solids(t);
  ASSERT_EQ(solids.size(), 3u);
  const double rise = 1.2 * std::tan(15 * M_PI / 180);  // 0.3215 m
  for (const auto& s : solids) {
    EXPECT_TRUE(s.ramp);
    EXPECT_NEAR(top(s), rise, 1e-9);
  }
  // cell 0 (world y 3.2..4.4) pitches up to the north edge; cell 1 (4.4..5.6) rolls up to the
  // element's left (+y there, world -x)
  auto high_points = [](const TerrainSolid& s) {
    std::vector<Vec3> out;
    for (const Vec3& v : s.geometry.mesh.vertices) {
      if (v.z() > 0.1) out.push_back(v);
    }
    return out;
  };
  for (const Vec3& v : high_points(solids[0])) EXPECT_NEAR(v.y(), 4.4, 1e-9);
  for (const Vec3& v : high_points(solids[1])) EXPECT_NEAR(v.x(), 9.4, 1e-9);
}

TEST(Terrain, AGapOpensBetweenTwoDecksReachedByFifteenDegreeRamps) {
  TerrainSpec t = element(Kind::gap, 3.6, 1.2);  // 30 cm opening, 20 cm decks
  const auto solids = terrain_solids(t);
  ASSERT_EQ(solids.size(), 4u);
  const double ramp = 0.2 / std::tan(15 * M_PI / 180);  // 0.746 m
  EXPECT_NEAR(solids[1].X_WS.p.x() + 0.5 * solids[1].geometry.size.x(), -0.15, 1e-12);
  EXPECT_NEAR(solids[2].X_WS.p.x() - 0.5 * solids[2].geometry.size.x(), 0.15, 1e-12);
  EXPECT_NEAR(solids[1].X_WS.p.x() - 0.5 * solids[1].geometry.size.x(), -1.8 + ramp, 1e-12);
  EXPECT_NEAR(top(solids[0]), 0.2, 1e-12);
  EXPECT_NEAR(top(solids[2]), 0.2, 1e-12);
}

TEST(Terrain, ElementsThatCannotBeBuiltSayWhy) {
  auto message = [](const TerrainSpec& t) {
    try {
      terrain_solids(t);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(built)");
  };
  EXPECT_NE(message(element(Kind::stepfield, 0.05, 1.2)).find("holds no 0.1 m post"), std::string::npos);
  TerrainSpec steep = element(Kind::stairs, 2.4, 1.2);
  steep.angle = 70;
  EXPECT_NE(message(steep).find("stairs at 70 deg cannot be built"), std::string::npos) << message(steep);
  TerrainSpec tall = element(Kind::stairs, 2.4, 1.2);
  tall.height = 3.0;  // 15 risers of 0.238 m: 3.3 m of treads
  EXPECT_NE(message(tall).find("15 steps of 0.238"), std::string::npos) << message(tall);
  EXPECT_NE(message(element(Kind::gap, 1.5, 1.2)).find("needs 2.39"), std::string::npos) << message(element(Kind::gap, 1.5, 1.2));
  EXPECT_NE(message(element(Kind::crossing_ramps, 1.0, 1.2)).find("at least as long as it is wide"), std::string::npos);
  TerrainSpec fine = element(Kind::stepfield, 100, 100);
  fine.post = 0.001;  // 10^10 posts: refused before anything is built
  EXPECT_NE(message(fine).find("would have 1e+10 posts (expected at most 100000"), std::string::npos) << message(fine);
  TerrainSpec tiny_risers = element(Kind::stairs, 2.4, 1.2);
  tiny_risers.riser = 1e-9;
  EXPECT_NE(message(tiny_risers).find("more than 1000 steps"), std::string::npos) << message(tiny_risers);
  TerrainSpec negative = element(Kind::curb, 1.2, 1.2);
  negative.height = -0.1;
  EXPECT_NE(message(negative).find("negative"), std::string::npos);
}

/// Every diagnostic, one per line.
std::string format(const Diagnostics& d) {
  std::string out;
  for (const auto& item : d.items()) out += item.str() + "\n";
  return out;
}

/// A drawing 10 m x 5 m at 100 units per metre: world (x, y) = (u / 100, (500 - v) / 100).
SvgLoadResult load(const std::string& body) {
  return load_svg_world_from_string("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10m\" height=\"5m\" viewBox=\"0 0 1000 500\">\n" +
                                        body + "\n</svg>\n",
                                    "arena.svg");
}

TEST(TerrainSvg, FootprintsAndDataAttributesBecomeElementsAndWriteBackTheSame) {
  const auto r = load(R"svg(
  <rect x="100" y="100" width="240" height="120" data-kind="stepfield" data-pattern="full-cubic" data-seed="7" id="field"/>
  <rect x="400" y="100" width="240" height="120" data-kind="stairs" data-angle="35" data-riser="0.15"/>
  <rect x="700" y="50" width="120" height="360" data-kind="crossing-ramps"/>
  <rect x="100" y="300" width="120" height="120" data-kind="curb" data-height="10cm" data-yaw="0"/>
  <rect x="300" y="300" width="120" height="120" data-kind="hurdle" data-yaw="90" data-material="obstacle"/>)svg");
  ASSERT_EQ(r.world.terrain.size(), 5u);
  const TerrainSpec& field = r.world.terrain[0];
  EXPECT_EQ(field.kind, Kind::stepfield);
  EXPECT_EQ(field.name, "field");
  EXPECT_FALSE(field.half_cubic);
  EXPECT_EQ(field.seed, 7u);
  EXPECT_NEAR(field.pose.x, 2.2, 1e-9);
  EXPECT_NEAR(field.pose.y, 3.4, 1e-9);  // 5 - (100 + 60) / 100
  EXPECT_NEAR(field.length, 2.4, 1e-9);
  EXPECT_NEAR(field.width, 1.2, 1e-9);
  EXPECT_EQ(r.world.terrain[1].name, "stairs_2");
  EXPECT_DOUBLE_EQ(r.world.terrain[1].angle, 35);
  EXPECT_DOUBLE_EQ(r.world.terrain[1].riser, 0.15);
  // drawn tall: travel runs along the long side, north or south
  EXPECT_NEAR(std::abs(std::sin(r.world.terrain[2].pose.yaw)), 1.0, 1e-9);
  EXPECT_NEAR(r.world.terrain[2].length, 3.6, 1e-9);
  EXPECT_DOUBLE_EQ(r.world.terrain[3].height, 0.1);
  EXPECT_NEAR(r.world.terrain[4].pose.yaw, M_PI / 2, 1e-12);
  EXPECT_EQ(r.world.terrain[4].material, "obstacle");
  EXPECT_FALSE(validate(r.world).has_errors()) << format(validate(r.world));

  const auto again = load_svg_world_from_string(world_to_svg(r.world), "again.svg");
  ASSERT_EQ(again.world.terrain.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    const TerrainSpec &a = r.world.terrain[i], &b = again.world.terrain[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.half_cubic, b.half_cubic);
    EXPECT_EQ(a.material, b.material);
    EXPECT_NEAR(a.pose.x, b.pose.x, 1e-6);
    EXPECT_NEAR(a.pose.y, b.pose.y, 1e-6);
    EXPECT_NEAR(std::cos(a.pose.yaw - b.pose.yaw), 1.0, 1e-9);
    EXPECT_NEAR(a.length, b.length, 1e-6);
    EXPECT_NEAR(a.width, b.width, 1e-6);
    EXPECT_NEAR(a.height, b.height, 1e-9);
    EXPECT_NEAR(a.angle, b.angle, 1e-9);
    EXPECT_NEAR(a.riser, b.riser, 1e-9);
  }
}

TEST(TerrainSvg, BadTerrainIsAnErrorNamingTheElement) {
  auto load_error = [](const std::string& body) {
    try {
      load(body);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  const std::string neg = load_error(R"svg(<rect x="100" y="100" width="240" height="120" data-kind="curb" data-height="-0.2"/>)svg");
  EXPECT_NE(neg.find("arena.svg:2"), std::string::npos) << neg;
  EXPECT_NE(neg.find("data-height"), std::string::npos) << neg;
  const std::string pattern =
      load_error(R"svg(<rect x="100" y="100" width="240" height="120" data-kind="stepfield" data-pattern="cubic"/>)svg");
  EXPECT_NE(pattern.find("unknown pattern 'cubic'; expected half-cubic or full-cubic"), std::string::npos) << pattern;

  auto problems = [](const std::string& body) { return format(validate(load(body).world)); };
  const std::string small = problems(R"svg(<rect x="100" y="100" width="240" height="5" data-kind="stepfield"/>)svg");
  EXPECT_NE(small.find("arena.svg:2"), std::string::npos) << small;
  EXPECT_NE(small.find("holds no 0.1 m post"), std::string::npos) << small;
  const std::string steep = problems(R"svg(<rect x="100" y="100" width="240" height="120" data-kind="stairs" data-angle="65"/>)svg");
  EXPECT_NE(steep.find("stairs at 65 deg cannot be built"), std::string::npos) << steep;
  const std::string overlap = problems(R"svg(
  <rect x="100" y="100" width="240" height="120" data-kind="stepfield" id="a"/>
  <rect x="300" y="100" width="240" height="120" data-kind="stairs" id="b"/>)svg");
  EXPECT_NE(overlap.find("arena.svg:4: <rect id=\"b\">"), std::string::npos) << overlap;
  EXPECT_NE(overlap.find("overlaps stepfield 'a' (line 3)"), std::string::npos) << overlap;
  const std::string material = problems(R"svg(<rect x="100" y="100" width="120" height="120" data-kind="curb" data-material="lava"/>)svg");
  EXPECT_NE(material.find("unknown material 'lava'"), std::string::npos) << material;
  // side by side, edge to edge, is no overlap: lanes of an arena touch
  EXPECT_EQ(problems(R"svg(
  <rect x="100" y="100" width="240" height="120" data-kind="stepfield"/>
  <rect x="100" y="220" width="240" height="120" data-kind="stairs"/>)svg").find("overlaps"),
            std::string::npos);
}

}  // namespace
}  // namespace rescuesim
