#pragma once
/// Internal to world/maze: geometric limits shared by the generator (which rejects options that
/// cannot fit) and the world builder (which lays the features out).

namespace rescuesim::maze_limits {

/// Smallest platform side left between ramps (m).
inline constexpr double kMinPlatform = 0.10;
/// A victim lies 0.05 m from a wall and is 0.4 m wide: the cell interior must hold both (m).
inline constexpr double kMinVictimInterior = 0.50;

}  // namespace rescuesim::maze_limits
