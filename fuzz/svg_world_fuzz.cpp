/// libFuzzer target for the SVG world loader: every input is a whole SVG document going
/// through load_svg_world_from_string — tinyxml2, units and scale, styles, shapes, layers,
/// victims, ramps, rubble, terrain, smoke and dust — and, when it loads, through validate (which
/// builds every terrain element's solids), a ray through every valid medium at t = 10 s, and
/// back out through world_to_svg. rescuesim::Error
/// is the only failure the loader may report; any other exception, a crash or a sanitizer
/// finding is a bug.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "import/svg/svg_world.h"
#include "world/media.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const SvgLoadResult r = load_svg_world_from_string(text, "fuzz.svg");
    if (!validate(r.world).has_errors()) {
      std::vector<MediumVolume> media;
      std::vector<MediumSegment> segments;
      media_at(r.world.media, 10.0, SensingBand::near_infrared, media);
      const double tau = optical_depth(media, Vec3(0, 0, 0.3), Vec3(0.6, 0.8, 0), 30, segments);
      (void)distance_at_depth(segments, 0.5 * tau);
    }
    world_to_svg(r.world);
  } catch (const Error&) {
  }
  return 0;
}
