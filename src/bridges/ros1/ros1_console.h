#pragma once
/// roscpp's own log lines (rosconsole: "Failed to contact master", md5 mismatches on
/// connections, ...) go through rescuesim's log instead of rosconsole's printer, so they share
/// its format and honour --log-level. Lines are prefixed "roscpp: ".

namespace rescuesim {

/// Initialises rosconsole (if it is not yet) and takes over its printing. Idempotent.
void route_rosconsole_to_log();

}  // namespace rescuesim
