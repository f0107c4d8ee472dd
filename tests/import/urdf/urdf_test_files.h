#pragma once
// Fixtures for the URDF tests, written by the tests themselves: a temporary folder per test,
// a binary STL writer, closed box and prism meshes, environment variables set for one scope,
// the Error a call throws, and look-ups into an imported robot.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/error.h"
#include "import/mesh/mesh_test_files.h"
#include "import/urdf/urdf_import.h"
#include "world/geometry.h"

namespace rescuesim::urdf_test {

/// The TurtleBot3 description shipped in worlds/robots (ROBOTIS, Apache-2.0).
inline std::filesystem::path robots_dir() { return std::filesystem::path(RESCUESIM_SOURCE_DIR) / "worlds" / "robots"; }
inline std::filesystem::path turtlebot3_urdf(const std::string& model) {
  return robots_dir() / "turtlebot3_description" / "urdf" / ("turtlebot3_" + model + ".urdf");
}

using mesh_test::binary_stl;
using mesh_test::put;
using mesh_test::TempDir;

/// A closed prism: the counter-clockwise polygon `xz` in the x-z plane (seen from -y, so x
/// right and z up), extruded from y = -half_width to +half_width; outward-facing triangles.
inline TriangleMesh xz_prism(const std::vector<Vec2>& xz, double half_width) {
  TriangleMesh m;
  const int n = static_cast<int>(xz.size());
  for (double y : {-half_width, half_width}) {
    for (const Vec2& p : xz) m.vertices.emplace_back(p.x(), y, p.y());
  }
  // x cross z = -y: the polygon's own order faces the -y cap outward, the reverse the +y cap
  for (int i = 1; i + 1 < n; ++i) {
    m.triangles.push_back({0, i, i + 1});
    m.triangles.push_back({n, n + i + 1, n + i});
  }
  // each edge i -> j swept along +y
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, n + i, n + j});
    m.triangles.push_back({i, n + j, j});
  }
  return m;
}

/// A closed axis-aligned box from `lo` to `hi`.
inline TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m = xz_prism({{lo.x(), lo.z()}, {hi.x(), lo.z()}, {hi.x(), hi.z()}, {lo.x(), hi.z()}}, 0.5 * (hi.y() - lo.y()));
  for (Vec3& v : m.vertices) v.y() += 0.5 * (lo.y() + hi.y());
  return m;
}

/// Sets (or, with nullopt, unsets) an environment variable until the end of the scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      ::setenv(name, value->c_str(), 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

/// The Error `f` throws; fails the test (and returns an empty Error) when it throws nothing.
template <typename F>
Error error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected a rescuesim::Error, nothing was thrown";
  return Error("(nothing thrown)");
}

/// Import options that look for meshes nowhere but relative to the URDF (no ROS or Gazebo
/// environment).
inline UrdfOptions no_environment() {
  UrdfOptions o;
  o.resolver = ResourceResolver({}, false);
  return o;
}

/// The link of this name; fails the test (and returns the first link) when there is none.
inline const LinkSpec& link_named(const RobotSpec& r, const std::string& name) {
  const int i = r.link_index(name);
  EXPECT_GE(i, 0) << "no link " << name;
  return r.links.at(static_cast<std::size_t>(std::max(i, 0)));
}

/// The joint of this name; fails the test (and returns the first joint) when there is none.
inline const JointSpec& joint_named(const RobotSpec& r, const std::string& name) {
  const int i = r.joint_index(name);
  EXPECT_GE(i, 0) << "no joint " << name;
  return r.joints.at(static_cast<std::size_t>(std::max(i, 0)));
}

/// Every warning of an import, one per line, for failure messages and searches.
inline std::string warnings(const UrdfRobot& u) {
  std::string out;
  for (const auto& d : u.diagnostics.items()) out += d.str() + "\n";
  return out;
}

/// The line (1-based) of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())), '\n'));
}

}  // namespace rescuesim::urdf_test
