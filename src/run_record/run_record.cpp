#include "run_record/run_record.h"

#include <charconv>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "import/svg/svg_world.h"

namespace rescuesim {

namespace {

/// The shortest text that reads back as exactly `v`.
std::string exact(double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

const std::string* find(const mcap::KeyValues& kv, const std::string& key) {
  for (const auto& [k, v] : kv) {
    if (k == key) return &v;
  }
  return nullptr;
}

}  // namespace

void describe_run(McapOptions& o, const Scenario& s, const WorldSpec& world, bool cameras, const std::string& version) {
  o.library = "rescuesim " + version;
  o.lossless = !s.realtime;
  o.metadata.push_back({kRunMetadataName,
                        {{"version", version},
                         {"scenario", s.name},
                         {"scenario_file", s.source_file},
                         {"seed", std::to_string(s.seed)},
                         {"mode", s.realtime ? "realtime" : "lockstep"},
                         {"rate", exact(s.rate)},
                         {"duration_s", exact(s.duration)},
                         {"physics_dt_s", exact(s.physics_dt)},
                         {"solver_iterations", std::to_string(s.solver_iterations)},
                         {"physics_groups", std::to_string(s.physics_groups)},
                         {"cameras", cameras ? "on" : "off"},
                         {"render_quality", s.render_quality},
                         {"world", world.name},
                         {"world_seed", std::to_string(world.seed)},
                         {"log_time", "sim time (ns) when the message was published"},
                         {"publish_time", "the message's header stamp (its log time when it has none)"}}});
  // the scenario text as it was read, so replay parses the same robots and sensors
  std::string yaml;
  if (s.source_file == "<built-in>") {
    yaml = default_scenario_text();
  } else if (!s.source_file.empty()) {
    try {
      yaml = read_file(s.source_file);
    } catch (const Error& e) {
      log::warn("mcap: the recording will not hold the scenario text: {}", e.what());
    }
  }
  if (!yaml.empty()) o.attachments.push_back({0, 0, kScenarioAttachmentName, "application/yaml", bytes_of(yaml)});
  o.attachments.push_back({0, 0, kWorldAttachmentName, "image/svg+xml", bytes_of(world_to_svg(world))});
}

RecordedRun rebuild_run(const mcap::McapReader& reader, const ModelMap& models) {
  const std::string file = reader.path().string();
  const mcap::Metadata* md = reader.find_metadata(kRunMetadataName);
  const mcap::Attachment* svg = reader.find_attachment(kWorldAttachmentName);
  if (!md || !svg) {
    throw Error({file, 0, ""}, std::string("not a rescuesim recording: it has no '") + (md ? kWorldAttachmentName : kRunMetadataName) +
                                   "' " + (md ? "attachment" : "metadata record") + ", so replay cannot rebuild the world it ran in");
  }
  RecordedRun run;
  run.info = md->entries;
  const mcap::Attachment* yaml = reader.find_attachment(kScenarioAttachmentName);
  if (yaml) {
    run.scenario = parse_scenario(std::string(yaml->data.begin(), yaml->data.end()), file + ":" + kScenarioAttachmentName, models);
  }
  // what the command line changed is in the metadata
  const auto number = [&](const char* key, auto fallback) {
    const std::string* v = find(md->entries, key);
    if (!v) return fallback;
    try {
      if constexpr (std::is_same_v<decltype(fallback), double>) {
        return std::stod(*v);
      } else {
        return static_cast<decltype(fallback)>(std::stoull(*v));
      }
    } catch (const std::exception&) {
      throw Error({file, 0, std::string("metadata '") + kRunMetadataName + "'." + key}, "'" + *v + "' is not a number");
    }
  };
  Scenario& s = run.scenario;
  if (const std::string* name = find(md->entries, "scenario")) s.name = *name;
  s.seed = number("seed", s.seed);
  s.duration = number("duration_s", s.duration);
  s.physics_dt = number("physics_dt_s", s.physics_dt);
  s.solver_iterations = number("solver_iterations", s.solver_iterations);
  s.physics_groups = number("physics_groups", s.physics_groups);
  s.svg.reset();
  s.maze.reset();

  // the world as it ran
  SvgLoadResult loaded = load_svg_world_from_string(std::string(svg->data.begin(), svg->data.end()), file + ":" + kWorldAttachmentName,
                                                    s.svg_options);
  run.spec = std::move(loaded.world);
  run.spec.ambient_temperature = s.svg_options.ambient_temperature;
  validate(run.spec).throw_if_errors();
  run.world = compile_scenario(s, run.spec, models);
  const std::string* cameras = find(md->entries, "cameras");
  if (cameras && *cameras == "off") {
    for (auto& robot : run.world.robots) {
      for (auto& sensor : robot.spec.sensors) {
        if (sensor.is_camera()) sensor.enabled = false;
      }
    }
  }
  return run;
}

RebuildWorld rebuild_into(RecordedRun& run, const ModelMap& models) {
  return [&run, models](const mcap::McapReader& reader) {
    run = rebuild_run(reader, models);
    ReplayWorld replayed{std::move(run.world), run.scenario.seed};
    run.world = World{};
    return replayed;
  };
}

}  // namespace rescuesim
