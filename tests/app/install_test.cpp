// An installed rescuesim, as a new user meets it (issue 19): `cmake --install` of this build
// into a fresh prefix under the system's temp folder, then, from a folder outside the source
// and build trees and with an environment that names neither, the installed CLI runs the
// default scenario, checks an installed world by its relative name, and Python imports the
// installed package and runs a few steps. Bad set-ups: a RESCUESIM_DATA_DIR that is not a data
// folder, and an installed copy whose data folder was removed, are refused with exit code 2
// and say where they looked.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "support/command.h"

namespace rescuesim {
namespace {

namespace fs = std::filesystem;

class Installed : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("rescuesim-install-test-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "home");
    const auto r =
        testing::run_command("cmake --install '" + std::string(RESCUESIM_BINARY_DIR) + "' --prefix '" + (root_ / "prefix").string() + "'");
    install_exit_ = r.exit_code;
    install_log_ = r.out + r.err;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  /// `command` in the home folder with only PATH (the prefix's bin first), HOME and `extra` set.
  static testing::CommandResult as_user(const std::string& command, const std::string& extra = "") {
    const std::string env =
        "env -i HOME='" + (root_ / "home").string() + "' PATH='" + (root_ / "prefix/bin").string() + ":/usr/bin:/bin' " + extra + " ";
    return testing::run_command(env + command, root_ / "home");
  }

  static inline fs::path root_;
  static inline int install_exit_ = -1;
  static inline std::string install_log_;
};

TEST_F(Installed, TheCliRunsAndFindsItsWorldsFromAnyFolder) {
  ASSERT_EQ(install_exit_, 0) << install_log_;
  const fs::path prefix = root_ / "prefix";
  EXPECT_TRUE(fs::exists(prefix / "bin/rescuesim"));
  EXPECT_TRUE(fs::exists(prefix / "bin/rescuesim-bench"));  // beside the CLI, which runs it for `rescuesim bench`
  EXPECT_TRUE(fs::exists(prefix / "share/rescuesim/worlds/team.yaml"));
  EXPECT_TRUE(fs::exists(prefix / "share/rescuesim/worlds/robots/turtlebot3_description/LICENSE"));  // licences stay with the data
  EXPECT_TRUE(fs::exists(prefix / "share/doc/rescuesim/README.md"));
  EXPECT_TRUE(fs::exists(prefix / "share/doc/rescuesim/missions.md"));

  // the default scenario, 5 s: its outputs where asked
  const auto run = as_user("rescuesim run --duration 5 --no-cameras --out out");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_TRUE(fs::exists(root_ / "home/out/summary.json")) << run.out;
  EXPECT_NE(run.out.find("5.0 s simulated"), std::string::npos) << run.out;

  // a shipped world by the name the README uses, though there is no worlds/ folder here
  const auto check = as_user("rescuesim check worlds/team.yaml");
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find((prefix / "share/rescuesim/worlds/team.yaml").string() + ": ok"), std::string::npos) << check.out;
  // and a URDF robot world whose package:// meshes resolve inside the installed data
  const auto urdf = as_user("rescuesim run worlds/turtlebot3_maze.yaml --duration 1 --no-cameras --out out2");
  EXPECT_EQ(urdf.exit_code, 0) << urdf.out << urdf.err;
}

TEST_F(Installed, PythonImportsTheInstalledPackage) {
  ASSERT_EQ(install_exit_, 0) << install_log_;
  fs::path site;
  for (const auto& e : fs::directory_iterator(root_ / "prefix/lib")) {
    if (e.path().filename().string().rfind("python3", 0) == 0) site = e.path() / "dist-packages";
  }
  if (site.empty() || !fs::exists(site / "rescuesim")) GTEST_SKIP() << "the Python API is not built here (RESCUESIM_PYTHON)";
  const auto py = as_user("/usr/bin/python3 -c \"import rescuesim; e = rescuesim.Env(rescuesim.default_scenario(), cameras=False); "
                          "e.reset(seed=3); [e.step([0.2, 0.0]) for _ in range(10)]; print(rescuesim.__file__)\"",
                          "PYTHONPATH='" + site.string() + "'");
  EXPECT_EQ(py.exit_code, 0) << py.out << py.err;
  EXPECT_NE(py.out.find(site.string()), std::string::npos) << py.out;  // this package, not the build tree's
}

TEST_F(Installed, AWrongDataFolderIsAClearError) {
  ASSERT_EQ(install_exit_, 0) << install_log_;
  const auto wrong = as_user("rescuesim run --duration 1", "RESCUESIM_DATA_DIR=/nonexistent/share/rescuesim");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("RESCUESIM_DATA_DIR=/nonexistent/share/rescuesim is not a rescuesim data folder"), std::string::npos)
      << wrong.err;

  // an installed copy whose data went: a shipped world cannot be found, and it says where it looked
  if (fs::exists("/usr/local/share/rescuesim/worlds")) GTEST_SKIP() << "a rescuesim is installed in /usr/local: it would be found";
  fs::rename(root_ / "prefix/share/rescuesim", root_ / "moved-away");
  const auto missing = as_user("rescuesim run worlds/team.yaml --duration 1");
  fs::rename(root_ / "moved-away", root_ / "prefix/share/rescuesim");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("worlds/team.yaml: no such file; looked in"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find((root_ / "prefix/share/rescuesim").string()), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("RESCUESIM_DATA_DIR"), std::string::npos) << missing.err;
}

TEST(DebPackage, HoldsTheProgramItsDataAndComputedDepends) {
  // what `make deb` does, into a folder of the test's own
  const fs::path dir = fs::temp_directory_path() / ("rescuesim-deb-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto pack =
      testing::run_command("cpack --config '" + std::string(RESCUESIM_BINARY_DIR) + "/CPackConfig.cmake' -G DEB -B '" + dir.string() + "'");
  ASSERT_EQ(pack.exit_code, 0) << pack.out << pack.err;
  fs::path deb;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".deb") deb = e.path();
  }
  ASSERT_FALSE(deb.empty()) << pack.out;
  EXPECT_EQ(deb.filename().string().rfind("rescuesim_", 0), 0u) << deb;

  const auto info = testing::run_command("dpkg-deb --info '" + deb.string() + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("Package: rescuesim"), std::string::npos) << info.out;
  // Depends comes from dpkg-shlibdeps: the runtime packages of the libraries linked
  const auto depends = testing::run_command("dpkg-deb --field '" + deb.string() + "' Depends");
  // (and, listed by hand, what is dlopened: EGL and Mesa for the headless cameras)
  for (const char* lib : {"libbullet", "libembree3", "libyaml-cpp", "libegl-mesa0", "libgl1-mesa-dri"}) {
    EXPECT_NE(depends.out.find(lib), std::string::npos) << lib << " is not in: " << depends.out;
  }
  // and every package it names exists: installed here, where it was built, or provided by an
  // installed package (dpkg's shlibs name virtual packages such as libspdlog1.10-fmt9)
  const std::string provided = testing::run_command("dpkg-query -W -f='${Provides}, '").out;
  std::string names = depends.out;
  for (char& c : names) {
    if (c == ',') c = ' ';
  }
  std::istringstream words(names);
  int checked = 0;
  for (std::string w; words >> w;) {
    if (w.front() == '(' || w.back() == ')' || w == "|") continue;  // version constraints
    const auto q = testing::run_command("dpkg-query -W -f='${Status}' '" + w + "'");
    const bool installed = q.out.find("install ok installed") != std::string::npos;
    const bool virtual_provided =
        (", " + provided).find(", " + w + " ") != std::string::npos || (", " + provided).find(", " + w + ",") != std::string::npos;
    EXPECT_TRUE(installed || virtual_provided) << "Depends names " << w << ", which nothing installed here is or provides";
    ++checked;
  }
  EXPECT_GT(checked, 5);

  const auto contents = testing::run_command("dpkg-deb --contents '" + deb.string() + "'");
  for (const char* f : {"./usr/bin/rescuesim", "./usr/bin/rescuesim-bench", "./usr/share/rescuesim/worlds/team.yaml",
                        "./usr/share/doc/rescuesim/LICENSE", "./usr/share/rescuesim/worlds/robots/turtlebot3_description/LICENSE"}) {
    EXPECT_NE(contents.out.find(f), std::string::npos) << f;
  }
  // Debian's python3 reads /usr/lib/python3/dist-packages
  if (fs::exists(fs::path(RESCUESIM_BINARY_DIR) / "python/rescuesim")) {
    EXPECT_NE(contents.out.find("./usr/lib/python3/dist-packages/rescuesim/__init__.py"), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(Wheel, PipInstallsItIntoAVenvAndTheExamplesRun) {
  if (!fs::exists(fs::path(RESCUESIM_BINARY_DIR) / "python/rescuesim")) {
    GTEST_SKIP() << "the Python API is not built here (RESCUESIM_PYTHON)";
  }
  const fs::path dir = fs::temp_directory_path() / ("rescuesim-wheel-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "home");
  // what `make wheel` does, into a folder of the test's own
  const auto made = testing::run_command("'" + std::string(RESCUESIM_SOURCE_DIR) + "/scripts/make-wheel.sh' '" + RESCUESIM_BINARY_DIR +
                                         "' '" + (dir / "dist").string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.out << made.err;
  fs::path wheel;
  for (const auto& e : fs::directory_iterator(dir / "dist")) {
    if (e.path().extension() == ".whl") wheel = e.path();
  }
  ASSERT_FALSE(wheel.empty()) << made.out;
  // tagged for this interpreter and platform, not "none-any": it holds a compiled module
  EXPECT_NE(wheel.filename().string().find("-linux_"), std::string::npos) << wheel;

  // a venv that sees Debian's numpy; pip offline
  const auto venv = testing::run_command("/usr/bin/python3 -m venv --system-site-packages '" + (dir / "venv").string() + "'");
  ASSERT_EQ(venv.exit_code, 0) << venv.err;
  const auto pip = testing::run_command("'" + (dir / "venv/bin/pip").string() + "' install --no-index '" + wheel.string() + "'");
  ASSERT_EQ(pip.exit_code, 0) << pip.out << pip.err;

  // the examples, from a folder outside both trees, with an environment that names neither
  const std::string env = "env -i HOME='" + (dir / "home").string() + "' PATH=/usr/bin:/bin '" + (dir / "venv/bin/python").string() + "' ";
  const std::string examples = std::string(RESCUESIM_SOURCE_DIR) + "/examples/python/";
  const auto agent = testing::run_command(env + "'" + examples + "random_agent.py' --episodes 1 --max-time 3", dir / "home");
  EXPECT_EQ(agent.exit_code, 0) << agent.out << agent.err;
  EXPECT_NE(agent.out.find("episode 0 (seed 1)"), std::string::npos) << agent.out;
  const auto team = testing::run_command(env + "'" + examples + "mission_team.py' --max-time 5", dir / "home");
  EXPECT_EQ(team.exit_code, 0) << team.out << team.err;
  const auto where = testing::run_command(env + "-c 'import rescuesim; print(rescuesim.__file__)'", dir / "home");
  EXPECT_NE(where.out.find((dir / "venv").string()), std::string::npos) << where.out;  // the wheel's, not the build tree's
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rescuesim
