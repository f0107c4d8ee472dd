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

}  // namespace rescuesim
