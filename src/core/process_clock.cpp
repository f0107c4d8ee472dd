#include "core/process_clock.h"

#include <time.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace rescuesim {

double seconds_since_process_start() {
  std::ifstream in("/proc/self/stat");
  std::string line;
  if (!std::getline(in, line)) return -1;
  // field 2 (the command name, in parentheses) may hold spaces: count fields after its ')'
  const std::size_t close = line.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(line.substr(close + 1));
  std::string field;
  // fields 3 .. 21, then 22: starttime in clock ticks since boot
  for (int k = 3; k <= 21; ++k) rest >> field;
  unsigned long long start_ticks = 0;
  if (!(rest >> start_ticks)) return -1;
  timespec now{};
  if (::clock_gettime(CLOCK_BOOTTIME, &now) != 0) return -1;
  const double ticks_per_s = static_cast<double>(::sysconf(_SC_CLK_TCK));
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec) - static_cast<double>(start_ticks) / ticks_per_s;
}

}  // namespace rescuesim
