// Session::snapshot and restore with everything attached: the default scenario with its
// explorer and rendered cameras. Frames in flight at the snapshot are rendered again after a
// restore and the frames in flight at the restore are dropped, so the replay — images, clouds,
// victims found — is bitwise the first run.

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "session/session.h"

namespace rescuesim {
namespace {

/// Every message published while stepping to `until`: (topic name, digest), in order.
std::vector<std::pair<std::string, std::uint64_t>> record(Session& session, SimTime until) {
  std::vector<std::pair<std::string, std::uint64_t>> out;
  bool live = false;  // not the latched messages subscribe replays
  const auto handle = session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    if (live) out.emplace_back(t.name, msg::digest(m));
  });
  live = true;
  session.step_until(until);
  session.sim().bus().unsubscribe(handle);
  return out;
}

TEST(SessionSnapshot, RestoreReplaysTheDefaultScenarioWithCamerasBitwise) {
  const ModelMap models = builtin_models();
  std::unique_ptr<Session> session;
  try {
    session = std::make_unique<Session>(default_scenario(models), models);
  } catch (const Error& e) {
    GTEST_SKIP() << "no headless OpenGL here: " << e.what();
  }
  ASSERT_FALSE(session->render_device().empty());
  // 1.05 s: cameras sampled at 1.0 s are still in flight (delivered one period later)
  session->step_until(SimTime::from_ms(1050));
  const SessionSnapshot snap = session->snapshot();
  const auto first = record(*session, SimTime::from_seconds(2.5));
  const std::uint64_t hash = state_hash(session->sim().state());
  std::map<std::string, int> count;
  for (const auto& [topic, d] : first) ++count[topic];
  // 10 Hz cameras delivered one period late: the frames of 1.0 s (in flight at the snapshot) to 2.4 s
  EXPECT_EQ(count["/camera/color/image_raw"], 15);
  EXPECT_EQ(count["/thermal/image_raw"], 15);
  // the explorer drove meanwhile
  EXPECT_GT(session->sim().state().robots[0].distance, snap.state.robots[0].distance + 0.1);

  // restore mid-frame: what is in flight now is dropped, the snapshot's frames come again
  session->step_until(SimTime::from_ms(2550));
  session->restore(snap);
  const auto again = record(*session, SimTime::from_seconds(2.5));
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(again[i], first[i]) << "message " << i << " on " << first[i].first;
  EXPECT_EQ(state_hash(session->sim().state()), hash);
}

}  // namespace
}  // namespace rescuesim
