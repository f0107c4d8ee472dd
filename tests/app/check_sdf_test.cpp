// `rescuesim check` and `rescuesim run` on SDF worlds, as a Gazebo user would call them: the
// shipped worlds/rescue_yard.sdf is described model by model; every class of bad SDF exits 2
// with a message naming the file, the line or element, and what was expected.

#include <gtest/gtest.h>

#include <filesystem>

#include "support/command.h"

namespace rescuesim {
namespace {

using testing::quoted;
using testing::rescuesim;
using testing::temp_dir;
using testing::write_text;

namespace fs = std::filesystem;


const fs::path kWorlds = fs::path(RESCUESIM_SOURCE_DIR) / "worlds";

TEST(CheckSdf, RescueYardIsDescribedModelByModel) {
  const auto r = rescuesim("check --resource-path " + quoted(kWorlds / "models") + " " + quoted(kWorlds / "rescue_yard.sdf"));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("SDF 1.9, world 'rescue_yard'"), std::string::npos) << r.out;
  // what each model became
  EXPECT_NE(r.out.find("model ground_plane                 floor"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model ramp                         static geometry"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model crate_1                      rigid body"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model victim_1                     victim"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model robot_start                  robot start"), std::string::npos) << r.out;
  // the ramp's STL has 12 triangles (6 quadrilateral faces) and stays a triangle mesh
  EXPECT_NE(r.out.find("meshes/rescue_ramp.stl (ramp::link): collision, 12 triangles, exact triangle mesh"), std::string::npos) << r.out;
  // walls (6 boxes), block, slab, pipe, ramp and 2 x 2 victim shapes; 3 crates
  EXPECT_NE(r.out.find("model solids  14 (1 exact meshes, 12 triangles)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model bodies  3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("light flood                spot"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("physics step 0.005"), std::string::npos) << r.out;
}

TEST(CheckSdf, ADrawnWorldTakesModelsPlacedByTheScenario) {
  // worlds/arena_models.yaml: the SVG arena (13 walls, 5 rubble) plus two model://crate includes
  const auto r = rescuesim("check " + quoted(kWorlds / "arena_models.yaml"));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("walls         13"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rubble        5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model bodies  2"), std::string::npos) << r.out;
}

TEST(CheckSdf, EveryKindOfBadSdfExitsTwoNamingTheFile) {
  const auto dir = temp_dir("check-sdf");
  fs::create_directories(dir / "junk_model" / "meshes");
  write_text(dir / "junk_model" / "model.config",
             "<?xml version=\"1.0\"?><model><name>junk</name><sdf version=\"1.9\">model.sdf</sdf></model>\n");
  write_text(dir / "junk_model" / "model.sdf",
             "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\"><model name=\"junk\"><static>true</static><link name=\"l\">\n"
             "<collision name=\"c\"><geometry><mesh><uri>meshes/junk.stl</uri></mesh></geometry></collision>\n"
             "</link></model></sdf>\n");
  write_text(dir / "junk_model" / "meshes" / "junk.stl", "this is not a mesh, only words in a file named .stl\n");
  const std::string head = "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n<world name=\"w\">\n";
  const std::string tail = "</world>\n</sdf>\n";
  const std::string box = "<model name=\"b\"><static>true</static><link name=\"l\"><collision name=\"c\"><geometry><box><size>";
  struct Case {
    const char* name;
    std::string text;
    const char* says;  ///< part of the message
  };
  const Case cases[] = {
      {"malformed", head + "<model name=\"m\">\n<link name=\"l\">\n" + tail, "malformed XML"},
      {"unknown_model", head + "<include>\n<uri>model://no_such_model</uri>\n</include>\n" + tail, "model://no_such_model"},
      {"not_a_mesh", head + "<include><uri>model://junk_model</uri></include>\n" + tail, "junk.stl"},
      {"absurd_scale", head + box + "1e9 1 1</size></box></geometry></collision></link></model>\n" + tail, "<box><size>"},
      {"version", "<?xml version=\"1.0\"?>\n<sdf version=\"2.0\">\n<world name=\"w\"/>\n</sdf>\n", "SDF 2.0"},
  };
  for (const Case& c : cases) {
    const fs::path file = dir / (std::string(c.name) + ".sdf");
    write_text(file, c.text);
    const auto r = rescuesim("check --resource-path " + quoted(dir) + " " + quoted(file));
    EXPECT_EQ(r.exit_code, 2) << c.name << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(c.name), std::string::npos) << c.name << ": the message names a file\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.name << "\n" << r.err;
  }
  // a world with nothing in it but the sun and the ground plane reads, and is reported empty
  const fs::path empty = dir / "empty.sdf";
  write_text(empty, head + "<include><uri>model://sun</uri></include>\n<include><uri>model://ground_plane</uri></include>\n" + tail);
  const auto r = rescuesim("check " + quoted(empty));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("the world is empty"), std::string::npos) << r.err;
}

TEST(CheckSdf, RunWithABadSdfWorldExitsTwoAndWritesNothing) {
  const auto dir = temp_dir("run-sdf");
  const fs::path file = dir / "broken.sdf";
  write_text(
      file,
      "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n<world name=\"w\">\n<include><uri>model://gone</uri></include>\n</world></sdf>\n");
  const fs::path out = dir / "out";
  const auto r = rescuesim("run --world " + quoted(file) + " --duration 1 --no-cameras --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("broken.sdf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("model://gone"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

TEST(CheckSdf, RunTheRescueYardFromItsScenario) {
  const auto out = temp_dir("run-yard") / "yard";
  const auto r = rescuesim("run " + quoted(kWorlds / "rescue_yard.yaml") + " --duration 5 --no-cameras --quiet --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "overview.png"));
}

}  // namespace
}  // namespace rescuesim
