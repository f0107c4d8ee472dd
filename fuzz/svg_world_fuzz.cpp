/// libFuzzer target for the SVG world loader: every input is a whole SVG document going
/// through load_svg_world_from_string — tinyxml2, units and scale, styles, shapes, layers,
/// victims, ramps, rubble, terrain — and, when it loads, through validate (which builds every
/// terrain element's solids) and back out through world_to_svg. rescuesim::Error
/// is the only failure the loader may report; any other exception, a crash or a sanitizer
/// finding is a bug.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "world/svg/svg_world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const SvgLoadResult r = load_svg_world_from_string(text, "fuzz.svg");
    (void)validate(r.world);
    world_to_svg(r.world);
  } catch (const Error&) {
  }
  return 0;
}
