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
/// blocks of 4 MiB and more are mapped apart and go back to the system when freed, and an arena
/// gives back free memory above 4 MiB at its top.
/// - Without it glibc raises both thresholds as it sees large blocks freed (up to 32 and 64
///   MiB), after which a 10-hour soak showed resident memory 150 MB over what was in use, with
///   malloc_trim every sim minute.
/// - A threshold of 256 KiB (stop 22 to 29) mapped every camera image and every copy the
///   transports make of one (roscpp's and Cyclone's send buffers) afresh: a mmap, 225 page
///   faults and a munmap with its TLB shootdown per 640 x 480 image and copy. The page faults
///   were 11 % of the simulation process's CPU with ROS 1 and ROS 2 sending images.
/// - At 4 MiB, a 640 x 480 image (0.9 MB) and a depth image (1.2 MB) are reused from the
///   arenas. A one-hour soak with every bridge held 160-165 MB resident after the first minute,
///   the same as at 256 KiB over its first 15 minutes; the ROS bridges' cost fell from 0.81 to 0.89
///   (docs/performance.md).
/// A no-op elsewhere than glibc.
void tune_allocator_for_long_runs();

}  // namespace rescuesim
