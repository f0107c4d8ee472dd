#pragma once
/// Internal to import/svg: the geometry of one drawn element after the XML walk, in world
/// metres, with its computed style. svg_loader.cpp makes these; svg_build.cpp turns them into
/// walls, obstacles, raised areas, victims, rubble and robot starts.

#include <string>
#include <vector>

#include "core/error.h"
#include "import/svg/svg_parse.h"
#include "import/svg/svg_style.h"
#include "import/svg/svg_world.h"

namespace rescuesim::svg {

/// One drawn element.
struct Shape {
  enum class Tag { rect, circle, ellipse, line, polyline, polygon, path };
  Tag tag = Tag::path;
  std::vector<Subpath> subpaths;  ///< world coordinates (m)
  bool is_round = false;          ///< circle or ellipse: centre and radius below are exact
  Vec2 centre = Vec2::Zero();     ///< world (m), for round shapes
  double radius = 0;              ///< mean radius (m), for round shapes
  double stroke_width = 0;        ///< world (m)
  ComputedStyle style;
  std::string id;
  SourceRef source;
};

/// Turns the shapes of one file into a WorldSpec's contents, adding warnings to `diag`.
/// Throws Error for data-* values that cannot be read.
void build_world(const std::vector<Shape>& shapes, const SvgLoadOptions& options, WorldSpec& world, Diagnostics& diag);

/// Reads a data-* value in metres: "0.3", "30cm", "300mm", "0.3m"; throws Error naming the
/// attribute when it is not a positive finite length (or zero when `allow_zero`).
double data_metres(const Shape& s, const std::string& key, double fallback, bool allow_zero = false);
/// Reads a temperature: "310", "310K", "37C"; throws Error when unreadable or not above 0 K.
double data_kelvin(const Shape& s, const std::string& key, double fallback);
/// Reads a plain number; throws Error when unreadable.
double data_number(const Shape& s, const std::string& key, double fallback);

}  // namespace rescuesim::svg
