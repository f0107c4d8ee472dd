#pragma once
/// One CDR encoding of a large message for every bridge that sends CDR. ROS 2, Foxglove and the
/// MCAP recorder all put a message on the wire as the same XCDR1 bytes (msgs/serialize.h's
/// to_cdr); for an image that is a megabyte encoded up to three times. shared_cdr() encodes a
/// message the first time a bridge asks and hands the same bytes to the others for as long as
/// the message itself lives (the Bus's shared message, held by the bridges' queues).
///
/// Only messages of kSharedCdrMinBytes and more are kept (images, maps, point clouds): a small
/// message costs less to encode again than to look up. Thread-safe: bridges call it from their
/// own threads.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "bus/bus.h"

namespace rescuesim {

/// Bytes shared by every bridge sending one message.
using SharedBytes = std::shared_ptr<const std::vector<std::uint8_t>>;

/// Messages whose Outbox::approx_bytes reach this are encoded once and shared.
inline constexpr std::size_t kSharedCdrMinBytes = 64 * 1024;

/// True when `message` is large enough for shared_cdr to keep its bytes (a bridge that
/// encodes small messages into a buffer of its own asks this first).
bool cdr_is_shared(const msg::Message& message);

/// The XCDR1 bytes of `message`: for a large one the bytes another bridge already encoded, or
/// encoded now and kept while `message` lives; for a small one encoded now, not kept.
SharedBytes shared_cdr(const Bus::SharedMessage& message);

/// Large messages whose bytes are kept now (for tests).
std::size_t shared_cdr_entries();

}  // namespace rescuesim
