/// libFuzzer target for the datagram request reader: every input is the text of a
/// std_msgs/String on /<robot>/rescue/comms/send going through parse_send_request.
/// rescuesim::Error is the only failure it may report; a request that parses must write back
/// with send_request_json to a request that parses to the same destination and bytes.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.h"
#include "mission/datagram_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  SendRequest r;
  try {
    r = parse_send_request(text);
  } catch (const Error&) {
    return 0;
  }
  const SendRequest again = parse_send_request(send_request_json(r));
  if (again.to != r.to || again.bytes != r.bytes) {
    std::fprintf(stderr, "datagram request: written back it reads as another request\n");
    std::abort();
  }
  // the inbox side of the same bytes must always be valid JSON
  InboxEntry e;
  e.from = r.to;
  e.to = r.to;
  e.bytes = &r.bytes;
  (void)inbox_json(e);
  return 0;
}
