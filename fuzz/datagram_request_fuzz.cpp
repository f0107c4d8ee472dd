/// libFuzzer target for the readers of datagram bytes from outside: every input is the text of
/// a std_msgs/String on /<robot>/rescue/comms/send going through parse_send_request, and the
/// bytes of a delivered datagram going through the built-in team's readers (read_team_datagram,
/// read_seen_datagram, read_map_datagram: any node may send a built-in robot anything).
/// rescuesim::Error is the only failure parse_send_request may report, and the team readers
/// none. Whatever reads must write back to bytes that read the same.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "mission/datagram_json.h"
#include "team/team_datagrams.h"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "datagram: %s\n", what);
  std::abort();
}

void check_team_readers(const std::vector<std::uint8_t>& bytes) {
  using namespace rescuesim;
  if (const auto p = read_team_datagram(bytes)) {
    if (!p->at.allFinite() || (p->going && !p->going->allFinite())) fail("a team position that is not finite");
    if (p->victims.size() > kMaxTeamVictims) fail("more team victims than kMaxTeamVictims");
    for (const Vec2& v : p->victims) {
      if (!v.allFinite()) fail("a team victim that is not finite");
    }
    const auto again = read_team_datagram(team_datagram(*p));
    if (!again || again->at != p->at || again->going.has_value() != p->going.has_value() || (p->going && *again->going != *p->going) ||
        again->victims != p->victims) {
      fail("a team position written back reads as another");
    }
  }
  if (const auto s = read_seen_datagram(bytes)) {
    if (!(s->cell > 0 && s->cell < 100)) fail("a seen datagram with a cell out of (0, 100)");
    for (const auto& [i, j] : s->squares) {
      if (std::abs(i) > kMaxSeenSide || std::abs(j) > kMaxSeenSide) fail("a seen square beyond kMaxSeenSide");
    }
    if (!s->squares.empty()) {
      const auto again = read_seen_datagram(seen_datagram(*s));
      if (!again || again->cell != s->cell || again->squares != s->squares) fail("seen squares written back read as others");
    }
  }
  if (const auto m = read_map_datagram(bytes)) {
    if (!(m->cell > 0 && m->cell < 100)) fail("a map datagram with a cell out of (0, 100)");
    if (m->width < 1 || m->height < 1 || static_cast<long>(m->width) * m->height > kMaxMapSquares) fail("a map box empty or too large");
    if (static_cast<long>(m->states.size()) != static_cast<long>(m->width) * m->height) fail("map states that do not fill the box");
    for (std::uint8_t v : m->states) {
      if (v > MapSquares::occupied) fail("a map square that is no state");
    }
    const auto again = read_map_datagram(map_datagram(*m));
    if (!again || again->cell != m->cell || again->origin != m->origin || again->width != m->width || again->height != m->height ||
        again->states != m->states) {
      fail("map squares written back read as others");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  check_team_readers(std::vector<std::uint8_t>(data, data + size));
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  SendRequest r;
  try {
    r = parse_send_request(text);
  } catch (const Error&) {
    return 0;
  }
  const SendRequest again = parse_send_request(send_request_json(r));
  if (again.to != r.to || again.bytes != r.bytes) fail("a request written back reads as another request");
  // the inbox side of the same bytes must always be valid JSON
  InboxEntry e;
  e.from = r.to;
  e.to = r.to;
  e.bytes = &r.bytes;
  (void)inbox_json(e);
  // and what a request carries is what a built-in robot's inbox would be handed
  check_team_readers(r.bytes);
  return 0;
}
