// `rescuesim check` on URDF robots: the TurtleBot3 burger (worlds/robots, ROBOTIS, Apache-2.0)
// is described with its links, joints and meshes; a bad URDF exits 2 naming the file and line.

#include <gtest/gtest.h>

#include <filesystem>

#include "support/command.h"

namespace rescuesim {
namespace {

using testing::quoted;
using testing::rescuesim;
using testing::temp_dir;
using testing::write_text;


TEST(CheckUrdf, TurtleBot3BurgerIsDescribed) {
  const auto robots = std::filesystem::path(RESCUESIM_SOURCE_DIR) / "worlds" / "robots";
  const auto urdf = robots / "turtlebot3_description" / "urdf" / "turtlebot3_burger.urdf";
  const auto r = rescuesim("check --resource-path " + quoted(robots) + " " + quoted(urdf));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("turtlebot3_burger"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("base_footprint"), std::string::npos) << r.out;
  // 7 links; base, caster, imu and scan joints fixed, the two wheels continuous
  EXPECT_NE(r.out.find("7 links, 6 joints (2 moving, 4 fixed)"), std::string::npos) << r.out;
  // burger_base.stl is a binary STL of 1716084 bytes: (1716084 - 84) / 50 triangles
  EXPECT_NE(r.out.find("34320 triangles"), std::string::npos) << r.out;
}

TEST(CheckUrdf, BadUrdfExitsTwoNamingTheFileAndLine) {
  const auto dir = temp_dir("check-urdf");
  const auto bad = dir / "bad.urdf";
  write_text(bad, "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n  <joint name=\"j\" type=\"ball\">\n"
                  "    <parent link=\"a\"/><child link=\"b\"/>\n  </joint>\n</robot>\n");
  const auto r = rescuesim("check " + quoted(bad));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(bad.string() + ":4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'ball'"), std::string::npos) << r.err;
}

TEST(CheckUrdf, XacroFileExitsTwoSayingHowToExpandIt) {
  const auto dir = temp_dir("check-xacro");
  const auto xacro = dir / "robot.urdf.xacro";
  write_text(xacro, "<?xml version=\"1.0\"?>\n<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
                    "  <xacro:include filename=\"wheels.xacro\"/>\n  <link name=\"base\"/>\n</robot>\n");
  const auto r = rescuesim("check " + quoted(xacro));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(xacro.string() + ":3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xacro"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rescuesim
