// Reset by snapshot beside reset by rebuild, on the default scenario without cameras.

#include "bench/bench_reset.h"

#include <chrono>
#include <memory>

#include "session/session.h"

namespace rescuesim::bench {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

nlohmann::ordered_json bench_reset(const Scenario& scenario, const ModelMap& models) {
  SessionOptions so;
  so.cameras = false;
  constexpr int kRebuilds = 5, kRestores = 20;
  // the baseline: a new Session (world, Bullet, Embree, controllers) per episode
  const auto t_build = Clock::now();
  for (int i = 0; i < kRebuilds; ++i) Session fresh(scenario, models, so);
  const double build_s = since(t_build) / kRebuilds;
  // ours: run an episode's first second (not timed), then go back to the start
  Session session(scenario, models, so);
  const SessionSnapshot start = session.snapshot();
  double restore_s = 0, snapshot_s = 0;
  for (int i = 0; i < kRestores; ++i) {
    session.step_until(SimTime::from_seconds(1));
    const auto t_snap = Clock::now();
    const SessionSnapshot mid = session.snapshot();
    snapshot_s += since(t_snap);
    const auto t0 = Clock::now();
    session.restore(start);
    restore_s += since(t0);
  }
  restore_s /= kRestores;
  snapshot_s /= kRestores;
  nlohmann::ordered_json j;
  j["value"] = restore_s > 0 ? 1.0 / restore_s : 0.0;
  j["unit"] = "resets/s";
  j["baseline"] = build_s > 0 ? 1.0 / build_s : 0.0;
  j["baseline_is"] = "building the Session anew (world, Bullet, Embree, controllers), no cameras";
  j["ratio"] = restore_s > 0 ? build_s / restore_s : 0.0;
  j["target_ratio"] = 10;
  j["meets_target"] = restore_s > 0 && build_s / restore_s >= 10;
  j["restore_ms"] = restore_s * 1e3;
  j["rebuild_ms"] = build_s * 1e3;
  j["snapshot_ms"] = snapshot_s * 1e3;
  j["note"] = "restore = Session::restore of the snapshot taken at construction, after 1 s of sim; snapshot_ms = what "
              "Session::snapshot costs the live run (state copy and the physics engine's canonicalisation)";
  return j;
}

}  // namespace rescuesim::bench
