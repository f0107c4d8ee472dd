#pragma once
// Internal to import/urdf: the XML side of a URDF (line numbers, checks urdfdom does not make,
// Gazebo extensions), shared by the files of the importer.

#include <map>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "import/urdf/urdf_import.h"

namespace rescuesim::urdf_detail {

/// Where each named element of a URDF is, for messages.
struct XmlIndex {
  std::string file;
  std::map<std::string, const tinyxml2::XMLElement*> links, joints;
  std::vector<std::string> joint_order;  ///< joint names in document order
  std::vector<std::string> link_order;   ///< link names in document order
  /// What the XML checks read differently from urdfdom or skipped, for the diagnostics.
  std::vector<std::pair<SourceRef, std::string>> notes;

  SourceRef link(const std::string& name) const;
  SourceRef joint(const std::string& name) const;
  SourceRef at(const tinyxml2::XMLElement* e) const;
};

/// Calls `f(element)` on `root` and every element below it, in document order (iteratively:
/// deep nesting cannot exhaust the stack). When `f` returns false, that element's children are
/// skipped.
template <class F>
void visit_elements(const tinyxml2::XMLElement* root, F&& f) {
  std::vector<const tinyxml2::XMLElement*> stack{root};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    if (!f(e)) continue;
    for (const tinyxml2::XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
  }
}

/// `<tag name="...">` for messages.
std::string describe(const tinyxml2::XMLElement* e);

/// Refuses xacro input: xacro elements other than the arg/property declarations that
/// TurtleBot3-style URDFs carry, and ${...} or $(...) left after `namespace_placeholder` is filled.
void refuse_xacro(const tinyxml2::XMLElement* robot, const std::string& file);

/// Checks what urdfdom accepts silently or reports without a line: joint types, parents and
/// children that exist, one tree without loops, masses that are not negative. What urdfdom
/// accepts, this accepts too; where it reads something differently it adds a note.
XmlIndex check_structure(const tinyxml2::XMLElement* robot, const std::string& file);

/// Reads <gazebo> extensions: the drive plugin, sensors, and warnings for what is ignored.
void read_gazebo(const tinyxml2::XMLElement* robot, const XmlIndex& index, UrdfRobot& out);

/// Reads one <sensor> element mounted on `link` (a URDF <gazebo> block's, or an SDF link's: the
/// same XML) into out.spec.sensors; unknown types and plugins are warnings in out.diagnostics.
void read_sensor(const tinyxml2::XMLElement* sensor, const std::string& link, const XmlIndex& index, UrdfRobot& out);

/// Parses "x y z" (or `n` numbers) from an attribute or text; throws naming the element.
std::vector<double> numbers_of(const char* text, std::size_t n, const XmlIndex& index, const tinyxml2::XMLElement* e,
                               const std::string& what);

}  // namespace rescuesim::urdf_detail
