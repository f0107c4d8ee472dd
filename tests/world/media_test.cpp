// Smoke and dust (world/media.h) against optical depths worked out by hand: a ray entering a
// prism through its side, through its top, starting inside, crossing a concave footprint twice
// and passing through vertices; growth and drift; the inverse (depth to distance); read from SVG,
// written back, and refused with a message naming the file, line and element.

#include "world/media.h"

#include <gtest/gtest.h>

#include <cmath>

#include "import/svg/svg_world.h"

namespace rescuesim {
namespace {

/// A counter-clockwise rectangle [x0, x1] x [y0, y1].
Polygon2 box(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

/// The slab of the tests: x in [2, 3], y in [-2, 2], z in [0, 1], smoke of 0.8 /m.
MediumSpec slab() {
  MediumSpec m;
  m.kind = MediumSpec::Kind::smoke;
  m.name = "slab";
  m.outline = box(2, -2, 3, 2);
  m.density = 0.8;
  m.bottom = 0;
  m.height = 1;
  return m;
}

std::vector<MediumVolume> volumes(const std::vector<MediumSpec>& media, double t = 0, SensingBand band = SensingBand::visible) {
  std::vector<MediumVolume> v;
  media_at(media, t, band, v);
  return v;
}

double depth(const std::vector<MediumVolume>& v, const Vec3& o, const Vec3& d, double length) {
  std::vector<MediumSegment> segments;
  return optical_depth(v, o, d.normalized(), length, segments);
}

TEST(MediaDepth, ThroughTheSideIsSigmaTimesTheChord) {
  const auto v = volumes({slab()});
  // along +x at mid-height: inside from x = 2 to 3, so tau = 0.8 * 1
  std::vector<MediumSegment> seg;
  EXPECT_NEAR(optical_depth(v, {0, 0, 0.5}, {1, 0, 0}, 10, seg), 0.8, 1e-12);
  ASSERT_EQ(seg.size(), 1u);
  EXPECT_NEAR(seg[0].enter, 2.0, 1e-12);
  EXPECT_NEAR(seg[0].leave, 3.0, 1e-12);
  // 30 degrees off: the chord is 1 / cos 30 = 1.1547 m (y stays within 3 tan 30 = 1.73 < 2)
  EXPECT_NEAR(depth(v, {0, 0, 0.5}, {std::cos(M_PI / 6), std::sin(M_PI / 6), 0}, 10), 0.8 / std::cos(M_PI / 6), 1e-12);
  // stopping inside (a wall at 2.4 m): only 0.4 m counts
  EXPECT_NEAR(depth(v, {0, 0, 0.5}, {1, 0, 0}, 2.4), 0.32, 1e-12);
  // above the top, beside the footprint, or pointing away: nothing
  EXPECT_EQ(depth(v, {0, 0, 1.5}, {1, 0, 0}, 10), 0.0);
  EXPECT_EQ(depth(v, {0, 2.5, 0.5}, {1, 0, 0}, 10), 0.0);
  EXPECT_EQ(depth(v, {0, 0, 0.5}, {-1, 0, 0}, 10), 0.0);
}

TEST(MediaDepth, ThroughTheTop) {
  const auto v = volumes({slab()});
  // straight down from 3 m over the middle: z from 1 to 0, tau = 0.8
  EXPECT_NEAR(depth(v, {2.5, 0, 3}, {0, 0, -1}, 10), 0.8, 1e-12);
  // down at 45 degrees from (1.6, 0, 1.5): in through the top at s = 0.5 sqrt2 (x = 2.1), out
  // through the side x = 3 at s = 1.4 sqrt2 (z = 0.1): tau = 0.8 * 0.9 sqrt2 = 1.01823
  EXPECT_NEAR(depth(v, {1.6, 0, 1.5}, {1, 0, -1}, 10), 0.8 * 0.9 * std::sqrt(2.0), 1e-12);
}

TEST(MediaDepth, StartingInside) {
  const auto v = volumes({slab()});
  // from x = 2.5 along +x: 0.5 m to the far side
  EXPECT_NEAR(depth(v, {2.5, 0, 0.5}, {1, 0, 0}, 10), 0.4, 1e-12);
  // and from the same point up: 0.5 m to the top
  EXPECT_NEAR(depth(v, {2.5, 0, 0.5}, {0, 0, 1}, 10), 0.4, 1e-12);
  // a segment that ends inside: 0.3 m
  EXPECT_NEAR(depth(v, {2.5, 0, 0.5}, {1, 0, 0}, 0.3), 0.24, 1e-12);
}

TEST(MediaDepth, AConcaveFootprintIsCrossedTwiceAndVerticesCountOnce) {
  // a U open to the north: arms x in [0, 1] and [2, 3] from y = 1 up to 3, joined below y = 1
  MediumSpec u = slab();
  u.outline = {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  u.density = 1;
  const auto v = volumes({u});
  EXPECT_NEAR(depth(v, {-1, 2, 0.5}, {1, 0, 0}, 10), 2.0, 1e-12);  // both arms, 1 m each
  EXPECT_NEAR(depth(v, {-1, 0.5, 0.5}, {1, 0, 0}, 10), 3.0, 1e-12);  // the base, 3 m
  // a diamond crossed through two opposite vertices: 2 m inside
  MediumSpec d = slab();
  d.outline = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  d.density = 1;
  EXPECT_NEAR(depth(volumes({d}), {-3, 0, 0.5}, {1, 0, 0}, 10), 2.0, 1e-12);
}

TEST(MediaDepth, OverlappingMediaAddAndTheInverseFindsTheDepth) {
  MediumSpec a = slab(), b = slab();
  b.outline = box(2.5, -2, 4, 2);  // overlaps a over x in [2.5, 3]
  b.density = 0.4;
  const auto v = volumes({a, b});
  std::vector<MediumSegment> seg;
  // 0.8 * 1 + 0.4 * 1.5 = 1.4
  const double tau = optical_depth(v, {0, 0, 0.5}, {1, 0, 0}, 10, seg);
  EXPECT_NEAR(tau, 1.4, 1e-12);
  // depth 0.4 is reached halfway into a (x = 2.5); depth 1.0 at x = 3 (0.8 * 0.5 + 1.2 * 0.5);
  // depth 1.2 at x = 3.5 (0.4 more at 0.4 /m); more than 1.4 never
  EXPECT_NEAR(distance_at_depth(seg, 0.4), 2.5, 1e-12);
  EXPECT_NEAR(distance_at_depth(seg, 1.0), 3.0, 1e-12);
  EXPECT_NEAR(distance_at_depth(seg, 1.2), 3.5, 1e-12);
  EXPECT_TRUE(std::isinf(distance_at_depth(seg, 1.5)));
  // one segment: linear inside it
  const auto one = volumes({a});
  optical_depth(one, {0, 0, 0.5}, {1, 0, 0}, 10, seg);
  EXPECT_NEAR(distance_at_depth(seg, 0.2), 2.25, 1e-12);
}

TEST(MediaMotion, GrowthMovesEachEdgeOutAndDriftMovesTheWhole) {
  MediumSpec m = slab();
  m.outline = box(-1, -1, 1, 1);
  m.growth = 0.1;
  m.drift = {0.2, -0.1};
  // at t = 5 s: edges 0.5 m out (a 3 m square), centre moved by (1, -0.5)
  const Polygon2 p = medium_outline(m, 5);
  const Polygon2 want = box(-0.5, -2, 2.5, 1);
  ASSERT_EQ(p.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(p[i].x(), want[i].x(), 1e-12) << i;
    EXPECT_NEAR(p[i].y(), want[i].y(), 1e-12) << i;
  }
  // the slab x in [2, 3] drifting east at 0.5 m/s and growing at 0.25 m/s: at t = 2 s it spans
  // x in [2.5, 4.5] (y in [-2.5, 2.5]), so a ray along +x stopping at x = 4 crosses 1.5 m of it
  MediumSpec s = slab();
  s.drift = {0.5, 0};
  s.growth = 0.25;
  EXPECT_NEAR(depth(volumes({s}, 2.0), {0, 0, 0.5}, {1, 0, 0}, 4), 0.8 * 1.5, 1e-12);
  EXPECT_NEAR(depth(volumes({s}, 0.0), {0, 0, 0.5}, {1, 0, 0}, 4), 0.8, 1e-12);
  // the top stays where it was: growth is sideways only
  EXPECT_EQ(depth(volumes({s}, 2.0), {0, 0, 1.01}, {1, 0, 0}, 4), 0.0);
}

TEST(MediaBands, CoefficientsFollowTheStatedRatios) {
  MediumSpec smoke = slab(), dust = slab();
  smoke.density = 2;
  dust.kind = MediumSpec::Kind::dust;
  dust.density = 2;
  EXPECT_DOUBLE_EQ(extinction(smoke, SensingBand::near_infrared), 2.0);
  EXPECT_DOUBLE_EQ(extinction(smoke, SensingBand::long_wave_infrared), 0.1);
  EXPECT_DOUBLE_EQ(extinction(smoke, SensingBand::ultrasound), 0.0);
  EXPECT_DOUBLE_EQ(extinction(dust, SensingBand::near_infrared), 2.0);
  EXPECT_DOUBLE_EQ(extinction(dust, SensingBand::long_wave_infrared), 1.4);
  EXPECT_DOUBLE_EQ(extinction(dust, SensingBand::ultrasound), 0.02);
  EXPECT_DOUBLE_EQ(visibility(0.5), 6.0);
  // a band that does not feel a medium does not see it at all
  EXPECT_TRUE(volumes({smoke}, 0, SensingBand::ultrasound).empty());
  EXPECT_EQ(volumes({dust}, 0, SensingBand::ultrasound).size(), 1u);
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
                                        body +
                                        "\n<line x1=\"0\" y1=\"0\" x2=\"1000\" y2=\"0\" stroke=\"#000\" stroke-width=\"5\"/>\n</svg>\n",
                                    "smoke.svg");
}

std::string load_error(const std::string& body) {
  try {
    load(body);
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(MediaSvg, AreasWithDataKindBecomeMediaAndWriteBackTheSame) {
  const auto r = load(R"svg(
  <rect x="200" y="100" width="100" height="300" data-kind="smoke" data-density="0.75" id="plume"
        data-growth="0.02" data-drift-x="0.1" data-drift-y="-0.05"/>
  <polygon points="500,400 700,400 600,200" data-kind="dust" data-density="2" data-bottom="0.2" data-height="50cm"/>)svg");
  ASSERT_EQ(r.world.media.size(), 2u);
  const MediumSpec& smoke = r.world.media[0];
  EXPECT_EQ(smoke.kind, MediumSpec::Kind::smoke);
  EXPECT_EQ(smoke.name, "plume");
  EXPECT_DOUBLE_EQ(smoke.density, 0.75);
  EXPECT_DOUBLE_EQ(smoke.bottom, 0.0);
  EXPECT_DOUBLE_EQ(smoke.height, 1.0);  // the wall height by default
  EXPECT_DOUBLE_EQ(smoke.growth, 0.02);
  EXPECT_DOUBLE_EQ(smoke.drift.x(), 0.1);
  EXPECT_DOUBLE_EQ(smoke.drift.y(), -0.05);
  const Box2 b = bounds(smoke.outline);  // x 2..3 m, y (500 - 400) / 100 = 1 .. 4 m
  EXPECT_NEAR(b.min.x(), 2.0, 1e-9);
  EXPECT_NEAR(b.max.x(), 3.0, 1e-9);
  EXPECT_NEAR(b.min.y(), 1.0, 1e-9);
  EXPECT_NEAR(b.max.y(), 4.0, 1e-9);
  EXPECT_GT(signed_area(smoke.outline), 0);  // counter-clockwise in the world
  const MediumSpec& dust = r.world.media[1];
  EXPECT_EQ(dust.kind, MediumSpec::Kind::dust);
  EXPECT_EQ(dust.name, "dust_2");
  EXPECT_DOUBLE_EQ(dust.bottom, 0.2);
  EXPECT_DOUBLE_EQ(dust.height, 0.5);
  EXPECT_EQ(dust.outline.size(), 3u);
  EXPECT_NEAR(std::abs(signed_area(dust.outline)), 0.5 * 2 * 2, 1e-9);
  EXPECT_FALSE(validate(r.world).has_errors()) << format(validate(r.world));

  const auto again = load_svg_world_from_string(world_to_svg(r.world), "again.svg");
  ASSERT_EQ(again.world.media.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const MediumSpec &a = r.world.media[i], &c = again.world.media[i];
    EXPECT_EQ(a.kind, c.kind);
    EXPECT_EQ(a.name, c.name);
    EXPECT_DOUBLE_EQ(a.density, c.density);
    EXPECT_DOUBLE_EQ(a.bottom, c.bottom);
    EXPECT_DOUBLE_EQ(a.height, c.height);
    EXPECT_DOUBLE_EQ(a.growth, c.growth);
    EXPECT_DOUBLE_EQ(a.drift.x(), c.drift.x());
    EXPECT_DOUBLE_EQ(a.drift.y(), c.drift.y());
    ASSERT_EQ(a.outline.size(), c.outline.size());
    for (std::size_t k = 0; k < a.outline.size(); ++k) EXPECT_NEAR((a.outline[k] - c.outline[k]).norm(), 0, 1e-6);
  }
}

TEST(MediaSvg, BadMediaAreErrorsNamingTheFileLineAndElement) {
  // negative density
  const std::string neg = load_error(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="smoke" data-density="-1"/>)svg");
  EXPECT_NE(neg.find("smoke.svg:2: <rect> attribute data-density: '-1' is not an extinction coefficient"), std::string::npos) << neg;
  // not a number (and no way to write infinity: the reader refuses it)
  const std::string inf = load_error(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="dust" data-density="inf"/>)svg");
  EXPECT_NE(inf.find("smoke.svg:2: <rect> attribute data-density: 'inf'"), std::string::npos) << inf;
  // no density at all
  const std::string none = load_error(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="smoke"/>)svg");
  EXPECT_NE(none.find("smoke.svg:2: <rect>: a smoke volume needs data-density"), std::string::npos) << none;
  // a height of zero or below
  const std::string flat =
      load_error(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="smoke" data-density="1" data-height="0"/>)svg");
  EXPECT_NE(flat.find("smoke.svg:2: <rect> attribute data-height: '0' is not a positive length in metres"), std::string::npos) << flat;
  // fewer than three points
  const std::string line = load_error(R"svg(<polyline points="100,100 300,100" data-kind="dust" data-density="1" id="d"/>)svg");
  EXPECT_NE(line.find("smoke.svg:2: <polyline id=\"d\">: a dust footprint needs an area"), std::string::npos) << line;
  EXPECT_NE(line.find("(it has 2 points)"), std::string::npos) << line;
  // shrinking
  const std::string shrink =
      load_error(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="smoke" data-density="1" data-growth="-0.1"/>)svg");
  EXPECT_NE(shrink.find("smoke.svg:2: <rect> attribute data-growth: '-0.1' is not a growth rate"), std::string::npos) << shrink;

  // the same classes in a spec built in memory (scenario, API): validate names the medium
  WorldSpec w = load(R"svg(<rect x="200" y="100" width="100" height="300" data-kind="smoke" data-density="1" id="s"/>)svg").world;
  const auto problem = [&w](auto change) {
    WorldSpec c = w;
    change(c.media[0]);
    return format(validate(c));
  };
  EXPECT_NE(problem([](MediumSpec& m) {
              m.density = NAN;
            }).find("smoke.svg:2: <rect id=\"s\">: error: density nan is not an extinction coefficient"),
            std::string::npos);
  EXPECT_NE(problem([](MediumSpec& m) { m.density = -0.5; }).find("density -0.5 is not an extinction coefficient"), std::string::npos);
  EXPECT_NE(problem([](MediumSpec& m) { m.height = 0; }).find("height 0 m is not positive"), std::string::npos);
  EXPECT_NE(problem([](MediumSpec& m) { m.outline.resize(2); }).find("footprint has 2 points; expected a polygon of at least 3"),
            std::string::npos);
  EXPECT_NE(problem([](MediumSpec& m) { m.growth = -1; }).find("growth -1 m/s is not 0 or more"), std::string::npos);
  EXPECT_EQ(problem([](MediumSpec&) {}).find("<rect id=\"s\">"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim
