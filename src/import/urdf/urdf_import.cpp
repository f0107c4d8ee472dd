// URDF → RobotSpec: urdfdom reads the model; tinyxml2 gives the line numbers and the <gazebo>
// extensions urdfdom skips; import/mesh loads meshes and makes convex collision shapes.
#include "import/urdf/urdf_import.h"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <tuple>
#include <console_bridge/console.h>

#include "core/atomic_file.h"
#include "import/mesh/mesh.h"
#include "import/urdf/urdf_detail.h"
#include "world/robot_lumping.h"

namespace rescuesim {

namespace {

using namespace urdf_detail;
using Clock = std::chrono::steady_clock;

/// console_bridge messages from urdfdom, collected instead of printed.
class CollectingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      errors += (errors.empty() ? "" : "; ") + text;
    } else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      warnings.push_back(text);
    }
  }
  std::string errors;
  std::vector<std::string> warnings;
};

/// urdfdom reports through a process-wide console_bridge handler: one parse at a time. It
/// drops an element it cannot read (an <inertial> missing a value, a <collision> without
/// geometry) with an error message and still returns a model, so any error counts.
urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& text, CollectingHandler& handler) {
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    handler.errors += std::string(handler.errors.empty() ? "" : "; ") + e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  return model;
}

Pose3 pose_of(const urdf::Pose& p) {
  return {Vec3(p.position.x, p.position.y, p.position.z), Quat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized()};
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

/// Builds the RobotSpec of one parsed model.
class Builder {
 public:
  Builder(const urdf::ModelInterface& model, const XmlIndex& index, const UrdfOptions& options, UrdfRobot& out)
      : model_(model), index_(index), options_(options), out_(out) {}

  void build() {
    RobotSpec& spec = out_.spec;
    spec.model = model_.getName();
    for (const auto& [name, m] : model_.materials_) {
      if (m) material_for(*m, name);
    }
    // links in tree order: the root, then each joint's child after its parent (document order)
    std::vector<std::string> order{model_.getRoot()->name};
    std::vector<std::string> joints;
    for (std::size_t k = 0; k < order.size(); ++k) {
      for (const auto& jn : index_.joint_order) {
        const auto j = model_.getJoint(jn);
        if (j && j->parent_link_name == order[k]) {
          order.push_back(j->child_link_name);
          joints.push_back(jn);
        }
      }
    }
    for (const auto& name : order) spec.links.push_back(link(*model_.getLink(name)));
    for (const auto& name : joints) spec.joints.push_back(joint(*model_.getJoint(name)));
    out_.root_link = order.front();
    for (const auto& j : spec.joints) (j.type == JointSpec::Type::fixed ? out_.fixed_joints : out_.moving_joints)++;
    for (auto& j : spec.joints) {
      if (!j.mimic.empty() && spec.joint_index(j.mimic) < 0) {
        out_.diagnostics.warn(index_.joint(j.name),
                              "joint '" + j.name + "' mimics '" + j.mimic + "', which is not a joint; it moves on its own");
        j.mimic.clear();
      }
    }
  }

  double hull_seconds = 0;

 private:
  /// The robot material `<model>/<name>` of this colour (added once); returns its name.
  std::string add_material(const std::string& name, const Vec3& color) {
    const std::string full = out_.spec.model + "/" + name;
    for (const auto& x : out_.spec.materials) {
      if (x.name == full) return full;
    }
    MaterialSpec ms;
    ms.name = full;
    ms.roughness = 0.6;
    ms.color = color;
    out_.spec.materials.push_back(ms);
    return full;
  }

  /// The robot material of a URDF <material> (named, or `fallback_name` when it has no name).
  std::string material_for(const urdf::Material& m, const std::string& fallback_name) {
    return add_material(m.name.empty() ? fallback_name : m.name, Vec3(m.color.r, m.color.g, m.color.b));
  }

  /// The line of a link's <mesh filename=...> element (the link's line if not found).
  int mesh_line(const std::string& link, const std::string& filename) const {
    int line = 0;
    const auto it = index_.links.find(link);
    if (it != index_.links.end()) {
      visit_elements(it->second, [&](const tinyxml2::XMLElement* e) {
        const char* f = e->Attribute("filename");
        if (!line && std::strcmp(e->Name(), "mesh") == 0 && f && filename == f) line = e->GetLineNum();
        return line == 0;
      });
    }
    return line ? line : index_.link(link).line;
  }

  /// A mesh file, loaded once per file and scale.
  struct MeshFile {
    const LoadedMesh& mesh;
    std::string file;  ///< resolved path
  };
  MeshFile mesh(const urdf::Mesh& m, const std::string& link) {
    const SourceRef where{index_.file, mesh_line(link, m.filename), "<link name=\"" + link + "\"> <mesh filename=\"" + m.filename + "\">"};
    const std::filesystem::path file = options_.resolver.resolve(m.filename, where);
    const auto key = std::make_tuple(file.string(), m.scale.x, m.scale.y, m.scale.z);
    auto it = meshes_.find(key);
    if (it == meshes_.end()) {
      MeshLoadOptions o;
      o.scale = Vec3(m.scale.x, m.scale.y, m.scale.z);
      o.max_triangles = options_.max_triangles;
      it = meshes_.emplace(key, load_mesh(file, o, where)).first;
    }
    return {it->second, file.string()};
  }

  /// Adds the shapes of one collision or visual element to `ls`.
  void add_geometry(LinkSpec& ls, const urdf::Geometry& g, const Pose3& X_LG, bool collision, const std::string& material) {
    auto add = [&](Geometry geometry, const std::string& mat) {
      LinkShape sh;
      sh.geometry = std::move(geometry);
      sh.X_LG = X_LG;
      sh.material = mat;
      sh.collides = collision;
      sh.visible = !collision;
      ls.shapes.push_back(std::move(sh));
    };
    const std::string what = std::string(collision ? "<collision>" : "<visual>");
    // a size that is not positive: an error on a collision (the robot would not touch the world
    // as described), and on a visual a shape left out with a warning, as Gazebo draws nothing
    // for it (PyBullet's laikago marks its toes with visual spheres of radius 0)
    auto positive = [&](double v, const char* name) {
      if (v > 0 && std::isfinite(v)) return true;
      const std::string message = "link '" + ls.name + "': " + what + " " + name + " must be positive, got " + std::to_string(v);
      if (collision) throw Error(index_.link(ls.name), message);
      out_.diagnostics.warn(index_.link(ls.name), message + ": the visual is left out");
      return false;
    };
    switch (g.type) {
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(g);
        if (positive(b.dim.x, "box size x") && positive(b.dim.y, "box size y") && positive(b.dim.z, "box size z")) {
          add(Geometry::box({b.dim.x, b.dim.y, b.dim.z}), material);
        }
        return;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(g);
        if (positive(c.radius, "cylinder radius") && positive(c.length, "cylinder length")) {
          add(Geometry::cylinder(c.radius, c.length), material);
        }
        return;
      }
      case urdf::Geometry::SPHERE:
        if (positive(static_cast<const urdf::Sphere&>(g).radius, "sphere radius")) {
          add(Geometry::sphere(static_cast<const urdf::Sphere&>(g).radius), material);
        }
        return;
      case urdf::Geometry::MESH: break;
    }
    const auto& m = static_cast<const urdf::Mesh&>(g);
    // a visual mesh that cannot be found or read is left out with a warning, as Gazebo and RViz
    // leave it out with an error line: the robot still moves and senses the same. A collision
    // mesh must be there: without it the robot would not touch the world.
    std::optional<MeshFile> found;
    try {
      found.emplace(mesh(m, ls.name));
    } catch (const Error& e) {
      if (collision) throw;
      out_.diagnostics.warn(e.where(), "visual mesh left out: " + e.message());
      return;
    }
    const LoadedMesh& loaded = found->mesh;
    UrdfMeshReport report;
    report.link = ls.name;
    report.uri = m.filename;
    report.file = found->file;
    report.collision = collision;
    report.triangles = static_cast<int>(loaded.mesh.triangles.size());
    if (!collision) {
      // no URDF material: the mesh file's own colour, if it has one
      const std::string mat = material == "robot_body" && loaded.color
                                  ? add_material("mesh:" + std::filesystem::path(m.filename).filename().string(), *loaded.color)
                                  : material;
      add(Geometry::triangles(loaded.mesh), mat);
      out_.meshes.push_back(report);
      return;
    }
    // a collision mesh on a moving link: its convex hull, or convex pieces when the hull is a poor fit
    const auto t0 = Clock::now();
    std::vector<TriangleMesh> pieces;
    try {
      TriangleMesh hull = convex_hull(loaded.mesh.vertices, options_.hull_vertices);
      report.mesh_volume = mass_properties(loaded.mesh).volume;
      report.hull_volume = mass_properties(hull).volume;
      const bool decompose = options_.collision == CollisionMode::decompose ||
                             (options_.collision == CollisionMode::automatic && report.mesh_volume > 0 &&
                              report.hull_volume > options_.decompose_ratio * report.mesh_volume);
      if (decompose) {
        DecompositionOptions d;
        d.max_vertices_per_hull = std::min(options_.hull_vertices, 32);
        pieces = convex_decomposition(loaded.mesh, d);
      } else {
        pieces.push_back(std::move(hull));
      }
    } catch (const Error& e) {
      throw Error({index_.file, mesh_line(ls.name, m.filename),
                   "<link name=\"" + ls.name + "\"> <collision> <mesh filename=\"" + m.filename + "\">"},
                  "collision mesh " + found->file + ": " + e.message());
    }
    hull_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    report.pieces = static_cast<int>(pieces.size());
    for (auto& p : pieces) {
      report.hull_vertices += static_cast<int>(p.vertices.size());
      add(Geometry::convex(std::move(p)), material);
    }
    out_.meshes.push_back(report);
  }

  LinkSpec link(const urdf::Link& l) {
    LinkSpec ls;
    ls.name = l.name;
    if (l.inertial) {
      const auto& in = *l.inertial;
      ls.mass = in.mass;
      ls.com = pose_of(in.origin).p;
      Eigen::Matrix3d I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Eigen::Matrix3d R = pose_of(in.origin).q.toRotationMatrix();
      set_inertia_tensor(ls, R * I * R.transpose());
    } else {
      ls.mass = 0;
      ls.inertia = Vec3::Zero();
    }
    for (const auto& c : l.collision_array) {
      if (c && c->geometry) add_geometry(ls, *c->geometry, pose_of(c->origin), true, "robot_body");
    }
    int k = 0;
    for (const auto& v : l.visual_array) {
      if (!v || !v->geometry) continue;
      const std::string mat = v->material ? material_for(*v->material, l.name + "_visual" + std::to_string(k)) : "robot_body";
      add_geometry(ls, *v->geometry, pose_of(v->origin), false, mat);
      ++k;
    }
    if (!l.inertial) estimate_inertial(ls);
    return ls;
  }

  /// A link with collision shapes but no <inertial>: a solid of default density filling the
  /// bounding box of its shapes (Gazebo would drop the link; a warning says what was assumed).
  void estimate_inertial(LinkSpec& ls) {
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    double volume = 0;
    for (const auto& sh : ls.shapes) {
      if (!sh.collides) continue;
      const TriangleMesh m = mesh_of(sh.geometry, 16);
      for (const auto& v : m.vertices) {
        lo = lo.cwiseMin(sh.X_LG * v);
        hi = hi.cwiseMax(sh.X_LG * v);
      }
      volume += mass_properties(m).volume;
    }
    if (volume <= 0) return;  // only visuals, or none: a frame without mass
    ls.mass = options_.default_density * volume;
    const Vec3 s = hi - lo;
    ls.com = 0.5 * (lo + hi);
    ls.inertia = ls.mass / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y());
    out_.diagnostics.warn(index_.link(ls.name), "link '" + ls.name + "' has no <inertial>: assuming " + std::to_string(ls.mass) +
                                                    " kg (" + std::to_string(static_cast<int>(options_.default_density)) +
                                                    " kg/m^3 over its collision shapes); give an <inertial> for faithful dynamics");
  }

  JointSpec joint(const urdf::Joint& j) {
    JointSpec js;
    js.name = j.name;
    js.parent = j.parent_link_name;
    js.child = j.child_link_name;
    js.X_PJ = pose_of(j.parent_to_joint_origin_transform);
    js.axis = Vec3(j.axis.x, j.axis.y, j.axis.z);
    if (js.axis.norm() < 1e-9) {
      if (j.type != urdf::Joint::FIXED) throw Error(index_.joint(j.name), "joint '" + j.name + "' has a zero <axis>");
      js.axis = Vec3::UnitX();
    }
    js.axis.normalize();
    switch (j.type) {
      case urdf::Joint::REVOLUTE: js.type = JointSpec::Type::revolute; break;
      case urdf::Joint::CONTINUOUS: js.type = JointSpec::Type::continuous; break;
      case urdf::Joint::PRISMATIC: js.type = JointSpec::Type::prismatic; break;
      case urdf::Joint::FIXED: js.type = JointSpec::Type::fixed; break;
      default: throw Error(index_.joint(j.name), "joint '" + j.name + "': unsupported type");
    }
    if (j.limits) {
      if (js.type == JointSpec::Type::revolute || js.type == JointSpec::Type::prismatic) {
        if (j.limits->lower > j.limits->upper) {
          throw Error(index_.joint(j.name), "joint '" + j.name + "': <limit lower> " + std::to_string(j.limits->lower) +
                                                " is above upper " + std::to_string(j.limits->upper));
        }
        js.lower = j.limits->lower;
        js.upper = j.limits->upper;
      }
      if (j.limits->effort > 0) js.max_effort = j.limits->effort;
      if (j.limits->velocity > 0) js.max_velocity = j.limits->velocity;
    } else if (js.type == JointSpec::Type::continuous) {
      js.max_velocity = 20.0;
    }
    if (j.dynamics) {
      js.damping = std::max(0.0, j.dynamics->damping);
      js.friction = std::max(0.0, j.dynamics->friction);
    }
    // revolute and prismatic joints hold their place like servos (commandable on joint_command);
    // continuous joints outside the drive turn freely, as casters do
    if (js.type == JointSpec::Type::revolute || js.type == JointSpec::Type::prismatic) {
      js.control = JointSpec::Control::position;
      js.initial = std::clamp(0.0, js.lower, js.upper);
    }
    if (j.mimic) {
      js.mimic = j.mimic->joint_name;
      js.mimic_multiplier = j.mimic->multiplier;
      js.mimic_offset = j.mimic->offset;
      if (js.type != JointSpec::Type::fixed) js.control = JointSpec::Control::position;
    }
    return js;
  }

  const urdf::ModelInterface& model_;
  const XmlIndex& index_;
  const UrdfOptions& options_;
  UrdfRobot& out_;
  std::map<std::tuple<std::string, double, double, double>, LoadedMesh> meshes_;  // by file and scale
};

/// The rigid bodies physics sees (links merged through fixed joints) made physical, each with a
/// warning naming the link and the change; only the merged body matters, so a small link fixed
/// to a heavier one (a camera on a CAD-exported body) may be anything. A body without mass gets
/// a token 0.01 kg (Bullet cannot move a body of zero mass). A body whose principal moments are
/// not all positive, or break the triangle inequality (no rigid body has one moment larger than
/// the other two together; CAD exports often do), gets their average for each, as MuJoCo's
/// `balanceinertia` does, or, with none positive, those of a sphere of its mass and 5 cm radius
/// of gyration. The correction is added to the body's top link, so the merged body is exactly
/// the corrected one.
void make_bodies_physical(UrdfRobot& out, const XmlIndex& index) {
  const LumpedRobot lumped = lump_fixed_joints(out.spec);
  for (std::size_t b = 0; b < lumped.spec.links.size(); ++b) {
    const LinkSpec& body = lumped.spec.links[b];
    LinkSpec& top = out.spec.links[static_cast<std::size_t>(out.spec.link_index(body.name))];
    const bool merged = std::count(lumped.body_of_link.begin(), lumped.body_of_link.end(), static_cast<int>(b)) > 1;
    const std::string what = "link '" + top.name + "'" + (merged ? " (with the links fixed to it)" : "");
    if (!(body.mass > 0)) {
      top.mass = 0.01;
      top.inertia = Vec3::Constant(1e-5);
      out.diagnostics.warn(index.link(top.name), what + " moves but nothing on it has mass: giving it 0.01 kg");
      continue;
    }
    const Eigen::Matrix3d I = inertia_tensor(body);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
    const Eigen::Vector3d& p = eig.eigenvalues();  // ascending
    const double tolerance = 1e-6 * std::max(std::abs(p[2]), 1e-30);
    const bool positive = p[0] > 0;
    const bool triangle = p[0] + p[1] >= p[2] - tolerance;
    if (positive && triangle) continue;
    auto num = [](double v) {
      std::ostringstream s;
      s << v;
      return s.str();
    };
    const std::string moments = num(p[0]) + ", " + num(p[1]) + ", " + num(p[2]) + " kg m^2";
    Eigen::Vector3d fixed;
    std::string why;
    if (p[2] <= 0) {
      fixed.setConstant(0.4 * body.mass * 0.05 * 0.05);
      why = "has no positive principal moment (" + moments + "): using a sphere's of its " + num(body.mass) + " kg and 5 cm radius, " +
            num(fixed[0]) + " kg m^2 each";
    } else {
      const double average = std::max((std::max(p[0], 0.0) + std::max(p[1], 0.0) + p[2]) / 3.0, 1e-12);
      fixed.setConstant(average);
      why = std::string(positive ? "breaks the triangle inequality" : "is not positive definite") + " (principal moments " + moments +
            "), as CAD exports often do: using their average, " + num(average) + " kg m^2, for each, as MuJoCo's balanceinertia does";
    }
    const Eigen::Matrix3d& V = eig.eigenvectors();
    const Eigen::Matrix3d target = V * fixed.asDiagonal() * V.transpose();
    set_inertia_tensor(top, inertia_tensor(top) + (target - I));
    out.diagnostics.warn(index.link(top.name), what + ": inertia " + why);
  }
}

/// The element whose name= is the last 'quoted' name in `message` that names one, for a
/// urdfdom warning (which has no line); the <robot> element otherwise.
SourceRef where_named(const tinyxml2::XMLElement* robot, const std::string& message, const std::string& file) {
  std::vector<std::string> quoted;
  for (std::size_t a = message.find('\''); a != std::string::npos;) {
    const std::size_t b = message.find('\'', a + 1);
    if (b == std::string::npos) break;
    quoted.push_back(message.substr(a + 1, b - a - 1));
    a = message.find('\'', b + 1);
  }
  for (auto q = quoted.rbegin(); q != quoted.rend(); ++q) {
    const tinyxml2::XMLElement* found = nullptr;
    visit_elements(robot, [&](const tinyxml2::XMLElement* e) {
      if (!found && e != robot && e->Attribute("name") && *q == e->Attribute("name")) found = e;
      return !found;
    });
    if (found) return {file, found->GetLineNum(), describe(found)};
  }
  return {file, robot->GetLineNum(), "<robot>"};
}

/// A robot whose root is an empty link ("world") joined to the real base by a floating joint,
/// as SolidWorks exports and MuJoCo-minded URDFs write a free base: urdfdom accepts it, and a
/// rescuesim robot's root moves freely anyway, so the empty link and the joint are dropped from
/// `doc` with a note. Any other floating or planar joint stays (check_structure refuses it).
bool drop_free_base(tinyxml2::XMLDocument& doc, const std::string& file, std::vector<std::pair<SourceRef, std::string>>& notes) {
  tinyxml2::XMLElement* robot = doc.RootElement();
  std::map<std::string, int> children_as_child;
  for (auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    if (auto* c = j->FirstChildElement("child"); c && c->Attribute("link")) children_as_child[c->Attribute("link")]++;
  }
  for (auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const char* type = j->Attribute("type");
    const auto* p = j->FirstChildElement("parent");
    if (!type || std::strcmp(type, "floating") != 0 || !p || !p->Attribute("link")) continue;
    const std::string parent = p->Attribute("link");
    if (children_as_child.count(parent)) continue;  // not the root
    tinyxml2::XMLElement* root = nullptr;
    int joints_from_root = 0;
    for (auto* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
      if (l->Attribute("name") && parent == l->Attribute("name")) root = l;
    }
    for (auto* k = robot->FirstChildElement("joint"); k; k = k->NextSiblingElement("joint")) {
      const auto* kp = k->FirstChildElement("parent");
      if (kp && kp->Attribute("link") && parent == kp->Attribute("link")) ++joints_from_root;
    }
    if (!root || root->FirstChildElement() || joints_from_root != 1) continue;  // a root with a body of its own
    notes.emplace_back(SourceRef{file, j->GetLineNum(), describe(j)},
                       "floating joint '" + std::string(j->Attribute("name") ? j->Attribute("name") : "") + "' from the empty root link '" +
                           parent + "' is the robot's free base: both are dropped, as a rescuesim robot's root moves freely");
    robot->DeleteChild(j);
    robot->DeleteChild(root);
    return true;
  }
  return false;
}

}  // namespace

void add_standard_sensors(RobotSpec& robot) {
  auto has = [&](SensorSpec::Type t) {
    for (const auto& s : robot.sensors) {
      if (s.type == t) return true;
    }
    return false;
  };
  auto add = [&](const char* name, SensorSpec::Type type, double rate, const char* topic, const std::string& frame) {
    SensorSpec s;
    s.name = name;
    s.type = type;
    s.link = robot.links.front().name;
    s.rate = rate;
    s.topic = topic;
    s.frame_id = frame;
    robot.sensors.push_back(s);
  };
  if (!robot.drive.left_wheels.empty() && !has(SensorSpec::Type::odometry)) add("odometry", SensorSpec::Type::odometry, 50, "odom", "odom");
  if (!has(SensorSpec::Type::ground_truth)) add("ground_truth", SensorSpec::Type::ground_truth, 50, "ground_truth/pose", "map");
  if (!has(SensorSpec::Type::joint_states)) add("joint_states", SensorSpec::Type::joint_states, 20, "joint_states", "");
  if (!has(SensorSpec::Type::contact)) add("bumper", SensorSpec::Type::contact, 20, "bumper", robot.links.front().name);
}

bool is_urdf_path(const std::filesystem::path& file) { return file.extension() == ".urdf"; }

UrdfRobot parse_urdf(const std::string& text, const std::string& file, const UrdfOptions& options) {
  const auto t0 = Clock::now();
  // TurtleBot3's ROS 2 URDFs prefix every link and joint with ${namespace}, which its launch
  // files fill in; rescuesim namespaces frames itself, so the prefix is empty unless asked for
  const std::string filled = replace_all(text, "${namespace}", options.namespace_prefix);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(filled.data(), filled.size()) != tinyxml2::XML_SUCCESS) {
    throw Error({file, doc.ErrorLineNum(), ""}, std::string("malformed XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") {
    const std::string name = robot ? robot->Name() : "";
    throw Error({file, robot ? robot->GetLineNum() : 0, robot ? "<" + name + ">" : ""},
                "not a URDF robot: the root element must be <robot>" +
                    std::string(name == "sdf" ? " (this is SDF: rescuesim reads SDF models through the scenario's sdf key)" : ""));
  }
  refuse_xacro(robot, file);
  std::vector<std::pair<SourceRef, std::string>> base_notes;
  const bool dropped_base = drop_free_base(doc, file, base_notes);
  XmlIndex index = check_structure(robot, file);
  index.notes.insert(index.notes.begin(), base_notes.begin(), base_notes.end());

  CollectingHandler urdfdom;
  std::string for_urdfdom = filled;
  if (dropped_base) {
    tinyxml2::XMLPrinter printer;
    doc.Print(&printer);
    for_urdfdom = printer.CStr();
  }
  const urdf::ModelInterfaceSharedPtr model = parse_with_urdfdom(for_urdfdom, urdfdom);
  if (!model || !model->getRoot() || !urdfdom.errors.empty()) {
    throw Error({file, robot->GetLineNum(), "<robot>"},
                "urdfdom could not read it" + (urdfdom.errors.empty() ? std::string() : ": " + urdfdom.errors));
  }

  UrdfRobot out;
  for (const auto& [where, note] : index.notes) out.diagnostics.warn(where, note);
  // urdfdom's warnings (it repeats some), placed at the element whose name they quote last
  std::vector<std::string> seen;
  for (const auto& w : urdfdom.warnings) {
    if (std::find(seen.begin(), seen.end(), w) != seen.end()) continue;
    seen.push_back(w);
    out.diagnostics.warn(where_named(robot, w, file), "urdfdom: " + w);
  }
  out.spec.description = filled;
  out.spec.source_file = file;
  Builder builder(*model, index, options, out);
  builder.build();
  read_gazebo(robot, index, out);
  make_bodies_physical(out, index);
  const bool collides = std::any_of(out.spec.links.begin(), out.spec.links.end(), [](const LinkSpec& l) {
    return std::any_of(l.shapes.begin(), l.shapes.end(), [](const LinkShape& sh) { return sh.collides; });
  });
  if (!collides) {
    out.diagnostics.warn({file, robot->GetLineNum(), "<robot>"},
                         "the robot has no <collision> shape: nothing holds it up, it falls through the floor (as in Gazebo)");
  }
  add_standard_sensors(out.spec);
  out.hull_seconds = builder.hull_seconds;
  out.load_seconds = std::chrono::duration<double>(Clock::now() - t0).count() - out.hull_seconds;
  return out;
}

UrdfRobot load_urdf(const std::filesystem::path& file, const UrdfOptions& options) {
  std::string text;
  try {
    text = read_file(file, std::size_t(64) << 20);
  } catch (const Error& e) {
    throw Error({file.string(), 0, ""}, std::string("cannot read the URDF: ") + e.message());
  }
  return parse_urdf(text, file.string(), options);
}

}  // namespace rescuesim
