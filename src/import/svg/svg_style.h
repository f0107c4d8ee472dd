#pragma once
/// Style resolution for the SVG loader: presentation attributes, the `style` attribute and
/// simple `<style>` sheets, with inheritance through groups. Internal to import/svg.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "import/svg/svg_parse.h"

namespace tinyxml2 {
class XMLElement;
}

namespace rescuesim::svg {

/// One `property: value` pair.
struct Declaration {
  std::string property;
  std::string value;
};

/// Parses `a: b; c: d` (as in a style attribute); malformed parts are skipped.
std::vector<Declaration> parse_declarations(std::string_view text);

/// A minimal CSS sheet: rules with `*`, `tag`, `.class`, `#id` and `tag.class` selectors.
class StyleSheet {
 public:
  /// Adds the rules of one `<style>` element's text; returns how many selectors were not understood.
  int add(std::string_view css);
  /// Declarations matching an element, lowest specificity first (later rules win ties).
  std::vector<Declaration> match(const tinyxml2::XMLElement& e) const;
  bool empty() const { return rules_.empty(); }

 private:
  struct Rule {
    std::string tag, cls, id;  ///< empty = any
    int specificity = 0;
    int order = 0;
    std::vector<Declaration> decls;
  };
  std::vector<Rule> rules_;
};

/// The computed style of an element: inherited properties plus data-* settings.
struct ComputedStyle {
  Paint fill{Paint::Kind::color, Vec3::Zero(), {}};  ///< SVG's initial fill is black
  Paint stroke{Paint::Kind::none, Vec3::Zero(), {}};
  double stroke_width = 1.0;        ///< user units
  std::string linecap = "butt";
  bool visible = true;              ///< visibility (inherited)
  bool displayed = true;            ///< display (not inherited, but hides the subtree)
  Vec3 color = Vec3::Zero();        ///< `color`, for currentColor
  std::map<std::string, std::string> data;  ///< data-* attributes, inherited through groups
  std::vector<std::string> bad_paints;      ///< paint values that could not be parsed, for warnings
};

/// Computes an element's style from its parent's, in cascade order: presentation attributes,
/// then the sheet, then the `style` attribute.
ComputedStyle compute_style(const tinyxml2::XMLElement& e, const ComputedStyle& parent, const StyleSheet& sheet);

}  // namespace rescuesim::svg
