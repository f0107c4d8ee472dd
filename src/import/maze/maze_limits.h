#pragma once
/// Internal to import/maze: geometric limits shared by the generator (which rejects options that
/// cannot fit) and the world builder (which lays the features out).

namespace rescuesim::maze_limits {

/// Smallest platform side left between ramps (m).
inline constexpr double kMinPlatform = 0.10;
/// A victim lies 0.05 m from a wall and is 0.4 m wide: the cell interior must hold both (m).
inline constexpr double kMinVictimInterior = 0.50;
/// A terrain element in a cell keeps this far from each wall face (m) ...
inline constexpr double kTerrainClearance = 0.05;
/// ... and needs at least this much cell interior (m): three stepfield posts.
inline constexpr double kMinTerrainInterior = 0.40;

}  // namespace rescuesim::maze_limits
