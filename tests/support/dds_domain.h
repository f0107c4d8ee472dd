#pragma once
// Test support: a DDS domain id no other test on this machine is using.
//
// ctest -j runs DDS tests side by side, and a domain id picked from the process id alone can
// collide: the peer of one test then reads the other test's /scan and /clock (CI saw this). Each
// id here is leased with an exclusive flock on /tmp/rescuesim-test-dds-domain-<id>.lock, held
// until the process exits (the kernel drops the lock when the process dies, so a crashed test
// leaves nothing held). /tmp, not the build tree: two clones testing at once share the network.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace rescuesim::testing {

/// Domains tests may use: 1..232 (0 is the default users run on; DDS's port mapping ends at 232).
inline constexpr int kFirstTestDomain = 1, kLastTestDomain = 232;

/// Takes domain `id` for this process if no other process holds it; the lock is held until this
/// process exits.
inline bool try_lease_dds_domain(int id) {
  const std::string path = "/tmp/rescuesim-test-dds-domain-" + std::to_string(id) + ".lock";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return true;  // the descriptor stays open, and the lock with it
  ::close(fd);
  return false;
}

/// Leases a domain no other process holds and returns it. Throws if every domain is taken.
inline int lease_free_dds_domain() {
  const int span = kLastTestDomain - kFirstTestDomain + 1;
  const int start = static_cast<int>(::getpid() % span);
  for (int k = 0; k < span; ++k) {
    const int id = kFirstTestDomain + (start + k) % span;
    if (try_lease_dds_domain(id)) return id;
  }
  throw std::runtime_error("no free DDS domain for a test in 1..232 (every /tmp/rescuesim-test-dds-domain-*.lock is held)");
}

/// The `index`-th domain this process holds (0, 1, ... in order of first call), leased on first
/// use and held for the life of the process.
inline int leased_dds_domain(int index = 0) {
  static std::vector<int> held;
  while (static_cast<int>(held.size()) <= index) held.push_back(lease_free_dds_domain());
  return held[static_cast<std::size_t>(index)];
}

}  // namespace rescuesim::testing
