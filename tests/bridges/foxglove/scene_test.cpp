// The foxglove.SceneUpdate drawn from a World: shapes and where they land (checked by hand
// against the WorldSpec), frames, what changes, and that every emitted field is in the schema.

#include "bridges/foxglove/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "robots/rescue_robot.h"

namespace rescuesim::foxglove {
namespace {

using json = nlohmann::json;

/// A 4 m x 2 m floor with a wall along its north edge, a 0.4 m square obstacle, a raised area
/// with one ramp, a rubble box, a victim, and the rescue robot at (1, 1) facing east.
World small_world() {
  WorldSpec w;
  w.name = "scene-test";
  w.floor_min = {0, 0};
  w.floor_max = {4, 2};
  w.materials = default_materials();
  w.walls.push_back({{0, 2}, {4, 2}, 0.1, 1.0, "wall", {}});
  w.blocks.push_back({{{3, 0.2}, {3.4, 0.2}, {3.4, 0.6}, {3, 0.6}}, 0.5, "obstacle", {}});
  RaisedAreaSpec r;
  r.outline = {{2, 0.2}, {2.6, 0.2}, {2.6, 0.6}, {2, 0.6}};
  r.height = 0.1;
  r.ramp_edges = {1};
  w.raised_areas.push_back(r);
  RubbleSpec rb;
  rb.pose = {3.5, 1.5, 0};
  rb.size = {0.2, 0.1, 0.1};
  w.rubble.push_back(rb);
  VictimSpec v;
  v.name = "bob";
  v.pose = {2.5, 1.5, 0};
  w.victims.push_back(v);
  RobotPlacement p;
  p.start = {1, 1, 0};
  w.robots.push_back(p);
  return compile_world(w, builtin_models());
}

SceneFrames odom_frames(const World& world) {
  SceneFrames f;
  f.world_frame = "odom";
  f.X_FW = world.robots[0].X_W_start.inverse();
  std::vector<std::string> links;
  for (const auto& l : world.robots[0].spec.links) links.push_back(l.name);
  f.link_frames.push_back(links);
  return f;
}

SceneState initial_state(const World& world) {
  SceneState s;
  for (const auto& d : world.dynamics) s.rubble.push_back(d.X_WO);
  s.victim_found_at.assign(world.victims.size(), -1.0);
  s.victim_found_by.assign(world.victims.size(), "");
  return s;
}

const json* entity(const json& update, const std::string& id) {
  for (const auto& e : update["entities"]) {
    if (e["id"] == id) return &e;
  }
  return nullptr;
}

/// Every key of `value` is a property of `schema` (recursively), required ones are present,
/// and types match: the scene never sends a field Foxglove's schema does not know.
void expect_conforms(const json& value, const json& schema, const std::string& path) {
  const std::string type = schema.value("type", "");
  if (type == "object") {
    ASSERT_TRUE(value.is_object()) << path;
    for (const auto& [k, v] : value.items()) {
      ASSERT_TRUE(schema["properties"].contains(k)) << path << "." << k << " is not in the schema";
      expect_conforms(v, schema["properties"][k], path + "." + k);
    }
    for (const auto& k : schema["required"]) EXPECT_TRUE(value.contains(k.get<std::string>())) << path << " lacks " << k;
  } else if (type == "array") {
    ASSERT_TRUE(value.is_array()) << path;
    for (std::size_t i = 0; i < value.size(); ++i) expect_conforms(value[i], schema["items"], path + "[" + std::to_string(i) + "]");
  } else if (type == "number") {
    EXPECT_TRUE(value.is_number()) << path;
  } else if (type == "integer") {
    EXPECT_TRUE(value.is_number_integer()) << path;
  } else if (type == "string") {
    EXPECT_TRUE(value.is_string()) << path;
  } else if (type == "boolean") {
    EXPECT_TRUE(value.is_boolean()) << path;
  }
}

TEST(FoxgloveScene, WallIsACubeWhereTheSpecPutsIt) {
  const World world = small_world();
  const SceneBuilder scene(world, odom_frames(world));
  const json update = json::parse(scene.full(SimTime::from_seconds(1.5), initial_state(world)));
  const json* walls = entity(update, "walls");
  ASSERT_NE(walls, nullptr);
  EXPECT_EQ((*walls)["frame_id"], "odom");
  EXPECT_EQ((*walls)["frame_locked"], false);
  ASSERT_EQ((*walls)["cubes"].size(), 1u);
  const json& cube = (*walls)["cubes"][0];
  // 4 m long, 0.1 m thick, 1 m high, centred at (2, 2, 0.5) in the world: (1, 1) from the start
  EXPECT_NEAR(cube["size"]["x"].get<double>(), 4.0, 1e-6);
  EXPECT_NEAR(cube["size"]["y"].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(cube["size"]["z"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(cube["pose"]["position"]["x"].get<double>(), 1.0, 1e-4);
  EXPECT_NEAR(cube["pose"]["position"]["y"].get<double>(), 1.0, 1e-4);
  EXPECT_NEAR(cube["pose"]["position"]["z"].get<double>(), 0.5 - world.robots[0].X_W_start.p.z(), 1e-4);
  EXPECT_EQ((*walls)["timestamp"]["sec"], 0);
}

TEST(FoxgloveScene, ExtrudedShapesAreIndexedTriangleLists) {
  const World world = small_world();
  const SceneBuilder scene(world, odom_frames(world));
  const json update = json::parse(scene.full(SimTime{}, initial_state(world)));
  for (const char* id : {"obstacles", "raised_areas"}) {
    const json* e = entity(update, id);
    ASSERT_NE(e, nullptr) << id;
    ASSERT_FALSE((*e)["triangles"].empty()) << id;
    for (const auto& t : (*e)["triangles"]) {
      const std::size_t n = t["points"].size();
      EXPECT_GT(t["indices"].size(), 0u);
      EXPECT_EQ(t["indices"].size() % 3, 0u);
      for (const auto& i : t["indices"]) EXPECT_LT(i.get<std::size_t>(), n);
    }
  }
  // the obstacle reaches 0.5 m above the floor
  double top = -1e9;
  for (const auto& p : (*entity(update, "obstacles"))["triangles"][0]["points"]) top = std::max(top, p["z"].get<double>());
  EXPECT_NEAR(top, 0.5, 1e-4);  // points are in the shape frame; its pose carries the offset
}

TEST(FoxgloveScene, VictimsAndRobotLinksAreEntities) {
  const World world = small_world();
  const SceneBuilder scene(world, odom_frames(world));
  const json update = json::parse(scene.full(SimTime{}, initial_state(world)));
  const json* bob = entity(update, "victim/bob");
  ASSERT_NE(bob, nullptr);
  EXPECT_GT((*bob)["spheres"].size() + (*bob)["cubes"].size() + (*bob)["cylinders"].size(), 3u);  // head, torso, limbs
  const json* base = entity(update, "robot/robot/" + world.robots[0].spec.links[0].name);
  ASSERT_NE(base, nullptr);
  EXPECT_EQ((*base)["frame_id"], world.robots[0].spec.links[0].name);
  EXPECT_EQ((*base)["frame_locked"], true);
  EXPECT_EQ(scene.static_entity_count() + 2, update["entities"].size());  // + rubble, victim labels
}

TEST(FoxgloveScene, MovingPartChangesOnlyWhenSomethingMoves) {
  const World world = small_world();
  const SceneBuilder scene(world, odom_frames(world));
  SceneState s = initial_state(world);
  const std::string before = scene.moving(SimTime::from_seconds(1), s);
  EXPECT_EQ(scene.moving(SimTime::from_seconds(1), s), before);
  const json m = json::parse(before);
  ASSERT_EQ(m["entities"].size(), 2u);
  EXPECT_NE(entity(m, "rubble"), nullptr);
  EXPECT_NE(entity(m, "victim_labels"), nullptr);
  EXPECT_EQ((*entity(m, "victim_labels"))["texts"][0]["text"], "bob");

  // resting rubble jitters by micrometres: that is no change; a centimetre is
  const SceneState resting = s;
  s.rubble[0].p.x() += 0.0005;
  EXPECT_TRUE(same_scene(s, resting));
  s.rubble[0].p.x() += 0.01;
  EXPECT_FALSE(same_scene(s, resting));
  EXPECT_NE(scene.moving(SimTime::from_seconds(1), s), before);
  s = initial_state(world);
  s.victim_found_at[0] = 12.34;
  s.victim_found_by[0] = "robot";
  EXPECT_FALSE(same_scene(s, resting));
  const json found = json::parse(scene.moving(SimTime::from_seconds(1), s));
  EXPECT_EQ((*entity(found, "victim_labels"))["texts"][0]["text"], "bob: found at 12.3 s by robot");
  const json& cube = (*entity(found, "rubble"))["cubes"][0];
  EXPECT_NEAR(cube["size"]["x"].get<double>(), 0.2, 1e-6);
}

TEST(FoxgloveScene, EverythingSentIsInTheSchema) {
  const World world = small_world();
  const SceneBuilder scene(world, odom_frames(world));
  const json schema = json::parse(scene_update_schema());
  EXPECT_EQ(schema["title"], "foxglove.SceneUpdate");
  SceneState s = initial_state(world);
  s.victim_found_at[0] = 3;
  expect_conforms(json::parse(scene.full(SimTime::from_seconds(2), s)), schema, "update");
}

}  // namespace
}  // namespace rescuesim::foxglove
