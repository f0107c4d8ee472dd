#pragma once
// rescuesim bench --soak: the default scenario run for hours of sim time (lockstep) with its
// cameras and every bridge this build has attached to local subscribers, sampling memory and
// speed every sim minute and checking every message for NaN. Finds leaks (a memory curve that
// climbs), slowdowns (a falling real-time factor) and numerical trouble that short tests miss.

#include <filesystem>
#include <nlohmann/json.hpp>

namespace rescuesim::bench {

/// Settings of a soak run.
struct SoakOptions {
  double hours = 10;                          ///< sim time to run (h)
  std::filesystem::path out = "runs/soak";    ///< folder for soak.csv, soak.json, soak.png
  bool cameras = true;                        ///< render the cameras (off when there is no OpenGL)
  double sample_seconds = 60;                 ///< sim time between samples (s)
  /// The MCAP recording is restarted into a fresh temporary file every this much sim time (s),
  /// so hours of camera images (about 13 MB per sim second) never fill the disk.
  double record_segment_seconds = 60;
};

/// Runs the soak (see the file comment), writes soak.csv (one row per sample: sim time, wall
/// time, real-time factor of the interval, resident and peak memory, heap in use, messages,
/// NaNs, bytes recorded), soak.json (the returned summary) and soak.png (memory and real-time factor
/// against sim time) into `out`, and returns the summary: which bridges were attached and to
/// what, the memory curve (first, last, max, least-squares slope per sim hour), the real-time
/// factor curve (first, last, min, mean) and the NaN count with the first NaN's topic and field.
/// SIGINT or SIGTERM ends the run early; the files are still written (stop_reason says so).
nlohmann::ordered_json bench_soak(const SoakOptions& options);

}  // namespace rescuesim::bench
