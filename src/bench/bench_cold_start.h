#pragma once
// `rescuesim bench --cold-start`: the time from exec to the first laser scan of the default
// scenario, beside the exec of the same binary (the `rescuesim` CLI, not rescuesim-bench) that only
// prints its version.

#include <nlohmann/json.hpp>

namespace rescuesim::bench {

/// Runs `rescuesim run` (the CLI beside this program) `runs` times with cameras and `runs` times without, each
/// for 0.5 sim s, and reads the cold start each prints; the baseline is `rescuesim --version`
/// from exec to exit, the same number of times. Medians, in seconds.
nlohmann::ordered_json bench_cold_start(int runs = 5);

}  // namespace rescuesim::bench
