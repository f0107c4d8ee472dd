#pragma once
/// A 64-bit digest of a message's every field (FNV-1a over the values), for determinism
/// checks: equal digests mean equal messages, bit for bit.

#include <cstdint>

#include "msgs/messages.h"

namespace rescuesim::msg {

std::uint64_t digest(const Message& m);

}  // namespace rescuesim::msg
