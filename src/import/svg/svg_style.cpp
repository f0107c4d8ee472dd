#include "import/svg/svg_style.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cstring>

namespace rescuesim::svg {

namespace {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool has_class(const tinyxml2::XMLElement& e, const std::string& cls) {
  const char* c = e.Attribute("class");
  if (!c) return false;
  std::string_view all(c);
  std::size_t i = 0;
  while (i < all.size()) {
    while (i < all.size() && std::isspace(static_cast<unsigned char>(all[i]))) ++i;
    std::size_t j = i;
    while (j < all.size() && !std::isspace(static_cast<unsigned char>(all[j]))) ++j;
    if (all.substr(i, j - i) == cls) return true;
    i = j;
  }
  return false;
}

/// Local name of an element (without a namespace prefix).
std::string_view local_name(const tinyxml2::XMLElement& e) {
  std::string_view n(e.Name());
  const auto colon = n.find(':');
  return colon == std::string_view::npos ? n : n.substr(colon + 1);
}

/// Applies one property to a style being computed.
void apply(ComputedStyle& s, const std::string& property, const std::string& raw, const ComputedStyle& parent) {
  const std::string value = trim(raw);
  const std::string p = lower(trim(property));
  if (value == "inherit") {
    // inherited properties already carry the parent's value; restore it for the others
    if (p == "fill") s.fill = parent.fill;
    if (p == "stroke") s.stroke = parent.stroke;
    if (p == "stroke-width") s.stroke_width = parent.stroke_width;
    return;
  }
  if (p == "fill" || p == "stroke") {
    Paint paint = parse_paint(value);
    if (paint.kind == Paint::Kind::invalid) {
      s.bad_paints.push_back(p + ": " + value);
      return;
    }
    if (paint.kind == Paint::Kind::inherit) paint = p == "fill" ? parent.fill : parent.stroke;
    (p == "fill" ? s.fill : s.stroke) = paint;
  } else if (p == "stroke-width") {
    try {
      const Length l = parse_length(value);
      if (l.unit != Unit::percent && l.value >= 0) s.stroke_width = l.user_units();
    } catch (const ParseError&) {
      // an unreadable stroke width keeps the inherited one, like a browser
    }
  } else if (p == "stroke-linecap") {
    s.linecap = lower(value);
  } else if (p == "display") {
    if (lower(value) == "none") s.displayed = false;
  } else if (p == "visibility") {
    const std::string v = lower(value);
    s.visible = !(v == "hidden" || v == "collapse");
  } else if (p == "color") {
    const Paint c = parse_paint(value);
    if (c.kind == Paint::Kind::color) s.color = c.rgb;
  }
}

const char* const kPresentation[] = {"fill", "stroke", "stroke-width", "stroke-linecap", "display", "visibility", "color"};

}  // namespace

std::vector<Declaration> parse_declarations(std::string_view text) {
  std::vector<Declaration> out;
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t end = text.find(';', i);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view part = text.substr(i, end - i);
    const auto colon = part.find(':');
    if (colon != std::string_view::npos) {
      std::string prop = trim(part.substr(0, colon));
      std::string val = trim(part.substr(colon + 1));
      // drop "!important": every rule here has equal weight anyway
      if (const auto bang = val.find("!important"); bang != std::string::npos) val = trim(val.substr(0, bang));
      if (!prop.empty()) out.push_back({lower(prop), val});
    }
    i = end + 1;
  }
  return out;
}

int StyleSheet::add(std::string_view css) {
  int unsupported = 0;
  // strip comments
  std::string text;
  for (std::size_t i = 0; i < css.size(); ++i) {
    if (css.substr(i, 2) == "/*") {
      const auto e = css.find("*/", i + 2);
      if (e == std::string_view::npos) break;
      i = e + 1;
      continue;
    }
    text.push_back(css[i]);
  }
  std::size_t i = 0;
  while (i < text.size()) {
    const auto open = text.find('{', i);
    if (open == std::string::npos) break;
    const auto close = text.find('}', open);
    if (close == std::string::npos) break;
    const std::string selectors = text.substr(i, open - i);
    const auto decls = parse_declarations(std::string_view(text).substr(open + 1, close - open - 1));
    std::size_t s = 0;
    while (s <= selectors.size()) {
      std::size_t comma = selectors.find(',', s);
      if (comma == std::string::npos) comma = selectors.size();
      const std::string sel = trim(std::string_view(selectors).substr(s, comma - s));
      s = comma + 1;
      if (sel.empty()) continue;
      // one simple selector: [tag][.class][#id] without combinators or pseudo-classes
      const bool simple = std::none_of(sel.begin(), sel.end(), [](char c) {
        return std::isspace(static_cast<unsigned char>(c)) || c == '>' || c == '+' || c == '~' || c == ':' || c == '[';
      });
      if (!simple || sel[0] == '@') {
        ++unsupported;
        continue;
      }
      Rule r;
      r.order = static_cast<int>(rules_.size());
      r.decls = decls;
      std::size_t k = 0;
      auto read_ident = [&](std::size_t from) {
        std::size_t e = from;
        while (e < sel.size() && sel[e] != '.' && sel[e] != '#') ++e;
        return e;
      };
      const std::size_t tag_end = read_ident(0);
      r.tag = sel.substr(0, tag_end);
      if (r.tag == "*") r.tag.clear();
      k = tag_end;
      bool ok = true;
      while (k < sel.size()) {
        const char kind = sel[k];
        const std::size_t e = read_ident(k + 1);
        const std::string name = sel.substr(k + 1, e - k - 1);
        if (name.empty()) ok = false;
        if (kind == '.') {
          if (!r.cls.empty()) ok = false;  // one class per selector is all we match
          r.cls = name;
        } else {
          r.id = name;
        }
        k = e;
      }
      if (!ok) {
        ++unsupported;
        continue;
      }
      r.specificity = (r.id.empty() ? 0 : 100) + (r.cls.empty() ? 0 : 10) + (r.tag.empty() ? 0 : 1);
      rules_.push_back(std::move(r));
    }
    i = close + 1;
  }
  return unsupported;
}

std::vector<Declaration> StyleSheet::match(const tinyxml2::XMLElement& e) const {
  std::vector<const Rule*> hits;
  const char* id = e.Attribute("id");
  const std::string_view tag = local_name(e);
  for (const auto& r : rules_) {
    if (!r.tag.empty() && r.tag != tag) continue;
    if (!r.id.empty() && (!id || r.id != id)) continue;
    if (!r.cls.empty() && !has_class(e, r.cls)) continue;
    hits.push_back(&r);
  }
  std::stable_sort(hits.begin(), hits.end(), [](const Rule* a, const Rule* b) {
    return a->specificity != b->specificity ? a->specificity < b->specificity : a->order < b->order;
  });
  std::vector<Declaration> out;
  for (const Rule* r : hits) out.insert(out.end(), r->decls.begin(), r->decls.end());
  return out;
}

ComputedStyle compute_style(const tinyxml2::XMLElement& e, const ComputedStyle& parent, const StyleSheet& sheet) {
  ComputedStyle s = parent;
  s.displayed = true;  // display is not inherited; a hidden parent stops the walk before here
  s.bad_paints.clear();
  // cascade: presentation attributes < style sheet < style attribute
  for (const char* name : kPresentation) {
    if (const char* v = e.Attribute(name)) apply(s, name, v, parent);
  }
  if (!sheet.empty()) {
    for (const auto& d : sheet.match(e)) apply(s, d.property, d.value, parent);
  }
  if (const char* st = e.Attribute("style")) {
    for (const auto& d : parse_declarations(st)) apply(s, d.property, d.value, parent);
  }
  // currentColor resolves against the element's own `color`
  // (a fill pattern's id, `url(#sand) currentColor`, stays)
  for (Paint* p : {&s.fill, &s.stroke}) {
    if (p->kind == Paint::Kind::current_color) p->kind = Paint::Kind::color, p->rgb = s.color;
  }
  // data-* settings inherit through groups
  for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next()) {
    const std::string_view n(a->Name());
    if (n.size() > 5 && n.substr(0, 5) == "data-") s.data[std::string(n.substr(5))] = a->Value();
  }
  return s;
}

}  // namespace rescuesim::svg
