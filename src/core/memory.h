#pragma once
/// The process's own memory: what it holds and giving back what it freed.

namespace rescuesim {

/// Hands pages the allocator keeps after free() back to the system (glibc's malloc_trim over
/// every arena; a no-op elsewhere). glibc gives each thread that allocates an arena of its own
/// (up to 8 per core) and arenas rarely shrink by themselves: a run whose threads come and go
/// (a recorder restarted per file, bridges' senders) otherwise keeps a high-water mark of
/// resident memory that it no longer uses. Costs about a millisecond; long runs call it about
/// once per sim minute (Session::run). Returns true when memory was given back.
bool return_free_memory();

/// Fixes glibc's thresholds for a long-running process, once at start-up (the CLI's main):
/// blocks of 256 KiB and more (camera images, recorder chunks) are mapped apart and go back
/// to the system when freed, and an arena gives back free memory above 4 MiB at its top.
/// Without it glibc raises both thresholds as it sees large blocks freed (up to 32 and 64 MiB),
/// after which images come from the per-thread arenas and stay resident there: a 10-hour soak
/// showed resident memory 150 MB over what was in use, with malloc_trim every sim minute. A
/// no-op elsewhere than glibc.
void tune_allocator_for_long_runs();

}  // namespace rescuesim
