/// libFuzzer target for the SDF importer: every input goes through parse_sdf_world as SDF text —
/// sdformat's parser and pose graph, then everything rescuesim does with the DOM (models, links,
/// shapes, robots and their drive plugins, sensors, lights, victims and starts). model:// and
/// mesh URIs resolve inside an empty temporary folder with no Gazebo environment, so only the
/// built-in sun and ground_plane are found. rescuesim::Error is the only failure the importer
/// may report; any other exception, a crash or a sanitizer finding is a bug (sdformat itself is
/// Debian's library, uninstrumented: a crash inside it is reported too).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "import/sdf/sdf_import.h"

namespace {

using namespace rescuesim;

/// An empty folder in which model:// and relative URIs find nothing (one for every run: nothing
/// is written to it, and libFuzzer exits without running destructors).
const std::filesystem::path& empty_folder() {
  static const std::filesystem::path path = [] {
    const auto p = std::filesystem::temp_directory_path() / "rescuesim_sdf_fuzz_empty";
    std::filesystem::create_directories(p);
    return p;
  }();
  return path;
}

SdfOptions isolated_options() {
  SdfOptions o;
  o.resolver = ResourceResolver({empty_folder()}, false);
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const SdfOptions options = isolated_options();
  static const std::string file = (empty_folder() / "fuzz.sdf").string();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    parse_sdf_world(text, file, options);
  } catch (const Error&) {
  }
  return 0;
}
