#pragma once
// Fixtures for the SDF tests: the hand-written test data in tests/data/sdf, import options that
// see nothing of the environment, and look-ups into an imported world.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "import/sdf/sdf_import.h"
#include "import/urdf/urdf_test_files.h"

namespace rescuesim::sdf_test {

using urdf_test::error_of;
using urdf_test::line_of;
using urdf_test::ScopedEnv;
using urdf_test::TempDir;

/// tests/data/sdf: test_world.sdf and the models/ folder (ramp, skid_steer, skid_steer_classic).
inline std::filesystem::path data_dir() { return std::filesystem::path(RESCUESIM_SOURCE_DIR) / "tests" / "data" / "sdf"; }
inline std::filesystem::path models_dir() { return data_dir() / "models"; }

/// Options that find models in `folders` only (no ROS or Gazebo environment).
inline SdfOptions isolated(std::vector<std::filesystem::path> folders = {models_dir()}) {
  SdfOptions o;
  o.resolver = ResourceResolver(std::move(folders), false);
  return o;
}

/// The solid of this name; fails the test (and returns a default one) when there is none.
inline const SolidSpec& solid_named(const WorldSpec& w, const std::string& name) {
  static const SolidSpec none;
  for (const auto& s : w.solids) {
    if (s.name == name) return s;
  }
  ADD_FAILURE() << "no solid " << name;
  return none;
}

/// The model report of this name, or nullptr.
inline const SdfModelReport* report_named(const SdfWorld& w, const std::string& name) {
  for (const auto& m : w.models) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

/// Every warning of an import, one per line.
inline std::string warnings(const Diagnostics& d) {
  std::string out;
  for (const auto& x : d.items()) out += x.str() + "\n";
  return out;
}

/// Expects two poses to agree to `tol` (position in m, rotation as an angle in rad).
inline void expect_pose(const Pose3& actual, const Pose3& expected, double tol = 1e-9) {
  EXPECT_LT((actual.p - expected.p).norm(), tol) << actual.p.transpose() << " vs " << expected.p.transpose();
  EXPECT_LT(actual.q.angularDistance(expected.q), tol);
}

}  // namespace rescuesim::sdf_test
