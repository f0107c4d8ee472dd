#pragma once
/// Work across the machine's cores: one task pool (TBB's, which Embree already uses) for the
/// whole process, and the one limit on its threads. Callers give each task its own output, so
/// what they compute never depends on how many threads ran it or in which order: that is how
/// the simulation keeps "same seed, same messages, at any thread count". In a ThreadSanitizer
/// build (`make test-tsan`) the pool is plain std::threads handing work over through a mutex,
/// which TSan sees and uninstrumented TBB would hide; the contract below is the same.

#include <cstddef>
#include <functional>

namespace rescuesim {

/// Limits the worker threads of the whole process (the pool behind parallel_for, and Embree's
/// ray casting and scene builds) to `n`; 0 lifts the limit (all cores).
void set_worker_threads(int n);

/// The limit set by set_worker_threads (0 = all cores).
int worker_threads();

/// Calls `task(i)` once for every i in [0, n), on the pool's threads and the caller's, and
/// returns when all have returned. Tasks must not share mutable data. The caller's thread waits
/// in isolation: while it waits it runs only tasks of this call, never a task its own caller
/// had queued. With one thread (or n < 2) it is a plain loop in index order. An exception a
/// task throws is rethrown here.
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task);

}  // namespace rescuesim
