/// libFuzzer target for the control interfaces' CDR decoders (bridges/common/control_cdr.h): the
/// request bodies a ROS 2 client sends to rescuesim's Simulation Interfaces, SimulateSteps and
/// parameter services, and the responses and action topics our own test client and bench read.
/// See control_cdr_cases.h for the input layout (first byte: the case) and the checks.

#include "control_cdr_cases.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& cases = rescuesim::fuzz::control_cases();
  cases[data[0] % cases.size()].run(std::span<const std::uint8_t>(data + 1, size - 1));
  return 0;
}
