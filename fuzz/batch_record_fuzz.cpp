/// libFuzzer target for the batch results reader: every input is one line of results.jsonl
/// (written by an earlier run, read again to resume or merge) going through parse_trial_line.
/// rescuesim::Error is the only failure it may report; a line that parses must write back with
/// to_json_line to a line that parses to the same outcome.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "batch/batch_record.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rescuesim;
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  TrialRecord record;
  try {
    record = parse_trial_line(line);
  } catch (const Error&) {
    return 0;
  }
  const std::string again = to_json_line(record);
  if (!same_outcome(record, parse_trial_line(again))) {
    std::fprintf(stderr, "batch record: written back as %s it reads as another outcome\n", again.c_str());
    std::abort();
  }
  return 0;
}
