// The rescuesim command line as a user meets it: help, exit codes, and clear errors for bad
// input files (each class of bad input has its own test).

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <utility>
#include <vector>

#include "support/command.h"

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::temp_dir;
using testing::write_text;

TEST(Cli, HelpListsTheSubcommands) {
  const auto r = rescuesim("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* sub : {"run", "maze", "check"}) EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
}

TEST(Cli, UnknownOptionIsAUsageError) {
  const auto r = rescuesim("maze --no-such-option");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no-such-option"), std::string::npos) << r.err;
}

TEST(Cli, NoSubcommandIsAUsageError) { EXPECT_EQ(rescuesim("").exit_code, 2); }

class CheckBadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = temp_dir("check-bad"); }
  /// Writes `text` to a file and runs `rescuesim check` on it.
  testing::CommandResult check(const std::string& name, const std::string& text) {
    const auto p = dir_ / name;
    write_text(p, text);
    return rescuesim("check '" + p.string() + "'");
  }
  std::filesystem::path dir_;
};

TEST_F(CheckBadInput, MalformedXmlNamesFileAndLine) {
  const auto r = check("broken.svg", "<svg viewBox=\"0 0 100 100\">\n<rect width=\"10\" height=\"10\">\n</svg>\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("broken.svg:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("malformed XML"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, UnclosedPathDataNamesTheElement) {
  const auto r = check("path.svg", "<svg viewBox=\"0 0 100 100\">\n  <path id=\"p1\" d=\"M 10 10 L\" stroke=\"#000\"/>\n</svg>\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("path.svg:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("<path id=\"p1\">"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, NanCoordinateIsRejected) {
  const auto r = check("nan.svg", "<svg viewBox=\"0 0 100 100\"><rect x=\"NaN\" width=\"10\" height=\"10\"/></svg>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("attribute x"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, HugeNumberIsRejected) {
  const auto r = check("huge.svg", "<svg viewBox=\"0 0 100 100\"><line x1=\"0\" y1=\"0\" x2=\"1e400\" y2=\"5\" stroke=\"black\"/></svg>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("x2"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, AbsurdlyLargeWorldIsRejected) {
  // finite numbers, but a world 10^8 m wide: validation refuses it
  const auto r = check("vast.svg", "<svg viewBox=\"0 0 1e9 100\"><line x1=\"0\" y1=\"50\" x2=\"1e9\" y2=\"50\" stroke=\"black\"/></svg>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("exceeds the limit"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, ZeroSizeViewBoxIsRejected) {
  const auto r = check("zero.svg", "<svg viewBox=\"0 0 0 100\"><rect width=\"10\" height=\"10\"/></svg>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("viewBox"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, EmptyFile) {
  const auto r = check("empty.svg", "");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, BinaryGarbage) {
  std::string junk;
  for (int i = 0; i < 4096; ++i) junk.push_back(static_cast<char>((i * 7919 + 13) & 0xff));
  const auto r = check("junk.svg", junk);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("junk.svg"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("binary"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, FiftyMegabyteFileIsRefusedBySize) {
  const auto p = dir_ / "big.svg";
  {
    std::ofstream f(p, std::ios::binary);
    f << "<svg viewBox=\"0 0 100 100\">";
    const std::string line(1023, ' ');
    for (int i = 0; i < 50 * 1024; ++i) f << line << '\n';
    f << "</svg>";
  }
  const auto r = rescuesim("check '" + p.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("MB"), std::string::npos) << r.err;
  std::filesystem::remove(p);
}

TEST_F(CheckBadInput, MissingFile) {
  const auto r = rescuesim("check '" + (dir_ / "nope.svg").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.svg"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, NotAnSvgRoot) {
  const auto r = check("html.svg", "<html><body/></html>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("expected <svg>"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, EmptyWorld) {
  const auto r = check("blank.svg", "<svg viewBox=\"0 0 100 100\"><rect width=\"100\" height=\"100\" fill=\"white\"/></svg>");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;
}

TEST_F(CheckBadInput, StartInsideAWallIsNamed) {
  const auto r = check("start.svg",
                       "<svg viewBox=\"0 0 500 500\">\n"
                       "<line id=\"wall1\" x1=\"0\" y1=\"250\" x2=\"500\" y2=\"250\" stroke=\"black\" stroke-width=\"10\"/>\n"
                       "<circle id=\"robot\" cx=\"100\" cy=\"260\" r=\"20\" fill=\"#00c000\"/>\n</svg>\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("<circle id=\"robot\">"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("wall1"), std::string::npos) << r.err;
}

// Ground areas (docs/terrain.md, "Ground materials"): each bad kind is exit 2 with the file, the
// line and the element.
TEST_F(CheckBadInput, BadGroundAreasAreNamed) {
  const auto world = [](const std::string& area) {
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"5m\" height=\"5m\" viewBox=\"0 0 500 500\">\n" + area +
           "\n<line x1=\"0\" y1=\"0\" x2=\"500\" y2=\"0\" stroke=\"black\" stroke-width=\"5\"/>\n</svg>\n";
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"(<rect id="pit" x="100" y="100" width="200" height="100" data-kind="ground" data-material="lava"/>)", "unknown material 'lava'"},
      {R"(<rect id="pit" x="100" y="100" width="200" height="100" data-kind="ground"/>)", "a ground area needs data-material"},
      {R"(<polyline id="pit" points="100,100 200,100 300,100" data-kind="ground" data-material="sand"/>)",
       "needs a footprint with an area"},
      {R"(<rect id="a" x="0" y="300" width="100" height="100" data-kind="ground" data-material="sand"/>
<rect id="pit" x="50" y="350" width="100" height="100" data-kind="ground" data-material="wood"/>)",
       "overlaps ground area 'a'"},
  };
  for (const auto& [area, message] : cases) {
    const auto r = check("ground.svg", world(area));
    EXPECT_EQ(r.exit_code, 2) << area;
    EXPECT_NE(r.err.find("ground.svg:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
}

TEST(CheckGood, SummaryOfASmallWorld) {
  const auto dir = temp_dir("check-good");
  write_text(dir / "room.svg",
             "<svg width=\"4m\" height=\"3m\" viewBox=\"0 0 400 300\">\n"
             "<rect x=\"0\" y=\"0\" width=\"400\" height=\"300\" fill=\"none\" stroke=\"black\" stroke-width=\"10\"/>\n"
             "<rect x=\"250\" y=\"100\" width=\"60\" height=\"60\" fill=\"red\"/>\n"
             "<rect x=\"100\" y=\"200\" width=\"120\" height=\"40\" fill=\"blue\"/>\n"
             "<circle cx=\"80\" cy=\"80\" r=\"20\" fill=\"green\"/>\n</svg>\n");
  const auto r = rescuesim("check '" + (dir / "room.svg").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4.00 x 3.00 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("walls         4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("raised areas  1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("victims       1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("robot starts  1"), std::string::npos) << r.out;
}

TEST(MazeCommand, WritesByteIdenticalFilesForTheSameSeedThatCheckAccepts) {
  const auto a = temp_dir("maze-a"), b = temp_dir("maze-b");
  const std::string args = "maze --seed 11 --count 2 --cols 6 --rows 5 --victims 3 --rubble 4 --raised 0.1 --loops 0.2 --out ";
  ASSERT_EQ(rescuesim(args + "'" + a.string() + "'").exit_code, 0);
  ASSERT_EQ(rescuesim(args + "'" + b.string() + "'").exit_code, 0);
  for (const char* f : {"maze-11.svg", "maze-12.svg", "maze-11.png", "maze-12.png"}) {
    ASSERT_TRUE(std::filesystem::exists(a / f)) << f;
    EXPECT_EQ(testing::slurp(a / f), testing::slurp(b / f)) << f;
  }
  EXPECT_NE(testing::slurp(a / "maze-11.svg"), testing::slurp(a / "maze-12.svg"));
  const auto r = rescuesim("check '" + (a / "maze-11.svg").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("victims       3"), std::string::npos) << r.out;
}

TEST(RunCommand, UnknownScenarioKeyNamesTheKeyPath) {
  const auto dir = temp_dir("run-bad");
  write_text(dir / "s.yaml", "name: t\nworld:\n  maze:\n    cols: 4\n    colls: 5\n");
  const auto r = rescuesim("run '" + (dir / "s.yaml").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("s.yaml:5"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("world.maze.colls"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::temp_dir;
using testing::write_text;

TEST(RunCommand, ImpossibleSensorSettingIsABadInputError) {
  const auto dir = temp_dir("run-sensor");
  write_text(dir / "s.yaml", "robots:\n  - name: r\n    sensors:\n      laser: {fov: 0}\n");
  const auto r = rescuesim("run '" + (dir / "s.yaml").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("robots[0].sensors.laser.fov"), std::string::npos) << r.err;
}

TEST(RunCommand, MissingScenarioFileIsNamed) {
  const auto r = rescuesim("run /nonexistent/scenario.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/scenario.yaml"), std::string::npos) << r.err;
}

TEST(RunCommand, MissingWorldFileNamedInAScenario) {
  const auto dir = temp_dir("run-world");
  write_text(dir / "s.yaml", "world:\n  svg: nowhere.svg\n");
  const auto r = rescuesim("run '" + (dir / "s.yaml").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nowhere.svg"), std::string::npos) << r.err;
}

TEST(RunCommand, ShortRunWritesItsOutputs) {
  const auto dir = temp_dir("run-short");
  const auto r = rescuesim("run --duration 5 --quiet --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"summary.json", "overview.png", "trajectory.csv", "world.svg", "sensors/laser.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  }
  EXPECT_NE(r.out.find("5.0 s simulated"), std::string::npos) << r.out;
}

TEST(RunCommand, RealtimeModeIsPacedByTheWallClock) {
  const auto dir = temp_dir("run-realtime");
  const auto t0 = std::chrono::steady_clock::now();
  // 2 s of sim time at 4x real time must take at least 0.5 s of wall time
  const auto r = rescuesim("run --duration 2 --realtime --rate 4 --quiet --out '" + (dir / "out").string() + "'");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GE(wall, 0.5);
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

TEST(RunCameras, NoEglIsSaidPlainlyWithExitCode2) {
  // point libglvnd at no vendor at all: as on a machine without any EGL driver
  const auto r = testing::run_command(std::string("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json '") + RESCUESIM_EXE +
                                      "' run --duration 1 -q --out '" + testing::temp_dir("no-egl").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no EGL display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-cameras"), std::string::npos) << r.err;
}

TEST(RunCameras, WithoutCamerasNoEglIsNeeded) {
  const auto r = testing::run_command(std::string("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json '") + RESCUESIM_EXE +
                                      "' run --duration 1 -q --no-cameras --out '" + testing::temp_dir("no-egl-ok").string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(RunCommand, SaysHowLongAfterItsStartTheFirstScanCame) {
  // the default scenario's laser scans at 0 s of sim time: the line names /scan and a time since
  // exec (a count of the kernel's clock ticks; no bound on it here, that is the bench's)
  const auto r = testing::rescuesim("run --duration 0.2 -q --no-cameras --out '" + temp_dir("cold-start").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.out.find("cold start: first scan (/scan) ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double s = std::stod(r.out.substr(at + std::string("cold start: first scan (/scan) ").size()));
  EXPECT_GT(s, 0.0);
  EXPECT_NE(r.out.find(" s after the process started", at), std::string::npos) << r.out;
}

TEST(RunCommand, OneWorkerThreadOrTwoWriteTheSameTrajectories) {
  // three robots with built-in controllers: sensors and controllers run on the worker threads
  std::string traj[2];
  for (int threads : {1, 2}) {
    const auto dir = temp_dir("threads-" + std::to_string(threads));
    const auto r = testing::rescuesim("--threads " + std::to_string(threads) +
                                      " run worlds/team.yaml --duration 5 -q --no-cameras --out '" + dir.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    traj[threads - 1] = testing::slurp(dir / "trajectory.csv");
  }
  EXPECT_GT(traj[0].size(), 1000u);
  EXPECT_EQ(traj[0], traj[1]);
}

TEST(RunCommand, ThreadsMustBeACount) {
  const auto r = testing::rescuesim("--threads -1 run");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
}

TEST(RunCommand, PausedNeedsALiveBridgeAndTheDistroIsChecked) {
  // nothing could play a paused run without a bridge: a usage error, before anything is built
  auto r = testing::rescuesim("run --paused --no-cameras --duration 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--paused needs a live bridge"), std::string::npos) << r.err;
  r = testing::rescuesim("run --ros2 --ros2-distro foxy --duration 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--ros2-distro"), std::string::npos) << r.err;
}

TEST(RunCameras, ZeroOrHugeResolutionAndBadFovAreRejected) {
  const auto dir = testing::temp_dir("cam-bad");
  const char* bad[] = {"color_camera: {width: 0}", "depth_camera: {height: 100000}", "thermal_camera: {hfov: 180}",
                       "color_camera: {hfov: 0}"};
  for (const char* b : bad) {
    testing::write_text(dir / "s.yaml", std::string("robots:\n  - name: r\n    sensors:\n      ") + b + "\n");
    const auto r = testing::rescuesim("run '" + (dir / "s.yaml").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << b;
    EXPECT_NE(r.err.find("robots[0].sensors."), std::string::npos) << b << ": " << r.err;
  }
}

}  // namespace
}  // namespace rescuesim
