// Bad SDF input: each is an Error whose text names the file, the element and, where there is
// one, the line; none crashes. Files are written by the tests into a temporary folder.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import/sdf/sdf_test_files.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using namespace sdf_test;

/// A world holding one static model whose link has this collision geometry.
std::string world_with(const std::string& geometry) {
  return R"(<?xml version="1.0"?>
<sdf version="1.9">
  <world name="w">
    <model name="thing">
      <static>true</static>
      <link name="l">
        <collision name="c">
          <geometry>)" +
         geometry + R"(</geometry>
        </collision>
      </link>
    </model>
  </world>
</sdf>
)";
}

TEST(SdfErrors, MalformedXmlNamesTheLine) {
  const std::string text = "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n<world name=\"w\">\n<model name=\"a\">\n<link "
                           "name=\"x\">\n</model>\n</world></sdf>\n";
  const Error e = error_of([&] { parse_sdf_world(text, "bad.sdf", isolated({})); });
  EXPECT_EQ(e.where().file, "bad.sdf");
  EXPECT_GT(e.where().line, 0);
  EXPECT_THAT(e.what(), HasSubstr("malformed XML"));
  EXPECT_THAT(e.what(), HasSubstr("link"));
}

TEST(SdfErrors, UnknownModelListsEveryPlaceSearched) {
  TempDir dir;
  const std::string text = "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n<world "
                           "name=\"w\">\n<include>\n<uri>model://nothere</uri>\n</include>\n</world></sdf>\n";
  const auto file = dir.write("w.sdf", text);
  const Error e = error_of([&] { load_sdf_world(file, isolated({dir.path(), models_dir()})); });
  EXPECT_EQ(e.where().file, file.string());
  EXPECT_EQ(e.where().line, 5);
  EXPECT_THAT(e.what(), HasSubstr("model://nothere"));
  EXPECT_THAT(e.what(), HasSubstr((dir.path() / "nothere").string()));
  EXPECT_THAT(e.what(), HasSubstr((models_dir() / "nothere").string()));
  EXPECT_THAT(e.what(), HasSubstr("uri"));
}

TEST(SdfErrors, GarbageMeshNamesTheFileAndTheElement) {
  TempDir dir;
  dir.write("garbage.stl", "this is not a mesh at all, just some text\nwith two lines\n");
  const std::string text = world_with("<mesh><uri>garbage.stl</uri></mesh>");
  const auto file = dir.write("w.sdf", text);
  const Error e = error_of([&] { load_sdf_world(file, isolated({})); });
  EXPECT_THAT(e.what(), HasSubstr("garbage.stl"));
  EXPECT_THAT(e.what(), HasSubstr("<collision name=\"c\">"));
  EXPECT_THAT(e.what(), HasSubstr(file.string()));
}

TEST(SdfErrors, AbsurdScaleIsRefused) {
  TempDir dir;
  const auto file = dir.write("w.sdf", world_with("<mesh><uri>model://ramp/meshes/ramp.stl</uri><scale>1e9 1e9 1e9</scale></mesh>"));
  const Error e = error_of([&] { load_sdf_world(file, isolated()); });
  EXPECT_THAT(e.what(), HasSubstr("<scale>"));
  EXPECT_THAT(e.what(), HasSubstr("absurd"));
  EXPECT_EQ(e.where().file, file.string());
  EXPECT_EQ(e.where().line, line_of(world_with("<mesh>"), "<geometry>"));
}

TEST(SdfErrors, NonPositiveAndHugeSizesAreRefused) {
  for (const std::string g : {"<box><size>1 0 1</size></box>", "<box><size>1 1 1e7</size></box>", "<sphere><radius>-1</radius></sphere>"}) {
    const Error e = error_of([&] { parse_sdf_world(world_with(g), "size.sdf", isolated({})); });
    EXPECT_EQ(e.where().file, "size.sdf") << g;
    EXPECT_THAT(e.what(), HasSubstr("<collision name=\"c\">")) << g;
  }
}

TEST(SdfErrors, VersionTwoIsRefusedNamingTheVersion) {
  const std::string text = "<?xml version=\"1.0\"?>\n<sdf version=\"2.0\">\n<world name=\"w\"/>\n</sdf>\n";
  const Error e = error_of([&] { parse_sdf_world(text, "v2.sdf", isolated({})); });
  EXPECT_EQ(e.where().file, "v2.sdf");
  EXPECT_EQ(e.where().line, 2);
  EXPECT_THAT(e.what(), HasSubstr("2.0"));
  EXPECT_THAT(e.what(), HasSubstr("up to 1.9"));
}

TEST(SdfErrors, NewerMinorVersionIsReadWithAWarning) {
  const std::string text = "<?xml version=\"1.0\"?>\n<sdf version=\"1.10\">\n" + world_with("<box><size>1 1 1</size></box>").substr(41);
  const SdfWorld w = parse_sdf_world(text, "v110.sdf", isolated({}));
  EXPECT_EQ(w.spec.solids.size(), 1u);
  EXPECT_THAT(warnings(w.diagnostics), HasSubstr("declares SDF 1.10; read as 1.9"));
}

TEST(SdfErrors, BallJointInARobotNamesTheJoint) {
  const std::string text = R"(<?xml version="1.0"?>
<sdf version="1.9">
  <model name="r">
    <link name="a"/>
    <link name="b"><pose>1 0 0 0 0 0</pose></link>
    <joint name="shoulder" type="ball">
      <parent>a</parent>
      <child>b</child>
    </joint>
  </model>
</sdf>
)";
  TempDir dir;
  const auto file = dir.write("r.sdf", text);
  const Error e = error_of([&] { load_sdf_robot(file.string(), isolated({})); });
  EXPECT_THAT(e.what(), HasSubstr("shoulder"));
  EXPECT_THAT(e.what(), HasSubstr("ball"));
  EXPECT_EQ(e.where().file, file.string());
  EXPECT_EQ(e.where().line, line_of(text, "<joint"));
}

TEST(SdfErrors, UnknownRobotUri) {
  const Error e = error_of([&] { load_sdf_robot("model://no_such_robot", isolated(), {"scenario.yaml", 7, "robots[0].model"}); });
  EXPECT_EQ(e.where().file, "scenario.yaml");
  EXPECT_EQ(e.where().line, 7);
  EXPECT_THAT(e.what(), HasSubstr((models_dir() / "no_such_robot").string()));
}

TEST(SdfErrors, NotSdfAtAll) {
  const Error e = error_of([&] { parse_sdf_world("<robot name=\"r\"/>", "r.sdf", isolated({})); });
  EXPECT_THAT(e.what(), HasSubstr("not SDF"));
}

}  // namespace
}  // namespace rescuesim
