// Robot lamps from an SDF model's link lights, end to end: loaded, placed in the render scene on
// their links and switched by /lights (the parts: tests/import/sdf, tests/render/darkness_test.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "import/sdf/sdf_import.h"
#include "render/render_scene.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

// An SDF model's link lights, end to end: loaded as lamps, on from the start (as in Gazebo), placed
// in the render scene on their link (the headlight 0.3 m ahead of the chassis, 5 cm up, shining
// the robot's way), and switched off by /lights.
TEST(Lights, AnSdfModelsLinkLightsLightTheSceneUntilSwitchedOff) {
  SdfOptions o;
  o.resolver = ResourceResolver({std::filesystem::path(RESCUESIM_SOURCE_DIR) / "tests/data/sdf/models"}, false);
  RobotSpec bot = load_sdf_robot("model://lamp_bot", o).spec;
  bot.model = "lamp_bot";
  WorldSpec spec = testing::room_spec();
  spec.robots[0].model = "lamp_bot";
  spec.robots[0].start.yaw = M_PI / 2;  // facing north
  Simulation sim(compile_world(spec, {{"lamp_bot", bot}}));
  ASSERT_TRUE(sim.state().robots[0].lights_on);
  RenderScene scene = build_render_scene(sim.world());
  update_render_scene(scene, sim.state());
  ASSERT_EQ(scene.lamps.size(), 2u);
  const RenderLight* head = nullptr;
  for (const RenderLight& l : scene.lights) head = l.spot && l.range == 15.0 ? &l : head;
  ASSERT_NE(head, nullptr);
  const Pose3& chassis = sim.state().robots[0].X_WL[0];
  EXPECT_TRUE(head->position.isApprox(chassis * Vec3(0.3, 0, 0.05), 1e-9));
  EXPECT_LT((head->direction - chassis.q * Vec3::UnitX()).norm(), 1e-9);
  EXPECT_NEAR(head->direction.y(), 1.0, 0.02);  // north, as the robot faces
  std::size_t lights = 0;
  while (sim.inputs()[lights].topic != "/lights") ++lights;
  sim.submit_input(lights, msg::Bool{false});
  sim.step();
  update_render_scene(scene, sim.state());
  for (const RenderLight& l : scene.lights) EXPECT_NE(l.range, 15.0);
}

}  // namespace
}  // namespace rescuesim
