// The ROS 1 simulation services: first the call logic on its own (a closure posted to a
// SimControl, a bounded wait for its answer), then the real thing: the bridge in this process on
// a roscore of its own, called with `rosservice`, a fake SimControl (fake_sim_control.h) whose
// posted tasks run on this test's simulation thread, which steps a real Simulation.

#include "bridges/ros1/ros1_sim_services.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "bridges/ros1/fake_sim_control.h"
#include "bridges/ros1/ros1_bridge.h"
#include "bridges/ros1/ros1_rig.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using namespace testing;
using std::chrono::milliseconds;

Simulation room() { return Simulation(compile_world(testing::room_spec(), builtin_models())); }

/// The test's simulation thread: ticks the fake until destroyed (about one step per ms).
class SimThread {
 public:
  explicit SimThread(FakeSimControl& control)
      : thread_([this, &control] {
          while (!stop_.load()) {
            control.tick();
            std::this_thread::sleep_for(milliseconds(1));
          }
        }) {}
  ~SimThread() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

const std::atomic<bool> kGoingOn{false};

TEST(Ros1SimServices, TheFourServicesHaveGazebosNamesAndStdSrvsTypes) {
  const std::vector<SimServiceInfo>& s = sim_services();
  ASSERT_EQ(s.size(), 4u);
  EXPECT_STREQ(s[0].name, "/reset_simulation");
  EXPECT_STREQ(s[1].name, "/pause_physics");
  EXPECT_STREQ(s[2].name, "/unpause_physics");
  EXPECT_STREQ(s[3].name, "/step_simulation");
  for (int i = 0; i < 3; ++i) EXPECT_STREQ(s[static_cast<std::size_t>(i)].type, "std_srvs/Empty");
  EXPECT_STREQ(s[3].type, "std_srvs/Trigger");
  // a service's MD5 is that of its request's text and then its response's: none for Empty,
  // "bool success\nstring message" for Trigger (what `rossrv md5` prints)
  EXPECT_STREQ(s[0].md5, "d41d8cd98f00b204e9800998ecf8427e");
  EXPECT_STREQ(s[3].md5, "937c9679a518e3a18d831e57125ea522");
  EXPECT_EQ(sim_seconds(12'005'000'000), "12.005000000");
  EXPECT_EQ(sim_seconds(0), "0.000000000");
}

TEST(Ros1SimServices, WithoutAControlSurfaceEveryCallIsRefusedSayingSo) {
  const SimServiceReply r = call_sim_service(nullptr, SimService::pause, milliseconds(5000), kGoingOn);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, control::kNoControl);
}

TEST(Ros1SimServices, PausePlayStepAndResetRunOnTheSimulationThread) {
  Simulation sim = room();
  FakeSimControl control(sim);
  SimThread thread(control);
  const auto call = [&](SimService s) { return call_sim_service(&control, s, milliseconds(5000), kGoingOn); };

  // stepping is for a paused simulation (the standard's OPERATION_FAILED for the service)
  SimServiceReply r = call(SimService::step);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "steps are taken only while the simulation is paused (OPERATION_FAILED)");

  r = call(SimService::pause);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.message, "paused");
  EXPECT_EQ(control.state(), control::RunState::paused);
  r = call(SimService::pause);  // as gazebo_ros: pausing a paused world succeeds
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.message, "already paused");

  // one step from paused: exactly one dt later, and the answer says so
  const std::int64_t t0 = control.now_ns(), n0 = control.steps();
  r = call(SimService::step);
  EXPECT_TRUE(r.ok) << r.message;
  const std::int64_t dt = SimTime::from_seconds(sim.dt()).ns;
  EXPECT_EQ(control.now_ns(), t0 + dt);
  EXPECT_EQ(control.steps(), n0 + 1);
  EXPECT_EQ(r.message, "stepped 1 step; sim time " + sim_seconds(t0 + dt) + " s");

  // reset: back to the start, at sim time 0
  r = call(SimService::reset);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.message, "reset; sim time 0.000000000 s");
  EXPECT_EQ(control.now_ns(), 0);

  r = call(SimService::unpause);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.message, "playing");
  EXPECT_EQ(control.calls(), (std::vector<std::string>{"start_steps(1, service)", "set_run_state(2)", "set_run_state(2)",
                                                       "start_steps(1, service)", "reset(255)", "set_run_state(1)"}));
}

TEST(Ros1SimServices, NoAnswerWithinTheTimeoutFailsAndTheRequestStaysQueued) {
  Simulation sim = room();
  FakeSimControl control(sim);  // nobody ticks it yet: posted tasks wait
  const SimServiceReply r = call_sim_service(&control, SimService::pause, milliseconds(200), kGoingOn);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "no answer from the simulation within 0.2 s; the request stays queued and takes effect at its next step boundary");
  // the closure outlived the call that gave up, and still does its work
  control.tick();
  EXPECT_EQ(control.state(), control::RunState::paused);
  EXPECT_EQ(control.calls(), std::vector<std::string>{"set_run_state(2)"});
}

TEST(Ros1SimServices, AStoppingBridgeOrAClosedRunEndsTheCall) {
  Simulation sim = room();
  FakeSimControl control(sim);
  const std::atomic<bool> stopping{true};
  SimServiceReply r = call_sim_service(&control, SimService::reset, milliseconds(5000), stopping);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "rescuesim's ROS 1 bridge is stopping");
  control.close();
  r = call_sim_service(&control, SimService::reset, milliseconds(5000), kGoingOn);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "the simulation takes no more requests (the run has ended, or 1024 requests wait already)");
}

/// The bridge in this process on its own roscore.
class Ros1SimServicesOverRos : public ::testing::Test {
 protected:
  void SetUp() override {
    SKIP_WITHOUT_ROS1();
    if (std::system("command -v rosservice >/dev/null 2>&1") != 0) GTEST_SKIP() << "rosservice is not installed (scripts/install-deps.sh)";
    dir_ = temp_dir("ros1-sim-services");
    master_ = std::make_unique<RosMaster>(dir_);
    ASSERT_TRUE(master_->start()) << "roscore did not come up on port " << master_->port();
    for (const auto& [k, v] : master_->env()) ::setenv(k.c_str(), v.c_str(), 1);
  }
  CommandResult rosservice(const std::string& args) { return master_->run("rosservice " + args, kToolSeconds); }

  fs::path dir_;
  std::unique_ptr<RosMaster> master_;
};

TEST_F(Ros1SimServicesOverRos, RosserviceListsCallsAndDrivesTheRun) {
  Simulation sim = room();
  FakeSimControl control(sim);
  sim.set_control(&control);
  Ros1Options options;
  options.node_name = "rescuesim_services";
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  std::unique_ptr<SimThread> thread = std::make_unique<SimThread>(control);
  const auto finish = [&] {
    thread.reset();
    bridge->stop();
  };

  // the four services, of their types, offered by the node
  const CommandResult list = rosservice("list -n");
  for (const char* s : {"/reset_simulation", "/pause_physics", "/unpause_physics", "/step_simulation"}) {
    EXPECT_NE(list.out.find(std::string(s) + " /rescuesim_services\n"), std::string::npos) << s << " missing in\n" << list.out << list.err;
  }
  EXPECT_EQ(rosservice("type /pause_physics").out, "std_srvs/Empty\n");
  EXPECT_EQ(rosservice("type /step_simulation").out, "std_srvs/Trigger\n");

  // pause: the simulation stops where it is (checked over 100 ticks of the simulation thread)
  CommandResult r = rosservice("call /pause_physics");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(control.state(), control::RunState::paused);
  const std::int64_t paused_at = control.now_ns(), steps = control.steps();
  EXPECT_GT(paused_at, 0);
  std::this_thread::sleep_for(milliseconds(300));
  EXPECT_EQ(control.now_ns(), paused_at);
  EXPECT_EQ(control.steps(), steps);

  // a step: one dt, and the new time in the answer
  const std::int64_t dt = SimTime::from_seconds(sim.dt()).ns;
  r = rosservice("call /step_simulation");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "success: True\nmessage: \"stepped 1 step; sim time " + sim_seconds(paused_at + dt) + " s\"\n");
  EXPECT_EQ(control.now_ns(), paused_at + dt);
  EXPECT_EQ(control.steps(), steps + 1);
  // pausing again is no error for gazebo users
  r = rosservice("call /pause_physics");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;

  // reset while paused: back to the start (time 0), still paused
  r = rosservice("call /reset_simulation");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(control.now_ns(), 0);
  EXPECT_EQ(control.state(), control::RunState::paused);

  // play: time runs again; stepping now is refused, with the reason
  r = rosservice("call /unpause_physics");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(wait_until([&] { return control.now_ns() > dt; }, kPatience));
  r = rosservice("call /step_simulation");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "success: False\nmessage: \"steps are taken only while the simulation is paused (OPERATION_FAILED)\"\n");

  EXPECT_EQ(control.calls(), (std::vector<std::string>{"set_run_state(2)", "start_steps(1, service)", "set_run_state(2)", "reset(255)",
                                                       "set_run_state(1)", "start_steps(1, service)"}));
  finish();
}

TEST_F(Ros1SimServicesOverRos, WithoutAControlSurfaceCallsFailWithTheReason) {
  Simulation sim = room();  // no set_control: a run that cannot be controlled
  Ros1Options options;
  options.node_name = "rescuesim_uncontrolled";
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  // an Empty service answers with a service error carrying the reason (Debian's rosservice
  // prints it as Python bytes: b'...')
  const CommandResult pause = rosservice("call /pause_physics");
  EXPECT_NE(pause.exit_code, 0);
  EXPECT_TRUE(std::regex_search(pause.out + pause.err,
                                std::regex(std::string("ERROR: service \\[/pause_physics\\] responded with an error: (b')?") +
                                           std::regex_replace(control::kNoControl, std::regex("[()]"), "\\$&"))))
      << pause.out << pause.err;
  // Trigger says it in its message
  const CommandResult step = rosservice("call /step_simulation");
  EXPECT_EQ(step.exit_code, 0) << step.err;
  EXPECT_EQ(step.out, std::string("success: False\nmessage: \"") + control::kNoControl + "\"\n");
  bridge->stop();
}

TEST_F(Ros1SimServicesOverRos, ASimulationThatDoesNotAnswerFailsTheCallAfterTheTimeout) {
  Simulation sim = room();
  FakeSimControl control(sim);  // never ticked: posted tasks wait forever
  sim.set_control(&control);
  Ros1Options options;
  options.node_name = "rescuesim_stalled";
  options.service_timeout = 1.0;
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  const CommandResult r = rosservice("call /reset_simulation");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE((r.out + r.err).find("ERROR: service [/reset_simulation] responded with an error: "), std::string::npos) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("no answer from the simulation within 1 s"), std::string::npos) << r.out << r.err;
  bridge->stop();
}

}  // namespace
}  // namespace rescuesim
