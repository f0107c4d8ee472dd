#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <filesystem>
#include <set>
#include <string>

#include "core/atomic_file.h"
#include "import/svg/svg_shapes.h"

namespace rescuesim {

namespace {

using svg::ComputedStyle;
using svg::Shape;
using tinyxml2::XMLElement;

constexpr int kMaxDepth = 200;                   // nesting of groups and clones
constexpr std::size_t kMaxVertices = 5'000'000;  // all flattened points of a file

std::string_view local_name(const XMLElement& e) {
  std::string_view n(e.Name());
  const auto colon = n.find(':');
  return colon == std::string_view::npos ? n : n.substr(colon + 1);
}

/// `<rect id="w3">` for messages.
std::string describe(const XMLElement& e) {
  std::string s = "<" + std::string(e.Name());
  if (const char* id = e.Attribute("id")) s += std::string(" id=\"") + id + "\"";
  return s + ">";
}

/// Rejects input that is not text before XML parsing gets to it.
void check_text(std::string_view text, const std::string& file) {
  bool blank = true;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) {
      blank = false;
      break;
    }
  }
  if (blank) throw Error({file, 0, ""}, "the file is empty; expected an SVG document");
  // binary data: NUL bytes or invalid UTF-8
  std::size_t i = 0;
  int line = 1;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    int extra = 0;
    if (c == '\n') ++line;
    if (c == 0 || (c < 0x20 && c != '\n' && c != '\r' && c != '\t')) {
      throw Error({file, line, ""}, "binary data (control byte 0x" + std::string(1, "0123456789abcdef"[c >> 4]) +
                                        std::string(1, "0123456789abcdef"[c & 15]) + " at byte " + std::to_string(i) +
                                        "); expected an SVG text file");
    }
    if (c >= 0x80) {
      if ((c & 0xE0) == 0xC0) extra = 1;
      else if ((c & 0xF0) == 0xE0) extra = 2;
      else if ((c & 0xF8) == 0xF0) extra = 3;
      else extra = -1;
      bool ok = extra > 0 && i + static_cast<std::size_t>(extra) < text.size();
      for (int k = 1; ok && k <= extra; ++k) ok = (static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]) & 0xC0) == 0x80;
      if (!ok) {
        throw Error({file, line, ""}, "binary data (invalid UTF-8 at byte " + std::to_string(i) + "); expected an SVG text file");
      }
    }
    i += 1 + static_cast<std::size_t>(std::max(extra, 0));
  }
}

/// The walk over the XML tree, producing shapes in document order.
class Walker {
 public:
  Walker(const std::string& file, const SvgLoadOptions& options, Diagnostics& diag, const tinyxml2::XMLDocument& doc)
      : file_(file), options_(options), diag_(diag) {
    index_ids(doc.RootElement());
  }

  /// Reads the root `<svg>`: floor size and the map from user units to world metres.
  void read_root(const XMLElement& root, WorldSpec& world, double& metres_per_unit, std::string& scale_source) {
    const SourceRef where = ref(root);
    double vb[4] = {0, 0, 0, 0};
    bool has_vb = false;
    if (const char* v = root.Attribute("viewBox")) {
      std::size_t pos = 0;
      const std::string_view s(v);
      try {
        for (double& x : vb) x = svg::read_number(s, pos);
        if (!svg::at_end(s, pos)) throw svg::ParseError("expected exactly 4 numbers", pos);
      } catch (const svg::ParseError& e) {
        throw Error(with(where, "viewBox"), std::string(e.what()) + " (expected 'min-x min-y width height')");
      }
      if (!(vb[2] > 0) || !(vb[3] > 0)) {
        throw Error(with(where, "viewBox"),
                    "width and height must be positive, got " + message_number(vb[2]) + " x " + message_number(vb[3]));
      }
      has_vb = true;
    }
    const auto length_attr = [&](const char* name) -> std::optional<svg::Length> {
      const char* v = root.Attribute(name);
      if (!v) return std::nullopt;
      try {
        const svg::Length l = svg::parse_length(v);
        if (!(l.value > 0)) throw svg::ParseError("must be positive", 0);
        return l;
      } catch (const svg::ParseError& e) {
        throw Error(with(where, name), std::string("'") + v + "': " + e.what());
      }
    };
    const auto width = length_attr("width");
    const auto height = length_attr("height");
    if (!has_vb && width && height && width->unit != svg::Unit::percent && height->unit != svg::Unit::percent) {
      vb[2] = width->user_units();
      vb[3] = height->user_units();
      has_vb = true;
    }

    // scale: physical units in width/height win, else the scenario setting
    const double default_mpu = 1.0 / options_.units_per_metre;
    metres_per_unit = default_mpu;
    scale_source = "default " + message_number(options_.units_per_metre) + " units per metre";
    if (has_vb && width && width->physical()) {
      metres_per_unit = width->metres() / vb[2];
      scale_source = "width=\"" + std::string(root.Attribute("width")) + "\" over a viewBox " + message_number(vb[2]) + " wide";
      if (height && height->physical()) {
        const double mpu_y = height->metres() / vb[3];
        if (std::abs(mpu_y - metres_per_unit) > 0.01 * metres_per_unit) {
          diag_.warn(where, "width and height give different scales (" + message_number(1 / metres_per_unit) + " and " +
                                message_number(1 / mpu_y) + " units per metre); using the width's");
        }
      }
    } else if (has_vb && height && height->physical()) {
      metres_per_unit = height->metres() / vb[3];
      scale_source = "height=\"" + std::string(root.Attribute("height")) + "\"";
    }
    if (!std::isfinite(metres_per_unit) || metres_per_unit <= 0) {
      throw Error(where, "cannot derive a scale from width/height and viewBox");
    }

    // the world map: user units -> metres, y flipped so north is up, origin at the viewBox's bottom-left
    Vec2 origin = Vec2::Zero();
    if (const char* o = root.Attribute("data-origin")) {
      std::size_t pos = 0;
      try {
        origin.x() = svg::read_number(o, pos);
        origin.y() = svg::read_number(o, pos);
      } catch (const svg::ParseError& e) {
        throw Error(with(where, "data-origin"), std::string(e.what()) + " (expected 'x y' in metres)");
      }
    }
    Eigen::Affine2d S = Eigen::Affine2d::Identity();
    S.linear() << metres_per_unit, 0, 0, -metres_per_unit;
    S.translation() = origin + Vec2(-vb[0] * metres_per_unit, (vb[1] + vb[3]) * metres_per_unit);
    to_world_root_ = S;
    if (has_vb) {
      world.floor_min = origin;
      world.floor_max = origin + Vec2(vb[2], vb[3]) * metres_per_unit;
    } else {
      floor_from_content_ = true;
    }
  }

  bool floor_from_content() const { return floor_from_content_; }

  /// Walks the document, collecting style sheets first so that rules apply everywhere.
  void walk(const XMLElement& root) {
    collect_sheets(root);
    ComputedStyle initial;
    const ComputedStyle root_style = svg::compute_style(root, initial, sheet_);
    if (!root_style.displayed) return;
    for (const XMLElement* c = root.FirstChildElement(); c; c = c->NextSiblingElement()) {
      visit(*c, root_style, to_world_root_, 1);
    }
  }

  std::vector<Shape> shapes;

 private:
  SourceRef ref(const XMLElement& e) const { return {file_, e.GetLineNum(), describe(e)}; }
  static SourceRef with(SourceRef r, const std::string& attribute) {
    r.element += " attribute " + attribute;
    return r;
  }
  void index_ids(const XMLElement* e) {
    // iterative, since documents may nest deeply
    std::vector<const XMLElement*> stack;
    if (e) stack.push_back(e);
    while (!stack.empty()) {
      const XMLElement* x = stack.back();
      stack.pop_back();
      if (const char* id = x->Attribute("id")) ids_.emplace(id, x);
      for (const XMLElement* c = x->FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
    }
  }

  void collect_sheets(const XMLElement& root) {
    std::vector<const XMLElement*> stack{&root};
    while (!stack.empty()) {
      const XMLElement* x = stack.back();
      stack.pop_back();
      if (local_name(*x) == "style") {
        const char* css = x->GetText();
        if (css) {
          const int unsupported = sheet_.add(css);
          if (unsupported > 0) {
            diag_.warn(ref(*x), std::to_string(unsupported) +
                                    " CSS selector(s) are not supported and were ignored (supported: *, tag, .class, #id, tag.class)");
          }
        }
        continue;
      }
      for (const XMLElement* c = x->FirstChildElement(); c; c = c->NextSiblingElement()) stack.push_back(c);
    }
  }

  /// Reads a length attribute in user units (0 when absent).
  double attr_length(const XMLElement& e, const char* name, double fallback = 0.0) const {
    const char* v = e.Attribute(name);
    if (!v) return fallback;
    try {
      const svg::Length l = svg::parse_length(v);
      if (l.unit == svg::Unit::percent) throw svg::ParseError("percentages are not supported here", 0);
      return l.user_units();
    } catch (const svg::ParseError& err) {
      throw Error(with(ref(e), name), std::string("'") + v + "': " + err.what());
    }
  }

  Eigen::Affine2d local_transform(const XMLElement& e) const {
    const char* t = e.Attribute("transform");
    if (!t) return Eigen::Affine2d::Identity();
    try {
      return svg::parse_transform(t);
    } catch (const svg::ParseError& err) {
      throw Error(with(ref(e), "transform"), std::string(err.what()) + " at character " + std::to_string(err.offset + 1));
    }
  }

  /// Reads polyline/polygon `points`.
  std::vector<Vec2> read_points(const XMLElement& e) const {
    const char* v = e.Attribute("points");
    std::vector<Vec2> pts;
    if (!v) return pts;
    const std::string_view s(v);
    std::size_t pos = 0;
    try {
      while (!svg::at_end(s, pos)) {
        const double x = svg::read_number(s, pos);
        if (svg::at_end(s, pos)) throw svg::ParseError("odd number of coordinates: expected a y after the last x", pos);
        const double y = svg::read_number(s, pos);
        pts.emplace_back(x, y);
      }
    } catch (const svg::ParseError& err) {
      throw Error(with(ref(e), "points"), std::string(err.what()) + " at character " + std::to_string(err.offset + 1));
    }
    return pts;
  }

  void add(Shape s) {
    for (const auto& sp : s.subpaths) vertices_ += sp.points.size();
    if (vertices_ > kMaxVertices) {
      throw Error(s.source, "the drawing has more than " + std::to_string(kMaxVertices) +
                                " vertices after flattening curves; simplify it or raise the curve tolerance");
    }
    shapes.push_back(std::move(s));
  }

  void visit(const XMLElement& e, const ComputedStyle& parent, const Eigen::Affine2d& ctm, int depth) {
    if (depth > kMaxDepth) throw Error(ref(e), "elements nest deeper than " + std::to_string(kMaxDepth) + " levels");
    // only elements of the SVG namespace (no prefix) are drawn; editor metadata is skipped
    if (std::strchr(e.Name(), ':')) return;
    const std::string_view tag = local_name(e);
    static const std::set<std::string_view> skipped = {
        "defs", "symbol", "clipPath", "mask", "pattern", "marker", "linearGradient", "radialGradient", "filter",
        "title", "desc", "metadata", "style", "script", "text", "image", "foreignObject"};
    if (skipped.count(tag)) return;

    ComputedStyle style = svg::compute_style(e, parent, sheet_);
    if (!style.displayed) return;
    for (const auto& bad : style.bad_paints) diag_.warn(ref(e), "cannot read colour '" + bad + "'; ignored");
    const Eigen::Affine2d m = ctm * local_transform(e);

    if (tag == "g" || tag == "a" || tag == "switch" || tag == "svg") {
      Eigen::Affine2d inner = m;
      if (tag == "svg") {
        inner = m * Eigen::Translation2d(attr_length(e, "x"), attr_length(e, "y"));
      }
      for (const XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) visit(*c, style, inner, depth + 1);
      return;
    }
    if (tag == "use") {
      visit_use(e, style, m, depth);
      return;
    }
    if (!style.visible) return;

    Shape s;
    s.style = style;
    s.source = ref(e);
    if (const char* id = e.Attribute("id")) s.id = id;
    // stroke width in metres: user width times the map's mean linear scale
    s.stroke_width = style.stroke_width * std::sqrt(std::abs(m.linear().determinant()));
    // curves are flattened to the tolerance measured in world metres
    const double tol = options_.curve_tolerance;

    if (tag == "rect") {
      s.tag = Shape::Tag::rect;
      const double x = attr_length(e, "x"), y = attr_length(e, "y");
      const double w = attr_length(e, "width"), h = attr_length(e, "height");
      if (w < 0 || h < 0) throw Error(s.source, "negative width or height");
      if (w == 0 || h == 0) {
        diag_.warn(s.source, "rectangle has zero width or height; ignored");
        return;
      }
      // rounded corners per SVG: a missing radius takes the other's value, both capped at half the side
      const char* rxa = e.Attribute("rx");
      const char* rya = e.Attribute("ry");
      double rx = attr_length(e, "rx", -1), ry = attr_length(e, "ry", -1);
      if (!rxa && rya) rx = ry;
      if (!rya && rxa) ry = rx;
      rx = std::clamp(rx < 0 ? 0.0 : rx, 0.0, w / 2);
      ry = std::clamp(ry < 0 ? 0.0 : ry, 0.0, h / 2);
      s.subpaths.push_back({svg::rect_points(x, y, w, h, rx, ry, m, tol), true});
    } else if (tag == "circle" || tag == "ellipse") {
      s.tag = tag == "circle" ? Shape::Tag::circle : Shape::Tag::ellipse;
      const double cx = attr_length(e, "cx"), cy = attr_length(e, "cy");
      const double rx = tag == "circle" ? attr_length(e, "r") : attr_length(e, "rx");
      const double ry = tag == "circle" ? rx : attr_length(e, "ry");
      if (rx < 0 || ry < 0) throw Error(s.source, "negative radius");
      if (rx == 0 || ry == 0) {
        diag_.warn(s.source, "zero radius; ignored");
        return;
      }
      s.subpaths.push_back({svg::ellipse_points(cx, cy, rx, ry, m, tol), true});
      s.is_round = true;
      s.centre = m * Vec2(cx, cy);
      s.radius = std::sqrt(rx * ry * std::abs(m.linear().determinant()));
    } else if (tag == "line") {
      s.tag = Shape::Tag::line;
      const Vec2 a(attr_length(e, "x1"), attr_length(e, "y1"));
      const Vec2 b(attr_length(e, "x2"), attr_length(e, "y2"));
      s.subpaths.push_back({{m * a, m * b}, false});
    } else if (tag == "polyline" || tag == "polygon") {
      s.tag = tag == "polygon" ? Shape::Tag::polygon : Shape::Tag::polyline;
      const auto pts = read_points(e);
      if (pts.size() < 2) {
        diag_.warn(s.source, "fewer than 2 points; ignored");
        return;
      }
      svg::Subpath sp;
      sp.closed = tag == "polygon";
      for (const auto& p : pts) sp.points.push_back(m * p);
      s.subpaths.push_back(std::move(sp));
    } else if (tag == "path") {
      s.tag = Shape::Tag::path;
      const char* d = e.Attribute("d");
      if (!d || !*d) {
        diag_.warn(s.source, "path without data; ignored");
        return;
      }
      try {
        s.subpaths = svg::parse_path(d, m, tol);
      } catch (const svg::ParseError& err) {
        throw Error(with(s.source, "d"), std::string(err.what()) + " at character " + std::to_string(err.offset + 1) +
                                             " of the path data");
      }
      if (s.subpaths.empty()) return;
    } else {
      return;  // not a shape we draw (unknown elements are skipped quietly, as browsers do)
    }
    add(std::move(s));
  }

  void visit_use(const XMLElement& e, const ComputedStyle& style, const Eigen::Affine2d& m, int depth) {
    const char* href = e.Attribute("href");
    if (!href) href = e.Attribute("xlink:href");
    if (!href || href[0] != '#') {
      diag_.warn(ref(e), "<use> without a local href (#id); ignored");
      return;
    }
    const auto it = ids_.find(href + 1);
    if (it == ids_.end()) {
      diag_.warn(ref(e), std::string("<use> refers to '") + href + "', which does not exist; ignored");
      return;
    }
    if (use_stack_.count(it->second)) throw Error(ref(e), std::string("<use> of '") + href + "' refers back to itself");
    use_stack_.insert(it->second);
    const Eigen::Affine2d inner = m * Eigen::Translation2d(attr_length(e, "x"), attr_length(e, "y"));
    const XMLElement& target = *it->second;
    if (local_name(target) == "symbol") {
      const ComputedStyle sym = svg::compute_style(target, style, sheet_);
      for (const XMLElement* c = target.FirstChildElement(); c; c = c->NextSiblingElement()) visit(*c, sym, inner, depth + 1);
    } else {
      visit(target, style, inner, depth + 1);
    }
    use_stack_.erase(it->second);
  }

  const std::string& file_;
  const SvgLoadOptions& options_;
  Diagnostics& diag_;
  svg::StyleSheet sheet_;
  std::map<std::string, const XMLElement*> ids_;
  std::set<const XMLElement*> use_stack_;
  Eigen::Affine2d to_world_root_ = Eigen::Affine2d::Identity();
  std::size_t vertices_ = 0;
  bool floor_from_content_ = false;
};

std::string xml_error_text(const tinyxml2::XMLDocument& doc) {
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: return "malformed XML: a closing tag does not match the open element";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: return "malformed XML: an element is not closed or is broken";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: return "malformed XML: an attribute is broken (missing quotes or '=')";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: return "the file is empty; expected an SVG document";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: return "malformed XML: elements nest too deeply";
    default: return std::string("malformed XML: ") + doc.ErrorName();
  }
}

/// Reads the generator record that rescuesim writes into <metadata>.
void read_generator(const XMLElement& root, WorldSpec& world) {
  for (const XMLElement* md = root.FirstChildElement("metadata"); md; md = md->NextSiblingElement("metadata")) {
    for (const XMLElement* g = md->FirstChildElement("rs:generator"); g; g = g->NextSiblingElement("rs:generator")) {
      if (const char* seed = g->Attribute("seed")) world.seed = std::strtoull(seed, nullptr, 10);
      if (const char* name = g->Attribute("name"); name && *name) world.name = name;
      for (const XMLElement* p = g->FirstChildElement("rs:param"); p; p = p->NextSiblingElement("rs:param")) {
        const char* k = p->Attribute("key");
        const char* v = p->Attribute("value");
        if (k && v) world.metadata[k] = v;
      }
    }
  }
}

}  // namespace

SvgLoadResult load_svg_world_from_string(std::string_view text, const std::string& name, const SvgLoadOptions& options) {
  if (!(options.units_per_metre > 0) || !std::isfinite(options.units_per_metre)) {
    throw Error({name, 0, "svg scale"}, "units per metre must be a positive number");
  }
  if (text.size() > options.max_file_bytes) {
    throw Error({name, 0, ""}, "file is " + std::to_string(text.size() >> 20) + " MB, larger than the " +
                                   std::to_string(options.max_file_bytes >> 20) + " MB limit for world drawings");
  }
  check_text(text, name);

  tinyxml2::XMLDocument doc(true, tinyxml2::COLLAPSE_WHITESPACE);
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw Error({name, doc.ErrorLineNum(), ""}, xml_error_text(doc));
  }
  const XMLElement* root = doc.RootElement();
  if (!root) throw Error({name, 0, ""}, "no root element; expected <svg>");
  if (local_name(*root) != "svg") {
    throw Error({name, root->GetLineNum(), describe(*root)}, "root element is <" + std::string(root->Name()) + ">, expected <svg>");
  }

  SvgLoadResult result;
  WorldSpec& world = result.world;
  world.source_file = name;
  world.name = std::filesystem::path(name).stem().string();
  world.ambient_temperature = options.ambient_temperature;
  world.materials = default_materials();
  read_generator(*root, world);  // a generated world keeps its own name and seed

  Walker walker(name, options, result.diagnostics, doc);
  walker.read_root(*root, world, result.metres_per_unit, result.scale_source);
  walker.walk(*root);
  svg::build_world(walker.shapes, options, world, result.diagnostics);

  if (walker.floor_from_content()) {
    const Box2 b = world.content_bounds();
    if (!b.empty()) {
      world.floor_min = b.min - Vec2(0.5, 0.5);
      world.floor_max = b.max + Vec2(0.5, 0.5);
    }
    result.diagnostics.warn({name, root->GetLineNum(), describe(*root)},
                            "no viewBox or width/height: the floor is the drawing's extent plus 0.5 m");
  }
  if (world.lights.empty()) {
    world.lights.push_back(LightSpec{});
  }
  return result;
}

SvgLoadResult load_svg_world(const std::filesystem::path& file, const SvgLoadOptions& options) {
  const std::string text = read_file(file, options.max_file_bytes);
  return load_svg_world_from_string(text, file.string(), options);
}

}  // namespace rescuesim
