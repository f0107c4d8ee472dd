// The XML side of a URDF: line numbers for messages, xacro refused, and the checks urdfdom
// does not make (or makes without saying where).
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>


#include "import/urdf/urdf_detail.h"

namespace rescuesim::urdf_detail {

namespace {

using tinyxml2::XMLElement;

std::string attr(const XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? v : "";
}

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Checks an <inertial> as urdfdom reads it: a mass that is not negative, and all six inertia
/// values (urdfdom drops an incomplete <inertia> with only a log line). Whether the inertia is
/// physical is judged later, on the rigid bodies physics sees (a link fixed to another only
/// adds to its body), where an impossible one is corrected with a warning (make_bodies_physical
/// in urdf_import.cpp).
void check_inertial(const XMLElement* link, const XMLElement* inertial, const XmlIndex& index) {
  const std::string name = attr(link, "name");
  const XMLElement* mass = inertial->FirstChildElement("mass");
  if (!mass) throw Error(index.at(inertial), "link '" + name + "': <inertial> has no <mass value=...>");
  const double m = numbers_of(mass->Attribute("value"), 1, index, mass, "mass value")[0];
  if (m < 0) throw Error(index.at(mass), "link '" + name + "': mass must not be negative, got " + num(m) + " kg");
  const XMLElement* in = inertial->FirstChildElement("inertia");
  if (!in) throw Error(index.at(inertial), "link '" + name + "': <inertial> has no <inertia ixx=... iyy=... izz=...>");
  const char* keys[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (const char* key : keys) {
    if (!in->Attribute(key)) {
      throw Error(index.at(in), "link '" + name + "': <inertia> has no " + key + " (give all six: ixx ixy ixz iyy iyz izz, 0 for none)");
    }
    numbers_of(in->Attribute(key), 1, index, in, key);
  }
}

/// Every numeric attribute of the URDF elements urdfdom reads: the right count of finite
/// numbers, or an error at its line (urdfdom drops a short "x y" silently).
void check_numbers(const XMLElement* robot, const XmlIndex& index) {
  struct Rule {
    const char* element;
    const char* attribute;
    std::size_t count;
  };
  static const Rule rules[] = {{"origin", "xyz", 3}, {"origin", "rpy", 3}, {"axis", "xyz", 3}, {"box", "size", 3},
                               {"mesh", "scale", 3}, {"color", "rgba", 4}, {"cylinder", "radius", 1}, {"cylinder", "length", 1},
                               {"sphere", "radius", 1}, {"limit", "lower", 1}, {"limit", "upper", 1}, {"limit", "effort", 1},
                               {"limit", "velocity", 1}, {"dynamics", "damping", 1}, {"dynamics", "friction", 1},
                               {"mimic", "multiplier", 1}, {"mimic", "offset", 1}};
  visit_elements(robot, [&](const XMLElement* e) {
    if (e != robot && e->Parent() == robot && std::strcmp(e->Name(), "gazebo") == 0)
      return false;  // Gazebo's own blocks are read elsewhere
    for (const Rule& r : rules) {
      if (std::strcmp(e->Name(), r.element) != 0) continue;
      if (const char* v = e->Attribute(r.attribute))
        numbers_of(v, r.count, index, e, std::string("<") + r.element + " " + r.attribute + ">");
    }
    return true;
  });
}

/// Each <visual> and <collision> holds a <geometry> whose first element is the shape, with the
/// attributes that shape needs (urdfdom would drop the element with only a log message).
/// urdfdom, RViz and PyBullet read the first element and ignore the rest (a <material> put
/// inside <geometry> by some exporters): so does rescuesim, with a note for each one ignored.
void check_geometry(const XMLElement* link, XmlIndex& index) {
  const std::string name = attr(link, "name");
  for (const char* kind : {"visual", "collision"}) {
    for (const XMLElement* v = link->FirstChildElement(kind); v; v = v->NextSiblingElement(kind)) {
      const XMLElement* g = v->FirstChildElement("geometry");
      if (!g) throw Error(index.at(v), "link '" + name + "': <" + kind + "> has no <geometry>");
      const XMLElement* s = g->FirstChildElement();
      if (!s) throw Error(index.at(g), "link '" + name + "': <geometry> holds no shape (expected box, cylinder, sphere or mesh)");
      const std::string shape = s->Name();
      static const std::map<std::string, std::vector<const char*>> needs{
          {"box", {"size"}}, {"cylinder", {"radius", "length"}}, {"sphere", {"radius"}}, {"mesh", {"filename"}}};
      const auto it = needs.find(shape);
      if (it == needs.end()) {
        throw Error(index.at(s), "link '" + name + "': unknown shape <" + shape + "> (expected box, cylinder, sphere or mesh)");
      }
      for (const char* a : it->second) {
        if (!s->Attribute(a)) throw Error(index.at(s), "link '" + name + "': <" + shape + "> needs a " + a + " attribute");
      }
      for (const XMLElement* extra = s->NextSiblingElement(); extra; extra = extra->NextSiblingElement()) {
        index.notes.emplace_back(index.at(extra), "link '" + name + "': <" + extra->Name() + "> inside <geometry> after the <" + shape +
                                                      "> is ignored, as urdfdom ignores it (only the first element is the shape)");
      }
    }
  }
}

}  // namespace

SourceRef XmlIndex::at(const XMLElement* e) const { return {file, e ? e->GetLineNum() : 0, e ? describe(e) : ""}; }

SourceRef XmlIndex::link(const std::string& name) const {
  const auto it = links.find(name);
  return it == links.end() ? SourceRef{file, 0, "<link name=\"" + name + "\">"} : at(it->second);
}

SourceRef XmlIndex::joint(const std::string& name) const {
  const auto it = joints.find(name);
  return it == joints.end() ? SourceRef{file, 0, "<joint name=\"" + name + "\">"} : at(it->second);
}

std::string describe(const XMLElement* e) {
  // appended piece by piece (GCC 12 warns, wrongly, about overlapping copies in a + chain here)
  std::string out = "<";
  out += e->Name();
  if (const char* name = e->Attribute("name")) {
    out += " name=\"";
    out += name;
    out += '"';
  }
  out += '>';
  return out;
}

std::vector<double> numbers_of(const char* text, std::size_t n, const XmlIndex& index, const XMLElement* e, const std::string& what) {
  std::vector<double> out;
  if (text) {
    std::istringstream in(text);
    std::string tok;
    while (in >> tok) {
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0' || !std::isfinite(v)) {
        throw Error(index.at(e), what + ": '" + tok + "' is not a finite number");
      }
      out.push_back(v);
    }
  }
  if (out.size() != n) {
    throw Error(index.at(e), what + ": expected " + std::to_string(n) + " number(s), got '" + std::string(text ? text : "") + "'");
  }
  return out;
}

void refuse_xacro(const XMLElement* robot, const std::string& file) {
  const std::string how =
      "this is a xacro file, not URDF: expand it first with `xacro robot.urdf.xacro > robot.urdf` (xacro comes with ROS; "
      "`pip install xacro` elsewhere) and give rescuesim the result";
  visit_elements(robot, [&](const XMLElement* e) {
    const std::string name = e->Name();
    if (name.rfind("xacro:", 0) == 0 && name != "xacro:arg" && name != "xacro:property") {
      throw Error({file, e->GetLineNum(), "<" + name + ">"}, how);
    }
    // TurtleBot3's declaration of its namespace argument is the one xacro construct understood
    const bool declaration = name == "xacro:arg" || name == "xacro:property";
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a && !declaration; a = a->Next()) {
      const std::string v = a->Value();
      if (v.find("${") != std::string::npos || v.find("$(") != std::string::npos) {
        throw Error({file, e->GetLineNum(), describe(e)}, "attribute " + std::string(a->Name()) + "=\"" + v + "\": " + how);
      }
    }
    return true;
  });
}

XmlIndex check_structure(const XMLElement* robot, const std::string& file) {
  XmlIndex index;
  index.file = file;
  for (const XMLElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const std::string name = attr(l, "name");
    if (name.empty()) throw Error(index.at(l), "a <link> needs a name");
    if (index.links.count(name))
      throw Error(index.at(l),
                  "link '" + name + "' is defined twice (first at line " + std::to_string(index.links[name]->GetLineNum()) + ")");
    index.links[name] = l;
    index.link_order.push_back(name);
    if (const XMLElement* inertial = l->FirstChildElement("inertial")) check_inertial(l, inertial, index);
    check_geometry(l, index);
  }
  if (index.links.empty()) throw Error({file, robot->GetLineNum(), "<robot>"}, "the robot has no <link>");
  check_numbers(robot, index);

  std::map<std::string, std::string> parent_joint;  // child link -> joint
  for (const XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const std::string name = attr(j, "name");
    if (name.empty()) throw Error(index.at(j), "a <joint> needs a name");
    if (index.joints.count(name)) throw Error(index.at(j), "joint '" + name + "' is defined twice");
    index.joints[name] = j;
    index.joint_order.push_back(name);
    const std::string type = attr(j, "type");
    static const std::set<std::string> known{"revolute", "continuous", "prismatic", "fixed"};
    if (type == "floating" || type == "planar") {
      throw Error(index.at(j), "joint type '" + type +
                                   "' is not supported: a rescuesim robot is one tree whose root link moves freely; "
                                   "use a fixed joint (or revolute/prismatic ones) instead");
    }
    if (!known.count(type)) {
      throw Error(index.at(j), "unknown joint type '" + type + "' (expected revolute, continuous, prismatic or fixed)");
    }
    const XMLElement* p = j->FirstChildElement("parent");
    const XMLElement* c = j->FirstChildElement("child");
    if (!p || !p->Attribute("link")) throw Error(index.at(j), "joint '" + name + "' has no <parent link=...>");
    if (!c || !c->Attribute("link")) throw Error(index.at(j), "joint '" + name + "' has no <child link=...>");
    const std::string parent = attr(p, "link"), child = attr(c, "link");
    if (!index.links.count(parent)) throw Error(index.at(p), "joint '" + name + "': parent link '" + parent + "' is not defined");
    if (!index.links.count(child)) throw Error(index.at(c), "joint '" + name + "': child link '" + child + "' is not defined");
    if (parent == child) throw Error(index.at(j), "joint '" + name + "' joins link '" + parent + "' to itself");
    if (parent_joint.count(child)) {
      throw Error(index.at(j), "link '" + child + "' has two parents (joints '" + parent_joint[child] + "' and '" + name +
                                   "'): URDF describes a tree, closed loops are not supported");
    }
    parent_joint[child] = name;
    if ((type == "revolute" || type == "prismatic") && !j->FirstChildElement("limit")) {
      throw Error(index.at(j), "joint '" + name + "' is " + type + " but has no <limit lower=... upper=... effort=... velocity=...>");
    }
  }

  // one root; following parents from every link must reach it (no loops)
  std::vector<std::string> roots;
  for (const auto& name : index.link_order) {
    if (!parent_joint.count(name)) roots.push_back(name);
  }
  if (roots.empty()) throw Error({file, robot->GetLineNum(), "<robot>"}, "every link has a parent: the joints form a loop");
  if (roots.size() > 1) {
    throw Error(index.link(roots[1]), "links '" + roots[0] + "' and '" + roots[1] +
                                          "' both have no parent joint: a URDF robot is one tree with a single root link");
  }
  for (const auto& name : index.link_order) {
    std::string at = name;
    std::size_t hops = 0;
    while (parent_joint.count(at)) {
      const XMLElement* j = index.joints.at(parent_joint.at(at));
      at = attr(j->FirstChildElement("parent"), "link");
      if (++hops > index.links.size()) throw Error(index.link(name), "link '" + name + "' is on a loop of joints");
    }
  }
  return index;
}

}  // namespace rescuesim::urdf_detail
