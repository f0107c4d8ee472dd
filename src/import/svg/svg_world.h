#pragma once
/// Reading and writing worlds as SVG drawings in the colour convention of docs/worlds.md.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.h"
#include "world/world_spec.h"

namespace rescuesim {

/// Settings for reading an SVG world; the defaults come from the scenario.
struct SvgLoadOptions {
  double units_per_metre = 100.0;   ///< scale when the file has no physical units
  double wall_height = 1.0;         ///< m, stroked black shapes
  double obstacle_height = 1.0;     ///< m, filled black shapes
  double raised_height = 0.12;      ///< m
  double ramp_length = 0.5;         ///< m
  double rubble_height = 0.15;      ///< m
  double rubble_density = 400.0;    ///< kg/m^3, when an element gives no data-mass
  double victim_length = 1.2;       ///< m, for victims drawn as markers (squares, circles)
  double victim_width = 0.4;        ///< m, likewise
  double curve_tolerance = 0.005;   ///< m, largest deviation of flattened curves
  double ambient_temperature = 293.15;  ///< K
  std::size_t max_file_bytes = std::size_t(32) << 20;  ///< larger files are refused
};

/// A loaded world and what was noticed on the way.
struct SvgLoadResult {
  WorldSpec world;
  Diagnostics diagnostics;      ///< warnings (unknown colours, ignored elements); never errors
  double metres_per_unit = 0;   ///< the scale that was used
  std::string scale_source;     ///< e.g. "width=\"12m\"" or "default 100 units/m"
};

/// Reads an SVG world file. Throws `Error` (naming the file and the line or element) for
/// unreadable, empty, binary, oversize or malformed files and bad attribute values.
SvgLoadResult load_svg_world(const std::filesystem::path& file, const SvgLoadOptions& options = {});

/// Same, from text in memory; `name` stands for the file name in messages.
SvgLoadResult load_svg_world_from_string(std::string_view text, const std::string& name,
                                         const SvgLoadOptions& options = {});

/// Writes a WorldSpec as an SVG in the same convention, 1 user unit = 1 cm, with
/// `width`/`height` in cm; everything needed to read it back (heights, ramps, masses,
/// postures, temperatures, names) is in data-* attributes; `world.seed` and `world.metadata`
/// are recorded on the root element.
std::string world_to_svg(const WorldSpec& world);

}  // namespace rescuesim
