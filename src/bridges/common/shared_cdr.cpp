#include "bridges/common/shared_cdr.h"

#include <algorithm>
#include <mutex>

#include "bridges/common/outbox.h"
#include "msgs/serialize.h"

namespace rescuesim {

namespace {

struct Entry {
  std::weak_ptr<const msg::Message> message;  // its bytes are kept while it lives
  SharedBytes bytes;
};

// few at a time (the large messages the bridges' queues hold), so a vector searched in order
std::mutex g_mutex;
std::vector<Entry> g_entries;

bool same(const std::weak_ptr<const msg::Message>& w, const Bus::SharedMessage& m) { return !w.owner_before(m) && !m.owner_before(w); }

SharedBytes encode(const msg::Message& m) {
  auto bytes = std::make_shared<std::vector<std::uint8_t>>();
  msg::to_cdr(m, *bytes);
  return bytes;
}

}  // namespace

bool cdr_is_shared(const msg::Message& message) { return Outbox::approx_bytes(message) >= kSharedCdrMinBytes; }

SharedBytes shared_cdr(const Bus::SharedMessage& message) {
  if (!cdr_is_shared(*message)) return encode(*message);
  {
    std::lock_guard lock(g_mutex);
    std::erase_if(g_entries, [](const Entry& e) { return e.message.expired(); });
    for (const Entry& e : g_entries) {
      if (same(e.message, message)) return e.bytes;
    }
  }
  // encoded outside the lock; two bridges asking at once may both encode, and the first kept wins
  SharedBytes bytes = encode(*message);
  std::lock_guard lock(g_mutex);
  for (const Entry& e : g_entries) {
    if (same(e.message, message)) return e.bytes;
  }
  g_entries.push_back({message, bytes});
  return bytes;
}

std::size_t shared_cdr_entries() {
  std::lock_guard lock(g_mutex);
  std::erase_if(g_entries, [](const Entry& e) { return e.message.expired(); });
  return g_entries.size();
}

}  // namespace rescuesim
