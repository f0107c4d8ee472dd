#pragma once
/// The engine behind `rescuesim.VectorEnv`: K independent environments (each its own
/// simulation) stepped together, optionally on several threads. Each observation field is one
/// contiguous [K, ...] block that the environments write their rows of, so Python sees every
/// environment's observations as one numpy array without copying. An environment whose
/// episode ended is reset by the next step() (Gymnasium's "next step" autoreset) with seed
/// previous seed + K, so the K seed sequences never overlap.

#include <cstdint>
#include <memory>
#include <vector>

#include "env_core.h"

namespace rescuesim::python {

class VecEnvCore {
 public:
  /// `count` environments of one scenario; `threads` (>= 1) steps them in parallel.
  VecEnvCore(const Scenario& scenario, const ModelMap& models, const EnvOptions& options, int count, int threads);

  int size() const { return static_cast<int>(envs_.size()); }
  EnvCore& env(int i) { return *envs_[static_cast<std::size_t>(i)]; }
  /// The fields of one environment (the blocks are [size(), field.shape...]).
  const std::vector<ObsField>& fields() const { return envs_.front()->fields(); }
  std::uint8_t* block(std::size_t k) { return blocks_[k].data(); }

  /// Resets environment i with seeds[i].
  void reset(const std::vector<std::uint64_t>& seeds);
  /// One step of every environment: `actions` holds size() × 2 numbers (linear m/s, angular
  /// rad/s); writes size() rewards and flags. An environment that ended on the previous step
  /// is reset instead (reward 0, flags false, `was_reset` set).
  void step(const double* actions, double* rewards, bool* terminated, bool* truncated, bool* was_reset);

 private:
  void for_each(const std::function<void(int)>& f);

  std::vector<std::unique_ptr<EnvCore>> envs_;
  std::vector<std::vector<std::uint8_t>> blocks_;
  std::vector<std::uint64_t> seeds_;
  std::vector<std::uint8_t> ended_;
  int threads_ = 1;
};

}  // namespace rescuesim::python
