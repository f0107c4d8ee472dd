// rescuesim check: read SVG worlds or scenario files and say what they contain or what is wrong.

#include <cstdio>
#include <filesystem>
#include <vector>

#include "app/commands.h"
#include "robots/rescue_robot.h"
#include "world/scenario/scenario.h"
#include "world/svg/svg_world.h"

namespace rescuesim::app {

namespace {

struct CheckOptions {
  std::vector<std::string> files;
  double scale = 100.0;
};

/// Checks one file; returns true when it is usable.
bool check_one(const std::string& file, const CheckOptions& o) {
  const std::filesystem::path p(file);
  const std::string ext = p.extension().string();
  WorldSpec world;
  Diagnostics diag;
  std::string scale_note;
  try {
    if (ext == ".yaml" || ext == ".yml") {
      const Scenario s = load_scenario(p, builtin_models());
      world = build_world(s, &diag);
      scale_note = "scenario '" + s.name + "', seed " + std::to_string(s.seed);
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
  std::printf("%s: %s (%s)\n%s", file.c_str(), ok ? "ok" : "has errors", scale_note.c_str(), world_summary(world).c_str());
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
  CLI::App* cmd = app.add_subcommand("check", "Read SVG worlds or scenario YAML files and print what they contain, or their errors");
  cmd->footer(
      "Prints the world's size in metres and counts of walls, obstacles, raised areas, victims,\n"
      "rubble and robot starts, then any warnings and errors with file, line and element.\n"
      "Exit code 0 when every file is usable, 2 when any has errors.\n\n"
      "Examples:\n"
      "  rescuesim check worlds/arena.svg\n"
      "  rescuesim check worlds/default.yaml mazes/*.svg");
  cmd->add_option("files", o->files, "SVG drawings (.svg) or scenarios (.yaml)")->required();
  cmd->add_option("--scale", o->scale, "SVG user units per metre when a drawing has no physical units")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->final_callback([o, &action] {
    action = [o] {
      bool all_ok = true;
      for (const auto& f : o->files) all_ok = check_one(f, *o) && all_ok;
      return all_ok ? kExitOk : kExitBadInput;
    };
  });
}

}  // namespace rescuesim::app
