#include "vector_env_core.h"

#include <exception>
#include <functional>
#include <thread>

#include "core/error.h"

namespace rescuesim::python {

VecEnvCore::VecEnvCore(const Scenario& scenario, const ModelMap& models, const EnvOptions& options, int count, int threads)
    : threads_(std::max(1, threads)) {
  if (count < 1) throw Error("rescuesim.VectorEnv: needs at least one environment");
  for (int i = 0; i < count; ++i) envs_.push_back(std::make_unique<EnvCore>(scenario, models, options));
  // one block per field; environment i writes row i
  const auto& fields = envs_.front()->fields();
  blocks_.resize(fields.size());
  for (std::size_t k = 0; k < fields.size(); ++k) blocks_[k].assign(fields[k].bytes() * static_cast<std::size_t>(count), 0);
  for (int i = 0; i < count; ++i) {
    std::vector<std::uint8_t*> rows;
    for (std::size_t k = 0; k < fields.size(); ++k) rows.push_back(blocks_[k].data() + fields[k].bytes() * static_cast<std::size_t>(i));
    envs_[static_cast<std::size_t>(i)]->bind(rows);
  }
  seeds_.assign(static_cast<std::size_t>(count), 0);
  ended_.assign(static_cast<std::size_t>(count), 0);
}

void VecEnvCore::for_each(const std::function<void(int)>& f) {
  const int n = size();
  const int t = std::min(threads_, n);
  if (t <= 1) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  // contiguous chunks, one per thread; the first error is passed on after all have finished
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(t));
  std::vector<std::thread> pool;
  for (int j = 0; j < t; ++j) {
    pool.emplace_back([&, j] {
      try {
        for (int i = n * j / t; i < n * (j + 1) / t; ++i) f(i);
      } catch (...) {
        errors[static_cast<std::size_t>(j)] = std::current_exception();
      }
    });
  }
  for (auto& th : pool) th.join();
  for (auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

void VecEnvCore::reset(const std::vector<std::uint64_t>& seeds) {
  if (static_cast<int>(seeds.size()) != size()) {
    throw Error("rescuesim.VectorEnv.reset: expected " + std::to_string(size()) + " seeds, got " + std::to_string(seeds.size()));
  }
  seeds_ = seeds;
  for_each([&](int i) {
    envs_[static_cast<std::size_t>(i)]->reset(seeds_[static_cast<std::size_t>(i)]);
    ended_[static_cast<std::size_t>(i)] = 0;
  });
}

void VecEnvCore::step(const double* actions, double* rewards, bool* terminated, bool* truncated, bool* was_reset) {
  for_each([&](int i) {
    const auto u = static_cast<std::size_t>(i);
    EnvCore& e = *envs_[u];
    if (ended_[u]) {
      seeds_[u] += static_cast<std::uint64_t>(size());
      e.reset(seeds_[u]);
      ended_[u] = 0;
      rewards[u] = 0;
      terminated[u] = truncated[u] = false;
      was_reset[u] = true;
      return;
    }
    const StepOutcome o = e.step(actions[2 * u], actions[2 * u + 1]);
    rewards[u] = o.reward;
    terminated[u] = o.terminated;
    truncated[u] = o.truncated;
    was_reset[u] = false;
    ended_[u] = o.terminated || o.truncated;
  });
}

}  // namespace rescuesim::python
