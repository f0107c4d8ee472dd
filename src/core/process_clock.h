#pragma once
/// How long this process has been running, by the kernel's clock: from the exec that started it,
/// so it includes loading the shared libraries and everything before main().

namespace rescuesim {

/// Seconds since the kernel started this process (its start time in /proc/self/stat against
/// CLOCK_BOOTTIME; resolution one clock tick, 10 ms on Linux). Negative when /proc is unreadable.
double seconds_since_process_start();

}  // namespace rescuesim
