/// libFuzzer target for the URDF importer: every input goes through parse_urdf as URDF text —
/// XML, xacro refusal, the structure checks, urdfdom, inertials, joints, Gazebo plugins and
/// sensors. Mesh URIs resolve inside an empty temporary folder with no ROS or Gazebo
/// environment, so they all fail cleanly. rescuesim::Error is the only failure the importer may
/// report; any other exception, a crash or a sanitizer finding is a bug.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "import/urdf/urdf_import.h"

namespace {

using namespace rescuesim;

/// An empty folder in which relative and package:// mesh URIs find nothing. One name for every
/// run and job: nothing is ever written to it, and libFuzzer exits without running destructors,
/// so a folder per process would be left behind each time.
const std::filesystem::path& empty_folder() {
  static const std::filesystem::path path = [] {
    const auto p = std::filesystem::temp_directory_path() / "rescuesim_urdf_fuzz_empty";
    std::filesystem::create_directories(p);
    return p;
  }();
  return path;
}

UrdfOptions isolated_options() {
  UrdfOptions o;
  o.resolver = ResourceResolver({empty_folder()}, false);
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const UrdfOptions options = isolated_options();
  static const std::string file = (empty_folder() / "fuzz.urdf").string();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    parse_urdf(text, file, options);
  } catch (const Error&) {
  }
  return 0;
}
