// The golden state hash (Box2D's test_determinism): the default scenario driven by a fixed
// command pattern for 1000 steps in lockstep with the scenario's seed must end in exactly this
// state, with one ray thread and with all of them. A deliberate change of behaviour (reordered
// random draws, a new State field, a physics setting) changes the hash: check the change is
// meant, then regenerate the constants — run
//   build/bin/sim_tests --gtest_filter='GoldenHash.*'
// and paste the table it prints over kGolden below.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "sim/drive_pattern.h"

namespace rescuesim {
namespace {

/// state_part_hashes of the default scenario after 1000 steps, then the whole state_hash.
const std::vector<std::pair<std::string, std::uint64_t>> kGolden = {
    {"time", 0x7cb5b6be393dace5ull},
    {"step", 0xad6323825fa766dcull},
    {"dynamics", 0x24b3145653d76249ull},
    {"dynamics[0]", 0xdecc5340a88c492dull},
    {"dynamics[1]", 0x85a5381393878180ull},
    {"dynamics[2]", 0x9cc90357151040c0ull},
    {"dynamics[3]", 0x174c8c9511893f80ull},
    {"dynamics[4]", 0x3bd3630b27c1656full},
    {"dynamics[5]", 0x78032ac94e43baafull},
    {"dynamics[6]", 0xaafcd3be90734099ull},
    {"dynamics[7]", 0x8e732c15e71a6fbdull},
    {"dynamics[8]", 0x5530e78bb190bff5ull},
    {"dynamics[9]", 0x3d7b6f2df97461b3ull},
    {"dynamics[10]", 0xbedf4d04a0f3614aull},
    {"dynamics[11]", 0x5f6d0558e6460b78ull},
    {"robots", 0x89cd31291d2aefa4ull},
    {"robots[0].base", 0x8c5f22414c0d438eull},
    {"robots[0].links", 0x1c76c31eb13ba4aeull},
    {"robots[0].joints", 0xf63b851feda37395ull},
    {"robots[0].commands", 0x3caf7ae9cdcffa72ull},
    {"robots[0].odometry", 0x13ee1d52da555281ull},
    {"robots[0].contacts", 0x881cbbe0f62ea582ull},
    {"victims", 0x2cdcdc0dfc5d1141ull},
    {"victims[0]", 0xe26a2a692e4c4f7dull},
    {"victims[1]", 0xe26a2a692e4c4f7dull},
    {"victims[2]", 0xe26a2a692e4c4f7dull},
    {"victims[3]", 0xe26a2a692e4c4f7dull},
    {"sensors", 0x5b84d4d48e81828ull},
    {"sensors[0]", 0x9372bfdaee8e9c07ull},
    {"sensors[1]", 0xa5dfd488b19bd328ull},
    {"sensors[2]", 0xbe0bc85bd8dd11ull},
    {"sensors[3]", 0x6801e15c1c320a51ull},
    {"sensors[4]", 0xef08b8c888f0afa2ull},
    {"sensors[5]", 0x93626c755aed899full},
    {"sensors[6]", 0x55cf3e554f5b57e6ull},
    {"sensors[7]", 0xd314a478fb30c793ull},
    {"sensors[8]", 0xe22c6a7798d23758ull},
    {"sensors[9]", 0xe903441e6051fc5cull},
    {"sensors[10]", 0x8d27efe015b74dd1ull},
    {"sensors[11]", 0xc8b439f0542fbd94ull},
    {"sensors[12]", 0x32c509fa5e2bd98cull},
    {"schedule", 0x1ccc27888be14b6cull},
    {"trouble", 0x88201fb960ff6465ull},
    {"total", 0x8341828d666adbcbull},
};

/// Runs the scenario, compares with kGolden, and says which parts changed.
void check_golden() {
  auto sim = testing::default_sim();
  testing::drive(*sim, SimTime::from_seconds(1000 * sim->dt()));
  ASSERT_EQ(sim->state().step, 1000);
  std::vector<std::pair<std::string, std::uint64_t>> now = state_part_hashes(sim->state());
  now.emplace_back("total", state_hash(sim->state()));
  if (now == kGolden) return;
  std::ostringstream changed, table;
  for (const auto& [name, h] : now) {
    bool same = false;
    for (const auto& [gname, gh] : kGolden) same = same || (gname == name && gh == h);
    if (!same) changed << " " << name;
    table << "    {\"" << name << "\", 0x" << std::hex << h << std::dec << "ull},\n";
  }
  ADD_FAILURE() << "the default scenario's state after 1000 steps changed in:" << changed.str()
                << "\nIf the change is meant, paste this over kGolden in tests/sim/golden_hash_test.cpp:\n"
                << table.str();
}

TEST(GoldenHash, DefaultScenarioAfter1000StepsOnOneRayThread) {
  set_worker_threads(1);
  check_golden();
  set_worker_threads(0);
}

TEST(GoldenHash, DefaultScenarioAfter1000StepsOnAllRayThreads) {
  set_worker_threads(0);
  check_golden();
}

}  // namespace
}  // namespace rescuesim
