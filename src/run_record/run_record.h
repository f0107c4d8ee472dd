#pragma once
/// What a recording keeps about its run besides the messages, and how `rescuesim replay`
/// rebuilds a simulation from it:
///   Metadata "rescuesim"   version, scenario name and file, seed, mode, duration, physics
///                          step, cameras on/off, world name and seed
///   Attachment scenario.yaml   the scenario text as it was read (application/yaml)
///   Attachment world.svg       the world that ran, as `world_to_svg` writes it (image/svg+xml)
/// Replay parses the scenario, takes the world from world.svg (so a generated maze or a
/// --world override comes back exactly) and compiles them into a World; it never steps it.
/// Its own module above the MCAP transport and the scenario importer, so that the transport
/// (and a replay that is handed its world) links no parser.

#include <string>

#include "bridges/mcap/mcap_bridge.h"
#include "bridges/mcap/mcap_player.h"
#include "bridges/mcap/mcap_reader.h"
#include "import/scenario/scenario.h"
#include "world/world.h"

namespace rescuesim {

/// Names rescuesim uses inside a recording.
inline constexpr const char* kRunMetadataName = "rescuesim";
inline constexpr const char* kScenarioAttachmentName = "scenario.yaml";
inline constexpr const char* kWorldAttachmentName = "world.svg";

/// Adds the run's description (metadata and attachments, see the file comment) to `options`
/// and sets its library string and lossless mode (lossless unless the scenario runs in realtime).
void describe_run(McapOptions& options, const Scenario& scenario, const WorldSpec& world, bool cameras, const std::string& version);

/// A run rebuilt from its recording.
struct RecordedRun {
  Scenario scenario;   ///< as recorded (seed, step and duration from the metadata)
  WorldSpec spec;      ///< from world.svg
  World world;         ///< compiled, with the scenario's robots
  mcap::KeyValues info;  ///< the "rescuesim" metadata entries
};

/// Rebuilds the run described in `reader`'s recording. Throws Error naming the file when the
/// description is missing (not recorded by rescuesim) or does not parse.
RecordedRun rebuild_run(const mcap::McapReader& reader, const ModelMap& models);

/// McapPlayer's rebuild step for a rescuesim recording: rebuild_run into `run` (which must
/// outlive the player's construction), handing its world to the player (`run.world` is left
/// empty: the player's world() is that world).
RebuildWorld rebuild_into(RecordedRun& run, const ModelMap& models);

}  // namespace rescuesim
