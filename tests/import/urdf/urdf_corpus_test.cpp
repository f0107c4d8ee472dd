// The conformance corpus (tests/data/thirdparty/robots, corpus.yaml; each file's source,
// commit and licence in SOURCE.md): public URDFs read by ROS's own parser, urdfdom, and by
// rescuesim, compared. The rule: what urdfdom accepts, rescuesim loads and reads the same way
// (links, joints, axes, limits, origins, masses, inertias), and what it reads differently it
// says in a warning; what urdfdom refuses, rescuesim refuses. The one exception: a collision
// mesh that is not there (the corpus left some out for size) is an error in rescuesim, where
// Gazebo drops the collision with an error line, because the robot would not touch the world.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Eigenvalues>
#include <console_bridge/console.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "import/urdf/urdf_import.h"
#include "world/robot_lumping.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;

std::filesystem::path corpus_dir() { return std::filesystem::path(RESCUESIM_SOURCE_DIR) / "tests/data/thirdparty/robots"; }

struct CorpusFile {
  std::string name, file;
  std::set<std::string> dropped, dropped_collision;  ///< mesh URIs left out of the corpus
};

std::vector<CorpusFile> corpus_urdfs() {
  std::vector<CorpusFile> out;
  for (const auto& e : YAML::LoadFile((corpus_dir() / "corpus.yaml").string())) {
    if (e["format"].as<std::string>() != "urdf") continue;
    CorpusFile f{e["name"].as<std::string>(), e["file"].as<std::string>(), {}, {}};
    for (const auto& d : e["meshes_dropped"]) {
      f.dropped.insert(d["uri"].as<std::string>());
      if (d["reason"].as<std::string>().find("collision") != std::string::npos) f.dropped_collision.insert(d["uri"].as<std::string>());
    }
    out.push_back(f);
  }
  return out;
}

/// urdfdom's model of `text`, or null when it refuses it (as check_urdf would); its console
/// output is kept quiet.
urdf::ModelInterfaceSharedPtr urdfdom_model(const std::string& text) {
  const console_bridge::LogLevel level = console_bridge::getLogLevel();
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception&) {
    model = nullptr;
  }
  console_bridge::setLogLevel(level);  // the importer's own tests read urdfdom's warnings
  return model;
}

/// Every package:// of the corpus resolves inside the robot's own folder; nothing from the
/// environment.
UrdfOptions corpus_options(const CorpusFile& f) {
  UrdfOptions o;
  o.resolver = ResourceResolver({corpus_dir() / std::filesystem::path(f.file).begin()->string()}, false);
  return o;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

bool warned(const UrdfRobot& r, const std::string& what) {
  for (const auto& d : r.diagnostics.items()) {
    if (d.message.find(what) != std::string::npos) return true;
  }
  return false;
}

Eigen::Matrix3d urdfdom_inertia(const urdf::Inertial& in) {
  Eigen::Matrix3d I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  double x, y, z, w;
  in.origin.rotation.getQuaternion(x, y, z, w);
  const Eigen::Matrix3d R = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  return R * I * R.transpose();
}

/// What rescuesim read compared with urdfdom's model: one line per difference.
std::vector<std::string> differences(const urdf::ModelInterface& ros, const UrdfRobot& ours) {
  std::vector<std::string> out;
  const RobotSpec& spec = ours.spec;
  const bool free_base = warned(ours, "is the robot's free base");
  for (const auto& [name, link] : ros.links_) {
    const int i = spec.link_index(name);
    if (i < 0) {
      if (!(free_base && !link->parent_joint && !link->inertial && link->visual_array.empty())) {
        out.push_back("link '" + name + "' missing");
      }
      continue;
    }
    const LinkSpec& l = spec.links[static_cast<std::size_t>(i)];
    // a corrected inertia says so (make_bodies_physical); the rest equal urdfdom's
    if (link->inertial && !warned(ours, "link '" + name + "'")) {
      if (std::abs(l.mass - link->inertial->mass) > 1e-12 * std::max(1.0, link->inertial->mass)) {
        out.push_back("link '" + name + "' mass " + std::to_string(l.mass));
      }
      const Eigen::Matrix3d want = urdfdom_inertia(*link->inertial), got = inertia_tensor(l);
      if ((want - got).norm() > 1e-9 * std::max(1.0, want.norm())) out.push_back("link '" + name + "' inertia");
      const auto& p = link->inertial->origin.position;
      if ((l.com - Vec3(p.x, p.y, p.z)).norm() > 1e-12) out.push_back("link '" + name + "' centre of mass");
    }
  }
  for (const auto& [name, joint] : ros.joints_) {
    const int i = spec.joint_index(name);
    if (i < 0) {
      if (!(free_base && joint->type == urdf::Joint::FLOATING)) out.push_back("joint '" + name + "' missing");
      continue;
    }
    const JointSpec& j = spec.joints[static_cast<std::size_t>(i)];
    const std::map<int, JointSpec::Type> types{{urdf::Joint::REVOLUTE, JointSpec::Type::revolute},
                                               {urdf::Joint::CONTINUOUS, JointSpec::Type::continuous},
                                               {urdf::Joint::PRISMATIC, JointSpec::Type::prismatic},
                                               {urdf::Joint::FIXED, JointSpec::Type::fixed}};
    if (!types.count(joint->type) || types.at(joint->type) != j.type) out.push_back("joint '" + name + "' type");
    if (j.parent != joint->parent_link_name || j.child != joint->child_link_name) out.push_back("joint '" + name + "' parent or child");
    const auto& o = joint->parent_to_joint_origin_transform;
    double x, y, z, w;
    o.rotation.getQuaternion(x, y, z, w);
    if ((j.X_PJ.p - Vec3(o.position.x, o.position.y, o.position.z)).norm() > 1e-12 ||
        j.X_PJ.q.angularDistance(Quat(w, x, y, z).normalized()) > 1e-9) {
      out.push_back("joint '" + name + "' origin");
    }
    if (joint->type != urdf::Joint::FIXED) {
      const Vec3 axis = Vec3(joint->axis.x, joint->axis.y, joint->axis.z).normalized();
      if ((j.axis - axis).norm() > 1e-12) out.push_back("joint '" + name + "' axis");
    }
    if (joint->limits && (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC)) {
      if (j.lower != joint->limits->lower || j.upper != joint->limits->upper) out.push_back("joint '" + name + "' limits");
    }
    // a drive plugin's torque is its wheels' effort limit, in Gazebo as here
    const auto& d = spec.drive;
    const bool wheel =
        std::count(d.left_wheels.begin(), d.left_wheels.end(), name) + std::count(d.right_wheels.begin(), d.right_wheels.end(), name);
    if (joint->limits && joint->limits->effort > 0 && j.max_effort != joint->limits->effort && !wheel) {
      out.push_back("joint '" + name + "' effort");
    }
    if (joint->limits && joint->limits->velocity > 0 && j.max_velocity != joint->limits->velocity) {
      out.push_back("joint '" + name + "' velocity");
    }
  }
  return out;
}

/// Every mesh URI of urdfdom's model.
std::set<std::string> mesh_uris(const urdf::ModelInterface& ros) {
  std::set<std::string> out;
  for (const auto& [name, link] : ros.links_) {
    for (const auto& v : link->visual_array) {
      if (v && v->geometry && v->geometry->type == urdf::Geometry::MESH) out.insert(static_cast<const urdf::Mesh&>(*v->geometry).filename);
    }
    for (const auto& c : link->collision_array) {
      if (c && c->geometry && c->geometry->type == urdf::Geometry::MESH) out.insert(static_cast<const urdf::Mesh&>(*c->geometry).filename);
    }
  }
  return out;
}

TEST(UrdfCorpus, WhatUrdfdomReadsRescuesimReadsTheSame) {
  const auto files = corpus_urdfs();
  ASSERT_GE(files.size(), 25u);
  int loaded = 0, refused_by_both = 0, refused_for_missing_collision = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f.name + " (" + f.file + ")");
    const std::filesystem::path path = corpus_dir() / f.file;
    // rescuesim fills TurtleBot3's ${namespace} with "" before urdfdom reads it; so does this
    const auto ros = urdfdom_model(replace_all(read_file(path), "${namespace}", ""));
    std::optional<UrdfRobot> ours;
    std::string error;
    try {
      ours = load_urdf(path, corpus_options(f));
    } catch (const Error& e) {
      error = e.what();
      EXPECT_THAT(error, HasSubstr(f.file)) << "an error names the file";
    }
    if (!ros) {
      EXPECT_FALSE(ours) << "urdfdom refuses it, rescuesim loaded it";
      ++refused_by_both;
      continue;
    }
    if (!f.dropped_collision.empty()) {
      EXPECT_FALSE(ours) << "a collision mesh is not in the corpus";
      bool names_one = false;
      for (const auto& uri : f.dropped_collision) names_one = names_one || error.find(uri) != std::string::npos;
      EXPECT_TRUE(names_one) << error;
      ++refused_for_missing_collision;
      continue;
    }
    ASSERT_TRUE(ours) << "urdfdom reads it, rescuesim refused: " << error;
    ++loaded;
    EXPECT_THAT(differences(*ros, *ours), ::testing::IsEmpty());
    // every mesh resolves, except those the corpus left out, each of which is a warning
    std::set<std::string> resolved;
    for (const auto& m : ours->meshes) resolved.insert(m.uri);
    for (const auto& uri : mesh_uris(*ros)) {
      if (f.dropped.count(uri)) {
        EXPECT_TRUE(warned(*ours, uri)) << uri << " left out without a warning";
      } else {
        EXPECT_TRUE(resolved.count(uri)) << uri << " not loaded";
      }
    }
    // every rigid body physics sees is physical
    const LumpedRobot lumped = lump_fixed_joints(ours->spec);
    for (const LinkSpec& body : lumped.spec.links) {
      EXPECT_GT(body.mass, 0) << body.name;
      const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_tensor(body)).eigenvalues();
      EXPECT_GT(p[0], 0) << body.name;
      EXPECT_GE(p[0] + p[1], p[2] * (1 - 1e-9)) << body.name;
    }
  }
  // the counts the docs give (docs/robots.md, "Files from the wild")
  EXPECT_EQ(loaded + refused_by_both + refused_for_missing_collision, static_cast<int>(files.size()));
  std::printf("URDF corpus: %zu files, %d loaded, %d refused by urdfdom too, %d missing a collision mesh\n", files.size(), loaded,
              refused_by_both, refused_for_missing_collision);
}

UrdfRobot corpus_robot(const std::string& name) {
  for (const auto& f : corpus_urdfs()) {
    if (f.name == name) return load_urdf(corpus_dir() / f.file, corpus_options(f));
  }
  throw std::runtime_error("no corpus file " + name);
}

double friction_of(const UrdfRobot& r, const std::string& link) {
  const LinkSpec& l = r.spec.links[static_cast<std::size_t>(r.spec.link_index(link))];
  for (const LinkShape& sh : l.shapes) {
    if (!sh.collides) continue;
    for (const auto& m : r.spec.materials) {
      if (m.name == sh.material) return m.friction;
    }
  }
  return -1;
}

TEST(UrdfCorpus, GazeboFrictionInTheValueAttributeFormIsRead) {
  // the racecar's <gazebo reference> blocks write <mu1 value="1.0"/>, which Gazebo's URDF
  // conversion reads before any text (it was friction 0 before, and the wheels spun in place)
  const UrdfRobot car = corpus_robot("pybullet_racecar");
  EXPECT_EQ(friction_of(car, "left_rear_wheel"), 1.0);
  EXPECT_EQ(friction_of(car, "right_front_wheel"), 1.0);
  EXPECT_EQ(friction_of(car, "left_front_wheel"), 1.0);
  // and the text form, in the Pioneer 3-AT's: <mu1>1.0</mu1>
  const UrdfRobot p3at = corpus_robot("pioneer3at");
  EXPECT_EQ(friction_of(p3at, "p3at_front_left_wheel"), 1.0);
  // what the blocks hold beyond friction is ignored, one warning each (the chassis: kp, kd, material)
  EXPECT_TRUE(warned(car, "link 'chassis': Gazebo's <kp> is ignored"));
  EXPECT_TRUE(warned(car, "link 'chassis': Gazebo's <material> is ignored"));
}

TEST(UrdfCorpus, AMaterialInsideGeometryIsSkippedAsUrdfdomSkipsIt) {
  // the racecar's laser link: <geometry><mesh .../><material name="grey"/></geometry>
  const UrdfRobot car = corpus_robot("pybullet_racecar");
  EXPECT_TRUE(warned(car, "link 'laser': <material> inside <geometry> after the <mesh> is ignored"));
  bool laser_mesh = false;
  for (const auto& m : car.meshes) laser_mesh = laser_mesh || (m.link == "laser" && m.uri == "meshes/hokuyo.obj");
  EXPECT_TRUE(laser_mesh);
}

TEST(UrdfCorpus, ImpossibleInertiasOnlyMatterOnTheBodiesPhysicsSees) {
  // ANYmal C: four depth-camera links fixed to the base break the triangle inequality on their
  // own; merged into the base they do not, so nothing is said about them
  const UrdfRobot anymal = corpus_robot("anymal_c");
  EXPECT_FALSE(warned(anymal, "depth_camera_front_camera"));
  EXPECT_FALSE(warned(anymal, "balanceinertia"));
  // the Robotiq 3-finger gripper's finger links move: each of the nine is balanced, with a warning
  const UrdfRobot robotiq = corpus_robot("robotiq_3f");
  int balanced = 0;
  for (const auto& d : robotiq.diagnostics.items()) balanced += d.message.find("balanceinertia") != std::string::npos;
  EXPECT_EQ(balanced, 9);
  // finger_1_link_0 (ixx 0.01, iyy 0.0008, izz 0.001 and small products): the average of its
  // principal moments is a third of the trace, 0.0118 / 3 kg m^2, each
  const LinkSpec& l = robotiq.spec.links[static_cast<std::size_t>(robotiq.spec.link_index("finger_1_link_0"))];
  const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_tensor(l)).eigenvalues();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], 0.0118 / 3, 1e-12);
}

TEST(UrdfCorpus, AFloatingJointFromAnEmptyWorldLinkIsTheFreeBase) {
  // Unitree B2 (SolidWorks export): world --floating--> base_link
  const UrdfRobot b2 = corpus_robot("unitree_b2_sw");
  EXPECT_EQ(b2.root_link, "base_link");
  EXPECT_LT(b2.spec.link_index("world"), 0);
  EXPECT_TRUE(warned(b2, "floating joint 'floating_base_joint' from the empty root link 'world' is the robot's free base"));
}

}  // namespace
}  // namespace rescuesim
