// SDF models with joints → RobotSpec: links in tree order from the canonical link, each in its
// joint's frame; joints with axes, limits and dynamics; the drive from a diff-drive plugin; and
// <sensor>s read by the URDF importer's sensor reader (an SDF <sensor> is the same XML).
#include <tinyxml2.h>

#include <chrono>
#include <cmath>
#include <set>

#include "import/sdf/sdf_detail.h"
#include "import/urdf/urdf_detail.h"

namespace rescuesim::sdf_detail {

namespace {

using tinyxml2::XMLElement;

std::string quoted(const std::string& kind, const std::string& name) { return kind + " '" + name + "'"; }

/// The XML of an sdformat element as a tinyxml2 document, for readers written on tinyxml2.
void to_xml(const sdf::ElementPtr& e, tinyxml2::XMLDocument& doc, const SourceRef& where) {
  const std::string text = e->ToString("");
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) {
    throw Error(where, std::string("cannot re-read the element's XML: ") + doc.ErrorStr());
  }
}

std::string trimmed(const char* s) {
  const std::string t = s ? s : "";
  const auto b = t.find_first_not_of(" \t\r\n"), e = t.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : t.substr(b, e - b + 1);
}

/// Every text of the children with one of these names, in order.
std::vector<std::string> texts(const XMLElement* e, std::initializer_list<const char*> names) {
  std::vector<std::string> out;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    for (const char* n : names) {
      if (std::string(c->Name()) == n && !trimmed(c->GetText()).empty()) out.push_back(trimmed(c->GetText()));
    }
  }
  return out;
}

/// The first child number among these names, or 0 when none is given.
double number(const XMLElement* e, std::initializer_list<const char*> names, const SourceRef& where) {
  for (const char* n : names) {
    const XMLElement* c = e->FirstChildElement(n);
    if (!c) continue;
    char* end = nullptr;
    const std::string t = trimmed(c->GetText());
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !std::isfinite(v)) throw Error(where, std::string("<") + n + "> must be a number, got '" + t + "'");
    return v;
  }
  return 0;
}

bool is_drive_plugin(const std::string& filename) {
  return filename.find("diff-drive-system") != std::string::npos || filename.find("diff_drive_system") != std::string::npos ||
         filename == "libgazebo_ros_diff_drive.so" || filename == "libgazebo_ros_skid_steer_drive.so";
}

/// Plugins whose work rescuesim does by itself: no warning.
bool is_covered_plugin(const std::string& filename) {
  static const std::set<std::string> covered{"joint-state-publisher-system", "joint_state_publisher", "pose-publisher-system",
                                             "odometry-publisher-system", "sensors-system", "imu-system"};
  for (const auto& c : covered) {
    if (filename.find(c) != std::string::npos) return true;
  }
  return false;
}

/// The diff-drive plugin (gz-sim's or ROS 1's classic one) on a robot.
void read_drive(const sdf::ElementPtr& plugin, const std::string& filename, Reader& r, RobotSpec& spec) {
  const SourceRef where = r.at(plugin, "<model name=\"" + spec.model + "\">");
  tinyxml2::XMLDocument doc;
  to_xml(plugin, doc, where);
  const XMLElement* p = doc.RootElement();
  const auto left = texts(p, {"left_joint", "leftJoint", "leftFrontJoint", "leftRearJoint"});
  const auto right = texts(p, {"right_joint", "rightJoint", "rightFrontJoint", "rightRearJoint"});
  const double separation = number(p, {"wheel_separation", "wheelSeparation"}, where);
  double radius = number(p, {"wheel_radius"}, where);
  if (radius <= 0) radius = 0.5 * number(p, {"wheel_diameter", "wheelDiameter"}, where);
  // ROS 1's classic plugin turns the wrong way round, so its files often swap the sides: take
  // them from where the wheels are (as the URDF importer does)
  const bool classic = filename.rfind("libgazebo_ros_", 0) == 0;
  if (configure_diff_drive(spec, left, right, radius, separation, where, classic)) {
    r.diagnostics.warn(where, "plugin '" + filename +
                                  "' names the right-hand wheels as its left ones: rescuesim takes each side from where its wheels are");
  }
}

/// One <sensor> on a link, read by the URDF importer's reader; `X_FL` places the link in its
/// robot frame (the joint frame).
void read_sensor(const sdf::Sensor& sensor, const std::string& link, const Pose3& X_FL, Reader& r, RobotSpec& spec) {
  const SourceRef where = r.at(sensor.Element(), "<link name=\"" + link + "\">");
  tinyxml2::XMLDocument doc;
  to_xml(sensor.Element(), doc, where);
  XMLElement* e = doc.RootElement();
  // the URDF reader knows no thermal camera: it reads one as a colour camera, typed here after
  const std::string type = e->Attribute("type") ? e->Attribute("type") : "";
  const bool thermal = type == "thermal" || type == "thermal_camera";
  if (thermal) e->SetAttribute("type", "camera");
  urdf_detail::XmlIndex index;
  index.file = where.file;
  UrdfRobot scratch;
  scratch.spec.sensors = spec.sensors;
  const std::size_t before = spec.sensors.size();
  try {
    urdf_detail::read_sensor(e, link, index, scratch);
  } catch (const Error& err) {
    throw Error(where, err.message());  // the re-read XML's lines are not the file's
  }
  for (const auto& d : scratch.diagnostics.items()) r.diagnostics.warn(where, d.message);
  const Pose3 X_LS = resolve(sensor.SemanticPose(), "", where);
  for (std::size_t i = before; i < scratch.spec.sensors.size(); ++i) {
    SensorSpec& s = scratch.spec.sensors[i];
    s.X_LS = X_FL * X_LS;
    if (thermal) {
      s.type = SensorSpec::Type::thermal_camera;
      s.topic = s.name + "/image_raw";
    }
  }
  spec.sensors = std::move(scratch.spec.sensors);
}

/// One <light> on a link: a spot becomes a lamp of the robot (RobotLightSpec, shining along its
/// frame's x), a point light a lamp that lights every direction; a directional light on a link
/// means nothing for a lamp and is left out with a warning. SDF gives the whole cone (outer and
/// inner angle, as Ogre's spotlight range) and the direction in the light's frame (default
/// down, -z); `X_FL` places the link in its robot frame.
void read_light(const sdf::Light& light, const std::string& link, const Pose3& X_FL, Reader& r, RobotSpec& spec) {
  const SourceRef where = r.at(light.Element(), "<link name=\"" + link + "\">");
  if (light.Type() == sdf::LightType::DIRECTIONAL) {
    r.diagnostics.warn(where, "directional light '" + light.Name() + "' on a link is left out (a robot's lamps are spot or point lights)");
    return;
  }
  const Pose3 X_LLight = resolve(light.SemanticPose(), "", where);
  check_pose(X_LLight, r.options.max_extent, where, "the light's pose");
  Vec3 d = vec_of(light.Direction());
  d = d.allFinite() && d.norm() > 1e-12 ? Vec3(d.normalized()) : Vec3(-Vec3::UnitZ());
  RobotLightSpec lamp;
  lamp.name = light.Name();
  lamp.link = link;
  lamp.X_LF = X_FL * X_LLight * Pose3{Vec3::Zero(), Quat::FromTwoVectors(Vec3::UnitX(), d)};
  // a value that is not a number keeps the lamp's default rather than reach the shaders
  const auto finite_or = [](double v, double fallback) { return std::isfinite(v) ? v : fallback; };
  const Vec3 color = color_of(light.Diffuse());
  if (color.allFinite()) lamp.color = color.cwiseMax(0.0).cwiseMin(1.0);
  lamp.intensity = light.Element()->HasElement("intensity") ? std::max(0.0, finite_or(light.Intensity(), 1.0)) : 1.0;
  lamp.range = std::isfinite(light.AttenuationRange()) && light.AttenuationRange() > 0 ? light.AttenuationRange() : lamp.range;
  if (light.Type() == sdf::LightType::SPOT) {
    lamp.cone = std::clamp(0.5 * finite_or(light.SpotOuterAngle().Radian(), 2 * lamp.cone), 1e-3, 0.5 * M_PI);
    lamp.inner_cone = std::clamp(0.5 * finite_or(light.SpotInnerAngle().Radian(), 0.0), 0.0, lamp.cone);
  } else {
    lamp.cone = M_PI;  // a point light: every direction
    lamp.inner_cone = M_PI;
  }
  spec.lights.push_back(lamp);
}

/// The material of a robot's visual: its own colour, else the mesh file's, else robot_body.
std::string visual_material(const sdf::Visual& v, const std::optional<Vec3>& mesh_color, const std::string& model, const std::string& link,
                            RobotSpec& spec) {
  std::optional<Vec3> color = visual_color(v);
  if (!color) color = mesh_color;
  if (!color) return "robot_body";
  MaterialSpec m;
  m.name = model + "::" + link + "::" + v.Name();
  m.color = color->cwiseMax(0.0).cwiseMin(1.0);
  m.roughness = 0.6;
  spec.materials.push_back(m);
  return m.name;
}

/// A link of the robot; X_FL places the SDF link frame in the robot's link frame F.
LinkSpec link_spec(const sdf::Link& link, const Pose3& X_FL, const std::string& model, Reader& r, RobotSpec& spec) {
  LinkSpec ls;
  ls.name = link.Name();
  const std::string context = "<model name=\"" + model + "\"> <link name=\"" + link.Name() + "\">";
  std::vector<Piece> collision_L;  // for the density estimate
  static const MaterialSpec kBody = default_materials()[7];  // robot_body
  for (uint64_t i = 0; i < link.CollisionCount(); ++i) {
    const sdf::Collision& c = *link.CollisionByIndex(i);
    const SourceRef at = r.at(c.Element(), context);
    const Pose3 X_LC = resolve(c.SemanticPose(), "", at);
    check_pose(X_LC, r.options.max_extent, at, "the collision's pose");
    const Shape shape = shape_of(*c.Geom(), X_FL * X_LC, MeshUse::convex, {model, link.Name(), describe(c.Element()), true}, r);
    if (shape.floor) r.diagnostics.warn(at, "a plane on a robot link is left out");
    // collision shapes are not drawn: only a given friction gives them a material of their own
    const std::string material = friction_of(c) ? material_of(link, &c, model, std::nullopt, kBody, spec.materials) : kBody.name;
    for (const Piece& p : shape.pieces) {
      collision_L.push_back({p.geometry, X_LC * p.X_GP});
      ls.shapes.push_back({p.geometry, X_FL * X_LC * p.X_GP, material, true, false});
    }
  }
  for (uint64_t i = 0; i < link.VisualCount(); ++i) {
    const sdf::Visual& v = *link.VisualByIndex(i);
    const SourceRef at = r.at(v.Element(), context);
    const Pose3 X_LV = resolve(v.SemanticPose(), "", at);
    check_pose(X_LV, r.options.max_extent, at, "the visual's pose");
    const Shape shape = shape_of(*v.Geom(), X_FL * X_LV, MeshUse::exact, {model, link.Name(), describe(v.Element()), false}, r);
    const std::string material = visual_material(v, shape.mesh_color, model, link.Name(), spec);
    for (const Piece& p : shape.pieces) ls.shapes.push_back({p.geometry, X_FL * X_LV * p.X_GP, material, false, true});
  }
  const Inertial in = inertial_of(link, collision_L, model, r);
  ls.mass = in.mass;
  const Pose3 X_FI = X_FL * in.X_LI;
  ls.com = X_FI.p;
  const Eigen::Matrix3d R = X_FI.q.toRotationMatrix();
  if (in.mass > 0) {
    set_inertia_tensor(ls, R * in.I * R.transpose());
  } else {
    ls.inertia = Vec3::Zero();
  }
  for (uint64_t i = 0; i < link.SensorCount(); ++i) read_sensor(*link.SensorByIndex(i), link.Name(), X_FL, r, spec);
  const std::size_t lamps_before = spec.lights.size();
  for (uint64_t i = 0; i < link.LightCount(); ++i) read_light(*link.LightByIndex(i), link.Name(), X_FL, r, spec);
  // a model's lights are on in Gazebo; /lights switches them
  if (spec.lights.size() > lamps_before) spec.lights_on = true;
  return ls;
}

/// True for a link whose collision shapes are all spheres (at least one): a caster ball.
bool is_caster_ball(const sdf::Link* link) {
  if (!link || link->CollisionCount() == 0) return false;
  for (uint64_t i = 0; i < link->CollisionCount(); ++i) {
    const sdf::Geometry* g = link->CollisionByIndex(i)->Geom();
    if (!g || g->Type() != sdf::GeometryType::SPHERE) return false;
  }
  return true;
}

/// A ball joint holding a caster ball: rescuesim fixes the ball and makes it frictionless, which
/// rolls the same way on flat ground.
bool is_caster_joint(const sdf::Joint& j, const sdf::Model& model) {
  return j.Type() == sdf::JointType::BALL && is_caster_ball(model.LinkByName(j.ChildLinkName()));
}

JointSpec::Type joint_type(const sdf::Joint& j, const SourceRef& where, bool caster = false) {
  if (caster) return JointSpec::Type::fixed;
  switch (j.Type()) {
    case sdf::JointType::REVOLUTE: return JointSpec::Type::revolute;
    case sdf::JointType::CONTINUOUS: return JointSpec::Type::continuous;
    case sdf::JointType::PRISMATIC: return JointSpec::Type::prismatic;
    case sdf::JointType::FIXED: return JointSpec::Type::fixed;
    default: break;
  }
  const sdf::ElementPtr e = j.Element();
  const std::string type = e && e->HasAttribute("type") ? e->GetAttribute("type")->GetAsString() : "?";
  throw Error(where, "joint '" + j.Name() + "' is of type '" + type +
                         "', which rescuesim does not simulate (expected revolute, continuous, prismatic or fixed)");
}

/// A joint; X_PJ is already known (the joint frame in its parent's robot frame).
JointSpec joint_spec(const sdf::Joint& j, bool caster, const std::string& parent, const std::string& child, const Pose3& X_PJ,
                     const SourceRef& where) {
  JointSpec js;
  js.name = j.Name();
  js.type = joint_type(j, where, caster);
  js.parent = parent;
  js.child = child;
  js.X_PJ = X_PJ;
  const sdf::JointAxis* axis = j.Axis(0);
  if (js.type == JointSpec::Type::fixed || !axis) {
    js.axis = Vec3::UnitZ();
    return js;
  }
  // the axis may be written in another frame (<xyz expressed_in>): sdformat resolves it into the joint frame
  ignition::math::Vector3d xyz;
  const sdf::Errors errors = axis->ResolveXyz(xyz);
  if (!errors.empty()) throw Error(where, "joint '" + j.Name() + "': cannot resolve its <axis><xyz>: " + errors.front().Message());
  js.axis = vec_of(xyz);
  if (!(js.axis.norm() > 1e-9) || !js.axis.allFinite()) throw Error(where, "joint '" + j.Name() + "' has a zero or non-finite <axis><xyz>");
  js.axis.normalize();
  // sdformat's "no limit" is +-1e16: a revolute joint without limits turns freely
  const bool unlimited = std::abs(axis->Lower()) >= 1e15 || std::abs(axis->Upper()) >= 1e15;
  if (js.type == JointSpec::Type::revolute && unlimited) js.type = JointSpec::Type::continuous;
  if (js.type == JointSpec::Type::revolute || js.type == JointSpec::Type::prismatic) {
    if (axis->Lower() > axis->Upper()) {
      throw Error(where, "joint '" + j.Name() + "': <limit><lower> " + std::to_string(axis->Lower()) + " is above <upper> " +
                             std::to_string(axis->Upper()));
    }
    js.lower = axis->Lower();
    js.upper = axis->Upper();
    js.control = JointSpec::Control::position;
    js.initial = std::clamp(0.0, js.lower, js.upper);
  }
  if (axis->Effort() > 0 && std::isfinite(axis->Effort())) js.max_effort = axis->Effort();
  js.max_velocity = axis->MaxVelocity() > 0 && std::isfinite(axis->MaxVelocity()) ? axis->MaxVelocity()
                    : js.type == JointSpec::Type::continuous                   ? 20.0
                                                                               : js.max_velocity;
  js.damping = std::max(0.0, axis->Damping());
  js.friction = std::max(0.0, axis->Friction());
  return js;
}

/// One joint of the model as the builder sees it.
struct JointInfo {
  const sdf::Joint* joint;
  std::string parent, child;  ///< links
  Pose3 X_MJ;                 ///< in the model frame
  bool caster = false;        ///< a ball joint holding a caster ball (see is_caster_joint)
};

/// Makes a caster ball's collision shapes frictionless.
void make_frictionless(LinkSpec& ls, RobotSpec& spec) {
  MaterialSpec m = default_materials()[7];  // robot_body
  m.name = spec.model + "::" + ls.name + "::caster";
  m.friction = 0;
  spec.materials.push_back(m);
  for (LinkShape& sh : ls.shapes) {
    if (sh.collides) sh.material = m.name;
  }
}

}  // namespace

RobotSpec build_robot(const sdf::Model& model, const std::string& name, const std::vector<std::string>& skip_links, Reader& r,
                      RobotExtras& extras) {
  RobotSpec spec;
  spec.model = name;
  const std::string context = "<model name=\"" + name + "\">";
  const SourceRef at_model = r.at(model.Element());
  auto skipped = [&](const std::string& l) { return std::find(skip_links.begin(), skip_links.end(), l) != skip_links.end(); };

  // every link and joint frame in the model frame
  std::map<std::string, Pose3> X_ML;
  for (uint64_t i = 0; i < model.LinkCount(); ++i) {
    const sdf::Link& l = *model.LinkByIndex(i);
    X_ML[l.Name()] = resolve(l.SemanticPose(), "__model__", r.at(l.Element(), context));
  }
  std::vector<JointInfo> joints;
  for (uint64_t i = 0; i < model.JointCount(); ++i) {
    const sdf::Joint& j = *model.JointByIndex(i);
    const SourceRef at = r.at(j.Element(), context);
    JointInfo info{&j, "", "", resolve(j.SemanticPose(), "__model__", at), is_caster_joint(j, model)};
    sdf::Errors errors = j.ResolveParentLink(info.parent);
    if (errors.empty()) errors = j.ResolveChildLink(info.child);
    if (!errors.empty()) throw Error(at, "joint '" + j.Name() + "': " + errors.front().Message());
    if (skipped(info.child)) continue;
    joint_type(j, at, info.caster);  // refuse ball, universal, screw... before anything else
    if (info.caster) {
      r.diagnostics.warn(at, "ball joint '" + j.Name() + "' holds a caster ball: it is fixed and the ball made frictionless");
    }
    if (info.parent == "world")
      throw Error(at, "joint '" + j.Name() +
                          "' moves a link against the world; rescuesim robots move freely (only fixed joints to the world are read)");
    joints.push_back(info);
  }

  // links in tree order from the canonical link; each joint's child after its parent
  const std::string root =
      model.CanonicalLinkName().empty() && model.LinkCount() ? model.LinkByIndex(0)->Name() : model.CanonicalLinkName();
  if (root.empty()) throw Error(at_model, "model '" + name + "' has no links");
  std::vector<std::string> order{root};
  std::map<std::string, Pose3> X_MF{{root, X_ML.at(root)}};  // each robot link frame: the root's own, else its joint's
  std::vector<const JointInfo*> tree;
  for (std::size_t k = 0; k < order.size(); ++k) {
    for (const JointInfo& j : joints) {
      if (j.parent != order[k]) continue;
      if (X_MF.count(j.child))
        throw Error(r.at(j.joint->Element(), context),
                    "joint '" + j.joint->Name() + "' closes a loop: link '" + j.child + "' already has a parent");
      order.push_back(j.child);
      X_MF[j.child] = j.X_MJ;
      tree.push_back(&j);
    }
  }
  for (const auto& [link, X] : X_ML) {
    if (!X_MF.count(link) && !skipped(link)) {
      r.diagnostics.warn(at_model,
                         quoted("link", link) + " is not joined to the canonical link '" + root + "' and is left out of the robot");
    }
  }

  for (const std::string& l : order) {
    const sdf::Link& link = *model.LinkByName(l);
    spec.links.push_back(link_spec(link, X_MF.at(l).inverse() * X_ML.at(l), name, r, spec));
  }
  for (const JointInfo* j : tree) {
    if (j->caster) make_frictionless(spec.links[static_cast<std::size_t>(spec.link_index(j->child))], spec);
    spec.joints.push_back(
        joint_spec(*j->joint, j->caster, j->parent, j->child, X_MF.at(j->parent).inverse() * j->X_MJ, r.at(j->joint->Element(), context)));
  }
  // Bullet cannot move a body without mass
  for (std::size_t i = 1; i < spec.links.size(); ++i) {
    LinkSpec& ls = spec.links[i];
    if (ls.mass > 0) continue;
    ls.mass = 0.01;
    ls.inertia = Vec3::Constant(1e-5);
    r.diagnostics.warn(at_model, quoted("link", ls.name) + " moves but has no mass: giving it 0.01 kg");
  }

  for (const auto& [filename, plugin] : plugins_of(model.Element())) {
    if (is_drive_plugin(filename) && extras.drive_source.empty()) {
      read_drive(plugin, filename, r, spec);
      extras.drive_source = "plugin " + filename;
      extras.plugins_honoured.push_back(name + "::" + filename);
      continue;
    }
    extras.plugins_ignored.push_back(name + "::" + filename);
    if (!is_covered_plugin(filename))
      r.diagnostics.warn(r.at(plugin, context), "plugin '" + filename + "' is ignored: rescuesim does not know what it does");
  }
  if (extras.drive_source.empty()) {
    r.diagnostics.warn(at_model, "model '" + name + "' has no diff-drive plugin: the robot has no drive (it will not answer cmd_vel)");
  }
  add_standard_sensors(spec);
  return spec;
}

}  // namespace rescuesim::sdf_detail

namespace rescuesim {

namespace {

/// An SdfRobot from a URDF file (sdformat could read it too, but the URDF importer gives the
/// same robot a URDF scenario would, with its line numbers).
SdfRobot from_urdf(const std::filesystem::path& file, const SdfOptions& options) {
  UrdfOptions o;
  o.resolver = options.resolver;
  o.hull_vertices = options.hull_vertices;
  o.collision = options.collision;
  o.max_triangles = options.max_triangles;
  o.default_density = options.default_density;
  UrdfRobot u = load_urdf(file, o);
  SdfRobot out;
  out.spec = std::move(u.spec);
  out.diagnostics = std::move(u.diagnostics);
  for (const auto& m : u.meshes) out.meshes.push_back({out.spec.model, m.link, m.uri, m.file, m.collision, false, m.triangles, "", false});
  out.drive_source = u.drive_source;
  out.load_seconds = u.load_seconds + u.hull_seconds;
  return out;
}

}  // namespace

SdfRobot load_sdf_robot(const std::string& uri, const SdfOptions& options, const SourceRef& where) {
  using namespace sdf_detail;
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path file = resolve_model_uri(uri, options, where);
  if (is_urdf_path(file)) return from_urdf(file, options);
  SdfRobot out;
  const std::string text = read_text(file);
  Parsed parsed;
  parse_sdf(text, file.string(), options, parsed, out.diagnostics);
  const sdf::Model* model = parsed.root.Model();
  if (!model && parsed.root.WorldCount() > 0 && parsed.root.WorldByIndex(0)->ModelCount() > 0)
    model = parsed.root.WorldByIndex(0)->ModelByIndex(0);
  if (!model) throw Error({file.string(), 0, "<sdf>"}, "no <model> in the file: expected the robot's model");
  Reader reader{options, file.string(), out.diagnostics, out.meshes, {}};
  RobotExtras extras;
  out.spec = build_robot(*model, model->Name(), {}, reader, extras);
  out.spec.source_file = file.string();
  out.spec.description = text;
  out.drive_source = extras.drive_source;
  out.plugins_ignored = extras.plugins_ignored;
  out.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace rescuesim
