// rescuesim check: read SVG worlds or scenario files and say what they contain or what is wrong.

#include <cstdio>
#include <filesystem>
#include <vector>

#include "app/commands.h"
#include "app/data_dir.h"
#include "import/scenario/scenario.h"
#include "import/sdf/sdf_import.h"
#include "import/svg/svg_world.h"
#include "import/urdf/urdf_import.h"
#include "robots/rescue_robot.h"
#include "world/robot_lumping.h"

namespace rescuesim::app {

namespace {

struct CheckOptions {
  std::vector<std::string> files;
  double scale = 100.0;
  std::vector<std::string> resource_paths;
};

const char* joint_type_name(JointSpec::Type t) {
  switch (t) {
    case JointSpec::Type::revolute: return "revolute";
    case JointSpec::Type::continuous: return "continuous";
    case JointSpec::Type::prismatic: return "prismatic";
    case JointSpec::Type::fixed: return "fixed";
  }
  return "?";
}

std::string names(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& n : v) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// Checks a URDF robot and prints what was understood.
bool check_urdf(const std::string& file, const CheckOptions& o) {
  UrdfOptions uo;
  uo.resolver = ResourceResolver(std::vector<std::filesystem::path>(o.resource_paths.begin(), o.resource_paths.end()));
  UrdfRobot u;
  try {
    u = load_urdf(file, uo);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error\n  %s\n", file.c_str(), e.what());
    return false;
  }
  const RobotSpec& r = u.spec;
  const LumpedRobot lumped = lump_fixed_joints(r);
  std::printf("%s: ok (URDF robot '%s', root link %s)\n", file.c_str(), r.model.c_str(), u.root_link.c_str());
  std::printf("  %zu links, %zu joints (%d moving, %d fixed); total mass %.4g kg; %zu rigid bodies for physics (fixed joints merged)\n",
              r.links.size(), r.joints.size(), u.moving_joints, u.fixed_joints, r.total_mass(), lumped.spec.links.size());
  for (const auto& l : r.links) {
    int collision = 0, visual = 0;
    for (const auto& sh : l.shapes) (sh.collides ? collision : visual)++;
    std::printf("  link  %-24s %8.4g kg  inertia (%.3g, %.3g, %.3g) kg m^2  %d collision, %d visual shape(s)\n", l.name.c_str(), l.mass,
                l.inertia.x(), l.inertia.y(), l.inertia.z(), collision, visual);
  }
  for (const auto& j : r.joints) {
    std::printf("  joint %-24s %-10s %s -> %s", j.name.c_str(), joint_type_name(j.type), j.parent.c_str(), j.child.c_str());
    if (j.type != JointSpec::Type::fixed) std::printf("  axis (%.3g, %.3g, %.3g)", j.axis.x(), j.axis.y(), j.axis.z());
    if (j.type == JointSpec::Type::revolute || j.type == JointSpec::Type::prismatic) std::printf("  limits [%.4g, %.4g]", j.lower, j.upper);
    if (!j.mimic.empty()) std::printf("  mimics %s", j.mimic.c_str());
    std::printf("\n");
  }
  for (const auto& m : u.meshes) {
    if (m.collision) {
      std::printf("  mesh  %s (%s): collision, %d triangles -> %d convex piece(s), %d hull vertices; volume %.4g m^3, hull %.4g m^3\n",
                  m.uri.c_str(), m.link.c_str(), m.triangles, m.pieces, m.hull_vertices, m.mesh_volume, m.hull_volume);
    } else {
      std::printf("  mesh  %s (%s): visual, %d triangles\n", m.uri.c_str(), m.link.c_str(), m.triangles);
    }
  }
  for (const auto& s : r.sensors) {
    std::printf("  sensor %-20s %-13s on %-16s %6.4g Hz  topic %s\n", s.name.c_str(), sensor_type_name(s.type), s.link.c_str(), s.rate,
                s.topic.c_str());
  }
  if (r.drive.left_wheels.empty()) {
    std::printf("  drive: none (give one in the scenario: drive: {type: diff_drive, left: [...], right: [...]})\n");
  } else {
    std::printf("  drive: diff_drive from %s; left [%s], right [%s]; wheel radius %.4g m, separation %.4g m\n", u.drive_source.c_str(),
                names(r.drive.left_wheels).c_str(), names(r.drive.right_wheels).c_str(), r.drive.wheel_radius, r.drive.track_width);
  }
  std::printf("  read in %.3f s, convex hulls in %.3f s\n", u.load_seconds, u.hull_seconds);
  if (!u.diagnostics.items().empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "  %d warning(s):\n", u.diagnostics.warning_count());
    print_diagnostics(u.diagnostics);
  }
  return true;
}

const char* light_type_name(LightSpec::Type t) {
  switch (t) {
    case LightSpec::Type::directional: return "directional";
    case LightSpec::Type::point: return "point";
    case LightSpec::Type::spot: return "spot";
  }
  return "?";
}

/// Checks an SDF world (or model) and prints what each model became.
bool check_sdf(const std::string& file, const CheckOptions& o) {
  SdfOptions so;
  so.resolver = ResourceResolver(std::vector<std::filesystem::path>(o.resource_paths.begin(), o.resource_paths.end()));
  SdfWorld w;
  try {
    w = load_sdf_world(file, so);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error\n  %s\n", file.c_str(), e.what());
    return false;
  }
  Diagnostics diag = w.diagnostics;
  diag.append(validate(w.spec));
  const bool ok = !diag.has_errors();
  std::printf("%s: %s (SDF %s, world '%s', read in %.3f s)\n%s", file.c_str(), ok ? "ok" : "has errors", w.sdf_version.c_str(),
              w.spec.name.c_str(), w.load_seconds, world_summary(w.spec).c_str());
  std::printf("  gravity       %.4g m/s^2; physics step %s\n", w.spec.gravity,
              w.spec.physics_dt > 0 ? (std::to_string(w.spec.physics_dt) + " s").c_str() : "the scenario's");
  for (const auto& m : w.models) {
    std::printf("  model %-28s %-16s %s%d link(s), %d joint(s), %d collision(s), %d visual(s)\n", m.name.c_str(), m.becomes.c_str(),
                m.is_static ? "static, " : "", m.links, m.joints, m.collisions, m.visuals);
  }
  for (const auto& m : w.meshes) {
    std::string texture;
    if (!m.texture.empty())
      texture = "; texture " + m.texture + (m.texture_drawn ? " (drawn)" : " (not drawn: missing, or on a convex shape)");
    std::printf("  mesh  %s (%s::%s): %s, %d triangles%s%s\n", m.uri.c_str(), m.model.c_str(), m.link.c_str(),
                m.collision ? "collision" : "visual", m.triangles, m.collision ? (m.exact ? ", exact triangle mesh" : ", convex") : "",
                texture.c_str());
  }
  for (const auto& l : w.spec.lights) {
    std::printf("  light %-20s %s\n", l.name.c_str(), light_type_name(l.type));
  }
  for (const auto& [name, r] : w.robots) {
    std::printf("  robot %s: %zu links, %zu joints, %zu sensors; drive %s\n", name.c_str(), r.links.size(), r.joints.size(),
                r.sensors.size(), r.drive.left_wheels.empty() ? "none" : ("left [" + names(r.drive.left_wheels) + "], right [" +
                                                                          names(r.drive.right_wheels) + "]").c_str());
  }
  if (!w.plugins_honoured.empty()) std::printf("  plugins honoured: %s\n", names(w.plugins_honoured).c_str());
  if (!w.plugins_ignored.empty()) std::printf("  plugins ignored:  %s\n", names(w.plugins_ignored).c_str());
  if (!diag.items().empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "  %d error(s), %d warning(s):\n", diag.error_count(), diag.warning_count());
    print_diagnostics(diag);
  }
  return ok;
}

/// Checks one file; returns true when it is usable.
bool check_one(const std::string& file, const CheckOptions& o) {
  const std::filesystem::path p(file);
  const std::string ext = p.extension().string();
  if (ext == ".urdf" || ext == ".xacro") return check_urdf(file, o);
  if (is_sdf_path(p)) return check_sdf(file, o);
  WorldSpec world;
  Diagnostics diag;
  std::string scale_note, mission;
  try {
    if (ext == ".yaml" || ext == ".yml") {
      const Scenario s = load_scenario(p, builtin_models());
      for (const auto& robot : s.robots) diag.append(robot.diagnostics);  // warnings from their URDFs
      world = build_world(s, &diag);
      scale_note = "scenario '" + s.name + "', seed " + std::to_string(s.seed);
      if (s.mission) mission = mission_summary(*s.mission, world);
    } else {
      SvgLoadOptions svg;
      svg.units_per_metre = o.scale;
      SvgLoadResult r = load_svg_world(p, svg);
      world = std::move(r.world);
      diag = std::move(r.diagnostics);
      scale_note = "scale: " + r.scale_source;
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error\n  %s\n", file.c_str(), e.what());
    return false;
  }
  const Diagnostics problems = validate(world);
  diag.append(problems);
  const bool ok = !diag.has_errors();
  std::printf("%s: %s (%s)\n%s%s", file.c_str(), ok ? "ok" : "has errors", scale_note.c_str(), world_summary(world).c_str(),
              mission.c_str());
  if (!diag.items().empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "  %d error(s), %d warning(s):\n", diag.error_count(), diag.warning_count());
    print_diagnostics(diag);
  }
  return ok;
}

}  // namespace

void add_check_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* cmd =
      app.add_subcommand("check", "Read SVG worlds, scenario YAML, SDF worlds or URDF robots and print what they contain, or their errors");
  cmd->footer(
      "For worlds: the size in metres and counts of walls, obstacles, raised areas, victims,\n"
      "rubble and robot starts. For URDF robots: links with masses, joints, meshes with their\n"
      "triangle and convex-hull vertex counts, sensors and the drive. For SDF worlds (.sdf, .world):\n"
      "each model and what it became (static geometry, rigid body, robot, victim, robot start),\n"
      "meshes with triangle counts, lights, and the plugins honoured and ignored. Then any warnings and\n"
      "errors with file, line and element.\n"
      "Exit code 0 when every file is usable, 2 when any has errors.\n\n"
      "Examples:\n"
      "  rescuesim check worlds/arena.svg\n"
      "  rescuesim check worlds/default.yaml mazes/*.svg\n"
      "  rescuesim check --resource-path worlds/robots worlds/robots/turtlebot3_description/urdf/turtlebot3_burger.urdf\n"
      "  rescuesim check --resource-path worlds/models worlds/rubble_yard.sdf");
  cmd->add_option("files", o->files, "SVG drawings (.svg), scenarios (.yaml), SDF worlds (.sdf, .world) or robots (.urdf)")->required();
  cmd->add_option("--resource-path", o->resource_paths,
                  "URDF, SDF: a folder where package:// and model:// URIs are looked for first (repeatable; then ROS_PACKAGE_PATH, "
                  "AMENT_PREFIX_PATH; for model:// GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH, GAZEBO_MODEL_PATH)")
      ->allow_extra_args(false);
  cmd->add_option("--scale", o->scale, "SVG user units per metre when a drawing has no physical units")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->final_callback([o, &action] {
    action = [o] {
      bool all_ok = true;
      for (const auto& f : o->files) {
        // a relative name not found here may be one of the installed worlds; a missing file is check_one's to report
        std::string path = f;
        try {
          path = locate_data_file(f);
        } catch (const Error&) {
        }
        all_ok = check_one(path, *o) && all_ok;
      }
      return all_ok ? kExitOk : kExitBadInput;
    };
  });
}

}  // namespace rescuesim::app
