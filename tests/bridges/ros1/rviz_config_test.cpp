// The RViz configuration shipped in examples/rviz parses as YAML, uses the odom fixed frame, and
// every display in it shows a topic the simulation publishes, with the message type the display
// expects.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <map>

#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

TEST(RvizConfig, EveryDisplayShowsAPublishedTopicOfItsType) {
  const YAML::Node rviz = YAML::LoadFile(RESCUESIM_SOURCE_DIR "/examples/rviz/rescuesim.rviz");
  const YAML::Node manager = rviz["Visualization Manager"];
  ASSERT_TRUE(manager.IsMap());
  EXPECT_EQ(manager["Global Options"]["Fixed Frame"].as<std::string>(), "odom");

  // the topics one robot publishes, with their ROS 1 types
  Simulation sim(compile_world(testing::room_spec(), builtin_models()));
  std::map<std::string, std::string> published;
  for (const Topic& t : sim.bus().topics()) published[t.name] = t.type;

  const std::map<std::string, std::string> type_of_display = {
      {"rviz/LaserScan", "sensor_msgs/LaserScan"}, {"rviz/Image", "sensor_msgs/Image"},
      {"rviz/Range", "sensor_msgs/Range"},         {"rviz/PointCloud2", "sensor_msgs/PointCloud2"},
      {"rviz/Odometry", "nav_msgs/Odometry"},
  };
  std::map<std::string, int> shown;
  std::function<void(const YAML::Node&)> visit = [&](const YAML::Node& displays) {
    for (const auto& d : displays) {
      const std::string cls = d["Class"].as<std::string>();
      if (d["Displays"]) visit(d["Displays"]);
      const YAML::Node topic = d["Image Topic"] ? d["Image Topic"] : d["Topic"];
      if (!topic) continue;
      const std::string name = topic.as<std::string>();
      ASSERT_TRUE(published.count(name)) << cls << " shows " << name << ", which is not published";
      ASSERT_TRUE(type_of_display.count(cls)) << cls;
      EXPECT_EQ(published[name], type_of_display.at(cls)) << name;
      ++shown[cls];
    }
  };
  visit(manager["Displays"]);
  EXPECT_EQ(shown["rviz/LaserScan"], 1);
  EXPECT_EQ(shown["rviz/Range"], 4);
  EXPECT_EQ(shown["rviz/Image"], 3);
  EXPECT_EQ(shown["rviz/Odometry"], 1);
}

}  // namespace
}  // namespace rescuesim
