/// libFuzzer target for the scenario reader: every input is scenario YAML going through
/// parse_scenario with the built-in robot models — yaml-cpp, the key checks, robots, sensors,
/// drives, world options. The file sits in an empty folder, so relative paths resolve to
/// nothing; nothing is loaded from disk. rescuesim::Error is the only failure the reader may
/// report; any other exception (a yaml-cpp one escaping, say), a crash or a sanitizer finding
/// is a bug.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "import/scenario/scenario.h"
#include "robots/rescue_robot.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  static const ModelMap models = builtin_models();
  static const std::string file =
      (std::filesystem::temp_directory_path() / "rescuesim_scenario_fuzz_empty" / "fuzz.yaml").string();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    parse_scenario(text, file, models);
  } catch (const Error&) {
  }
  return 0;
}
