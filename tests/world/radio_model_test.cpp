// The link models against their formulas worked by hand: WSS and SubT received power,
// clamping, SubT's seeded shadowing, and validation of impossible parameters.

#include "world/radio_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;

TEST(RadioModelByName, NamesGiveTheirDefaultsAndUnknownNamesThrow) {
  const RadioModel wss = radio_model("wss");
  EXPECT_EQ(wss.kind, RadioModelKind::wss);
  EXPECT_DOUBLE_EQ(wss.wss.p0_dbm, -49.67);
  EXPECT_DOUBLE_EQ(wss.wss.d0_m, 2.0);
  EXPECT_DOUBLE_EQ(wss.wss.n, 1.0);
  EXPECT_DOUBLE_EQ(wss.wss.wall_loss_db, 6.325);
  EXPECT_EQ(wss.wss.max_walls, 5);
  EXPECT_DOUBLE_EQ(wss.wss.cutoff_dbm, -93.0);
  const RadioModel subt = radio_model("subt");
  EXPECT_EQ(subt.kind, RadioModelKind::subt);
  EXPECT_DOUBLE_EQ(subt.subt.l0_db, 40.0);
  EXPECT_DOUBLE_EQ(subt.subt.n, 1.5);
  EXPECT_DOUBLE_EQ(subt.subt.sigma_db, 10.0);
  EXPECT_DOUBLE_EQ(subt.subt.tx_power_dbm, 20.0);
  EXPECT_DOUBLE_EQ(subt.subt.noise_floor_dbm, -90.0);
  EXPECT_DOUBLE_EQ(subt.subt.capacity_bps, 1e6);
  EXPECT_EQ(radio_model("ideal").kind, RadioModelKind::ideal);
  try {
    radio_model("wifi");
    FAIL() << "no error for an unknown model";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'wifi'"));
    EXPECT_THAT(e.what(), HasSubstr("ideal, wss or subt"));
  }
}

TEST(RadioModelWss, PowerFollowsTheLogDistanceAndWallFormula) {
  const RadioModel m = radio_model("wss");
  // 10 m: −49.67 − 10·1·log10(10/2) = −49.67 − 6.9897 = −56.6597 dBm, then −6.325 per wall
  EXPECT_NEAR(received_power_dbm(m, 10.0, 0), -56.6597, 0.01);
  EXPECT_NEAR(received_power_dbm(m, 10.0, 1), -62.9847, 0.01);
  EXPECT_NEAR(received_power_dbm(m, 10.0, 3), -75.6347, 0.01);
  // 7 walls count as 5: −56.6597 − 31.625 = −88.2847
  EXPECT_NEAR(received_power_dbm(m, 10.0, 7), -88.2847, 0.01);
  EXPECT_NEAR(received_power_dbm(m, 10.0, 5), received_power_dbm(m, 10.0, 7), 1e-12);
  // at and below d0 = 2 m the reference power −49.67 dBm (clamped)
  EXPECT_NEAR(received_power_dbm(m, 2.0, 0), -49.67, 1e-9);
  EXPECT_NEAR(received_power_dbm(m, 0.5, 0), -49.67, 1e-9);
  EXPECT_NEAR(received_power_dbm(m, 0.0, 0), -49.67, 1e-9);
  // 200 m: −49.67 − 10·log10(100) = −69.67
  EXPECT_NEAR(received_power_dbm(m, 200.0, 0), -69.67, 1e-9);
  EXPECT_DOUBLE_EQ(link_threshold_dbm(m), -93.0);
  EXPECT_TRUE(std::isnan(received_power_dbm(m, std::nan(""), 0)));
}

TEST(RadioModelSubt, PowerFollowsTheLogDistanceFormulaWithoutShadowing) {
  RadioModel m = radio_model("subt");
  m.subt.sigma_db = 0;
  // P = 20 − (40 + 15·log10 d): d = 1 → −20, d = 10 → −35, d = 100 → −50 dBm
  EXPECT_NEAR(received_power_dbm(m, 1.0, 0), -20.0, 0.01);
  EXPECT_NEAR(received_power_dbm(m, 10.0, 0), -35.0, 0.01);
  EXPECT_NEAR(received_power_dbm(m, 100.0, 0), -50.0, 0.01);
  // below 1 m clamped to 1 m; walls are not part of the model
  EXPECT_NEAR(received_power_dbm(m, 0.1, 0), -20.0, 1e-9);
  EXPECT_NEAR(received_power_dbm(m, 10.0, 4), -35.0, 1e-9);
  // the default 500 m maximum range: 400 m links (20 − 40 − 15·2.602 = −59.03), 600 m does not
  EXPECT_NEAR(received_power_dbm(m, 400.0, 0), -59.0309, 0.01);
  EXPECT_EQ(received_power_dbm(m, 600.0, 0), -std::numeric_limits<double>::infinity());
  // shadowing adds in dB
  EXPECT_NEAR(received_power_dbm(m, 10.0, 0, -3.5), -38.5, 1e-9);
  EXPECT_DOUBLE_EQ(link_threshold_dbm(m), -90.0);
}

TEST(RadioModelSubt, CutOffDistanceFollowsTheExponent) {
  // with n = 4: P = −20 − 40·log10 d ≥ −90 ⇔ d ≤ 10^(70/40) = 56.23 m
  RadioModel m = radio_model("subt");
  m.subt.sigma_db = 0;
  m.subt.n = 4;
  EXPECT_NEAR(received_power_dbm(m, 50.0, 0), -87.9588, 0.01);  // −20 − 40·1.69897
  EXPECT_NEAR(received_power_dbm(m, 60.0, 0), -91.1261, 0.01);  // −20 − 40·1.77815
  EXPECT_GE(received_power_dbm(m, 56.2, 0), link_threshold_dbm(m));
  EXPECT_LT(received_power_dbm(m, 56.3, 0), link_threshold_dbm(m));
}

TEST(RadioModelSubt, ShadowingIsSeededPerUnorderedPairAndUpdate) {
  const RadioModel m = radio_model("subt");
  const double a = link_shadowing_db(m, 42, "robot1", "base", 3);
  EXPECT_EQ(a, link_shadowing_db(m, 42, "robot1", "base", 3));  // same seed, same draw
  EXPECT_EQ(a, link_shadowing_db(m, 42, "base", "robot1", 3));  // (a, b) and (b, a) share it
  EXPECT_NE(a, link_shadowing_db(m, 43, "robot1", "base", 3));  // another seed, another draw
  EXPECT_NE(a, link_shadowing_db(m, 42, "robot1", "base", 4));  // redrawn at each update
  EXPECT_NE(a, link_shadowing_db(m, 42, "robot2", "base", 3));  // each pair its own stream
  // σ = 10 dB: the spread of many draws is near 10 (1000 draws: standard error ≈ 0.22 dB)
  double sum = 0, sum2 = 0;
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const double s = link_shadowing_db(m, 7, "a", "b", k);
    sum += s;
    sum2 += s * s;
  }
  const double mean = sum / 1000, sd = std::sqrt(sum2 / 1000 - mean * mean);
  EXPECT_NEAR(mean, 0.0, 1.5);
  EXPECT_NEAR(sd, 10.0, 1.0);
  // no shadowing in wss, nor with σ = 0
  EXPECT_EQ(link_shadowing_db(radio_model("wss"), 42, "robot1", "base", 3), 0.0);
  RadioModel quiet = m;
  quiet.subt.sigma_db = 0;
  EXPECT_EQ(link_shadowing_db(quiet, 42, "robot1", "base", 3), 0.0);
}

TEST(RadioModelIdeal, AlwaysLinks) {
  const RadioModel m = radio_model("ideal");
  EXPECT_GE(received_power_dbm(m, 1e6, 100), link_threshold_dbm(m));
}

TEST(RadioModelValidation, DefaultsAreValid) {
  EXPECT_TRUE(validate_radio_model(radio_model("ideal")).empty());
  EXPECT_TRUE(validate_radio_model(radio_model("wss")).empty());
  EXPECT_TRUE(validate_radio_model(radio_model("subt")).empty());
}

TEST(RadioModelValidation, ImpossibleParametersAreNamed) {
  RadioModel wss = radio_model("wss");
  wss.wss.p0_dbm = std::nan("");
  wss.wss.d0_m = 0;
  wss.wss.n = -1;
  wss.wss.max_walls = -2;
  wss.wss.wall_loss_db = std::numeric_limits<double>::infinity();
  const std::vector<std::string> e = validate_radio_model(wss);
  ASSERT_EQ(e.size(), 5u) << ::testing::PrintToString(e);
  EXPECT_THAT(e[0], HasSubstr("radio.wss.p0_dbm: must be finite"));
  EXPECT_THAT(e[1], HasSubstr("radio.wss.d0_m: must be finite and > 0 (got 0)"));
  EXPECT_THAT(e[2], HasSubstr("radio.wss.n: must be finite and >= 0 (got -1)"));
  EXPECT_THAT(e[3], HasSubstr("radio.wss.wall_loss_db"));
  EXPECT_THAT(e[4], HasSubstr("radio.wss.max_walls: must be >= 0 (got -2)"));

  RadioModel subt = radio_model("subt");
  subt.subt.capacity_bps = 0;
  subt.subt.sigma_db = -1;
  subt.subt.max_range_m = std::nan("");
  subt.subt.tx_power_dbm = -std::numeric_limits<double>::infinity();
  subt.max_datagram_bytes = 0;
  const std::vector<std::string> f = validate_radio_model(subt);
  ASSERT_EQ(f.size(), 5u) << ::testing::PrintToString(f);
  EXPECT_THAT(f[0], HasSubstr("radio.subt.sigma_db"));
  EXPECT_THAT(f[1], HasSubstr("radio.subt.tx_power_dbm"));
  EXPECT_THAT(f[2], HasSubstr("radio.subt.capacity_bps: must be finite and > 0 (got 0)"));
  EXPECT_THAT(f[3], HasSubstr("radio.subt.max_range_m"));
  EXPECT_THAT(f[4], HasSubstr("radio.subt.max_datagram_bytes: must be > 0"));
  // an unlimited range is allowed
  RadioModel open = radio_model("subt");
  open.subt.max_range_m = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(validate_radio_model(open).empty());
}

TEST(RadioModelOverrides, SetByNameForTheModelsKind) {
  RadioModel m = radio_model("wss");
  EXPECT_FALSE(set_radio_parameter(m, "max_walls", 8));
  EXPECT_FALSE(set_radio_parameter(m, "n", 2));
  EXPECT_FALSE(set_radio_parameter(m, "max_datagram_bytes", 1024));
  EXPECT_EQ(m.wss.max_walls, 8);
  EXPECT_DOUBLE_EQ(m.wss.n, 2.0);
  EXPECT_EQ(m.max_datagram_bytes, 1024);
  const auto unknown = set_radio_parameter(m, "sigma_db", 3);  // a subt parameter
  ASSERT_TRUE(unknown);
  EXPECT_THAT(*unknown, HasSubstr("radio.wss: unknown parameter 'sigma_db'"));
  EXPECT_THAT(*unknown, HasSubstr("cutoff_dbm"));
  const auto fraction = set_radio_parameter(m, "max_walls", 2.5);
  ASSERT_TRUE(fraction);
  EXPECT_THAT(*fraction, HasSubstr("radio.wss.max_walls: expected a whole number"));
  RadioModel s = radio_model("subt");
  EXPECT_FALSE(set_radio_parameter(s, "capacity_bps", 2e6));
  EXPECT_DOUBLE_EQ(s.subt.capacity_bps, 2e6);
}

}  // namespace
}  // namespace rescuesim
