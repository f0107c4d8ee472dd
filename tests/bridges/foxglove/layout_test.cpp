// The Foxglove layout shipped in examples/ (docs/foxglove.md): it parses, every panel the
// layout tree places has a configuration, and the settings the documentation promises are there
// (the 3D panel shows the scene and the robot model from /robot_description; the teleop panel
// publishes /cmd_vel faster than the drive's 0.5 s command timeout).

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>

namespace rescuesim {
namespace {

using json = nlohmann::json;

json shipped_layout() {
  std::ifstream in(RESCUESIM_SOURCE_DIR "/examples/foxglove-layout.json");
  EXPECT_TRUE(in.good());
  return json::parse(in, nullptr, false);
}

TEST(FoxgloveLayout, EveryPlacedPanelIsConfigured) {
  const json layout = shipped_layout();
  ASSERT_FALSE(layout.is_discarded()) << "examples/foxglove-layout.json is not valid JSON";
  std::vector<std::string> placed;
  const std::function<void(const json&)> walk = [&](const json& node) {
    if (node.is_string()) {
      placed.push_back(node.get<std::string>());
    } else {
      walk(node.at("first"));
      walk(node.at("second"));
    }
  };
  walk(layout.at("layout"));
  EXPECT_EQ(placed.size(), 5u);
  for (const std::string& panel : placed) EXPECT_TRUE(layout["configById"].contains(panel)) << panel;
}

TEST(FoxgloveLayout, ThreeDPanelShowsTheSceneAndTheRobotDescription) {
  const json layout = shipped_layout();
  ASSERT_FALSE(layout.is_discarded());
  const json& topics = layout["configById"]["3D!rescuesim"]["topics"];
  EXPECT_EQ(topics["/scene"]["visible"], true);
  // the 3D panel's own URDF entry for /robot_description is hidden unless the layout says so
  EXPECT_EQ(topics["/robot_description"]["visible"], true);
  const json& teleop = layout["configById"]["Teleop!drive"];
  EXPECT_EQ(teleop["topic"], "/cmd_vel");
  EXPECT_GE(teleop["publishRate"].get<double>(), 10.0);
}

}  // namespace
}  // namespace rescuesim
