// Services between two participants in this process, pinned to loopback: a ServiceServer
// polled by a thread of its own (as the bridge's receive thread polls it) answers a
// ServiceClient, later and from another thread (as the simulation thread does); its endpoints
// carry serviceid= in USER_DATA; a malformed request is counted and gets no reply.

#include "bridges/ros2/dds_services.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <thread>

#include "bridges/ros2/service_registry.h"
#include "core/error.h"
#include "bridges/ros2/dds_loopback.h"
#include "bridges/ros2/registry_spinner.h"
#include "support/dds_domain.h"

namespace rescuesim::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

class DdsServicesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
  }
  int domain() const { return testing::leased_dds_domain(); }
};


/// Requests handed over from the polling thread to a "simulation thread".
struct Inbox {
  std::mutex mutex;
  std::condition_variable cv;
  std::deque<std::pair<Bytes, ReplyHandle>> items;
  std::vector<RequestHeader> headers;
  bool closed = false;

  void push(const RequestHeader& h, std::span<const std::uint8_t> body, ReplyHandle r) {
    std::lock_guard lock(mutex);
    headers.push_back(h);
    items.push_back({Bytes(body.begin(), body.end()), std::move(r)});
    cv.notify_all();
  }
};

// ResetSimulation request {uint8 scope} and a response {Result {uint8 result; string error_message}}
Bytes reset_request(std::uint8_t scope) { return {0x00, 0x01, 0x00, 0x00, scope}; }
Bytes reset_response(std::uint8_t result) { return {0x00, 0x01, 0x00, 0x00, result, 0, 0, 0, 1, 0, 0, 0, 0}; }

const ServiceTopics& reset_topics() {
  static const ServiceTopics t = service_topics("/reset_simulation", "simulation_interfaces/srv/ResetSimulation");
  return t;
}

TEST_F(DdsServicesTest, ARequestIsAnsweredLaterFromAnotherThread) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  ServiceRegistry registry(server_side);
  Inbox inbox;
  ServiceServer& server = registry.add_service(
      "/reset_simulation", "simulation_interfaces/srv/ResetSimulation",
      [&](const RequestHeader& h, std::span<const std::uint8_t> body, ReplyHandle r) { inbox.push(h, body, std::move(r)); });
  // the "simulation thread": answers each request with result = 10 + its scope
  std::thread simulation([&] {
    std::unique_lock lock(inbox.mutex);
    for (;;) {
      inbox.cv.wait(lock, [&] { return inbox.closed || !inbox.items.empty(); });
      if (inbox.items.empty()) return;
      auto [body, reply] = std::move(inbox.items.front());
      inbox.items.pop_front();
      lock.unlock();
      std::this_thread::sleep_for(5ms);  // "later"
      EXPECT_TRUE(reply.send(reset_response(static_cast<std::uint8_t>(10 + body.at(4)))));
      EXPECT_FALSE(reply.send(reset_response(0))) << "a request is answered once";
      lock.lock();
    }
  });
  testing::RegistrySpinner spinner(registry);

  ServiceClient client(client_side, reset_topics());
  ASSERT_TRUE(client.wait_for_server(10s)) << "the client never matched the server";
  std::string why;
  const auto first = client.call(reset_request(2), 10s, &why);
  ASSERT_TRUE(first) << why;
  EXPECT_EQ(*first, reset_response(12));
  const auto second = client.call(reset_request(4), 10s, &why);
  ASSERT_TRUE(second) << why;
  EXPECT_EQ(*second, reset_response(14));
  {
    std::lock_guard lock(inbox.mutex);
    inbox.closed = true;
    inbox.cv.notify_all();
  }
  simulation.join();

  // the server saw the client's guid and sequence numbers 1 and 2
  ASSERT_EQ(inbox.headers.size(), 2u);
  EXPECT_EQ(inbox.headers[0], (RequestHeader{client.guid(), 1}));
  EXPECT_EQ(inbox.headers[1], (RequestHeader{client.guid(), 2}));
  EXPECT_EQ(server.requests(), 2u);
  // the client may hold a reply before the polling thread has counted it as written
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  while (server.replies() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(1ms);
  EXPECT_EQ(server.replies(), 2u);
  EXPECT_EQ(server.malformed(), 0u);
}

TEST_F(DdsServicesTest, TwoClientsCallingInTurnEachGetTheirOwnReplies) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  ServiceRegistry registry(server_side);
  registry.add_service(reset_topics(), [](const RequestHeader&, auto body, ReplyHandle r) {
    r.send(reset_response(static_cast<std::uint8_t>(10 + body[4])));
  });
  testing::RegistrySpinner spinner(registry);
  // both clients read every reply on rr/reset_simulationReply; each keeps those with its guid
  ServiceClient a(client_side, reset_topics()), b(client_side, reset_topics());
  ASSERT_NE(a.guid(), b.guid());
  ASSERT_TRUE(a.wait_for_server(10s) && b.wait_for_server(10s));
  std::vector<double> ms;
  std::string why;
  for (std::uint8_t i = 0; i < 100; ++i) {
    ServiceClient& c = i % 2 ? b : a;
    const auto t0 = std::chrono::steady_clock::now();
    const auto reply = c.call(reset_request(i), 10s, &why);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    ASSERT_TRUE(reply) << "call " << int(i) << ": " << why;
    ASSERT_EQ(*reply, reset_response(static_cast<std::uint8_t>(10 + i))) << "call " << int(i);
  }
  std::sort(ms.begin(), ms.end());
  std::printf("[ service round trip on loopback: p50 %.3f ms, max %.3f ms over %zu calls ]\n", ms[ms.size() / 2], ms.back(), ms.size());
}

// across processes the bytes go over loopback UDP and arrive through the raw type's from_ser,
// a large one in fragments that Cyclone reassembles
TEST_F(DdsServicesTest, ARoundTripBetweenTwoProcessesAlsoOfALargeBody) {
  const ServiceTopics echo = service_topics("/echo", "rescuesim_test/srv/Echo");
  Bytes large = {0x00, 0x01, 0x00, 0x00};
  for (int i = 0; i < 200'000; ++i) large.push_back(static_cast<std::uint8_t>(i * 7));  // a multiple of 4
  const int d = domain();
  const pid_t child = ::fork();  // before this process has any DDS participant
  ASSERT_GE(child, 0);
  if (child == 0) {
    // the client: exit code 0 when both replies came back as sent
    DdsParticipant dds(d, participant_user_data());
    ServiceClient client(dds, echo);
    if (!client.wait_for_server(20s)) ::_exit(2);
    const auto small = client.call(reset_request(3), 20s);
    // the network carries samples in multiples of 4 bytes: the 1-byte body comes back as 1 + 3 zeros
    if (!small || *small != Bytes({0x00, 0x01, 0x00, 0x00, 3, 0, 0, 0})) ::_exit(3);
    const auto big = client.call(large, 20s);
    if (!big || *big != large) ::_exit(4);
    ::_exit(0);
  }
  DdsParticipant dds(d, participant_user_data());
  ServiceRegistry registry(dds);
  ServiceServer& server = registry.add_service(echo, [](const RequestHeader&, auto body, ReplyHandle r) { r.send(body); });
  testing::RegistrySpinner spinner(registry);
  int status = 0;
  const auto give_up = std::chrono::steady_clock::now() + 60s;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > give_up) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      FAIL() << "the client process did not finish";
    }
    std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "2: no server matched, 3: small reply wrong or missing, 4: large reply wrong or missing";
  EXPECT_EQ(server.requests(), 2u);
  EXPECT_EQ(server.malformed(), 0u);
}

TEST_F(DdsServicesTest, EndpointsCarryServiceAndClientIdsInUserData) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  ServiceServer server(server_side, reset_topics(), [](const RequestHeader&, auto, ReplyHandle) {});
  // the first id on a participant: its GUID prefix and counter 1
  EXPECT_EQ(server.service_id(), client_service_id(server_side.participant_guid(), 1));
  const std::string serviceid = "serviceid=" + server.service_id() + ";";

  // what a client sees of the server's request reader and reply writer
  const int w = client_side.create_raw_writer(reset_topics().request_topic, reset_topics().request_type, service_qos());
  const int r = client_side.create_raw_reader(reset_topics().reply_topic, reset_topics().reply_type, service_qos(), {},
                                              DdsParticipant::Wake::own);
  // and what a server sees of a client's
  ServiceClient client(client_side, reset_topics());
  const int sw = server_side.create_raw_writer(reset_topics().reply_topic, reset_topics().reply_type, service_qos());
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  // (r also meets sw, a reply writer that announces nothing)
  while ((client_side.matched_readers(w) == 0 || client_side.matched_writers(r) < 2 || server_side.matched_readers(sw) < 2) &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(client_side.matched_reader_user_data(w), std::vector<std::string>{serviceid});
  auto writers = client_side.matched_writer_user_data(r);
  std::sort(writers.begin(), writers.end());
  EXPECT_EQ(writers, (std::vector<std::string>{"", serviceid}));
  // the client's reply reader announces its clientid (the raw reader above announces nothing)
  const auto seen = server_side.matched_reader_user_data(sw);
  EXPECT_NE(std::find(seen.begin(), seen.end(), "clientid=" + client.client_id() + ";"), seen.end());
  EXPECT_NE(std::find(seen.begin(), seen.end(), ""), seen.end());
  EXPECT_EQ(client.client_id(), client_service_id(client_side.participant_guid(), 1));
}

TEST_F(DdsServicesTest, AMalformedRequestIsCountedAndGetsNoReply) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  ServiceRegistry registry(server_side);
  std::atomic<int> handled{0};
  ServiceServer& server = registry.add_service(reset_topics(), [&](const RequestHeader&, auto body, ReplyHandle r) {
    ++handled;
    r.send(reset_response(static_cast<std::uint8_t>(body.size())));
  });
  testing::RegistrySpinner spinner(registry);
  // a client by hand, without clientid (so the server does not wait for its reader)
  const int w = client_side.create_raw_writer(reset_topics().request_topic, reset_topics().request_type, service_qos());
  const int r = client_side.create_raw_reader(reset_topics().reply_topic, reset_topics().reply_type, service_qos(), {},
                                              DdsParticipant::Wake::own);
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  while ((client_side.matched_readers(w) == 0 || client_side.matched_writers(r) == 0) && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(10ms);
  }
  std::string error;
  // 10 bytes: an encapsulation header and half a guid; then a well-formed request, seq 9
  ASSERT_TRUE(client_side.write(w, Bytes{0x00, 0x01, 0x00, 0x00, 1, 2, 3, 4, 5, 6}, &error)) << error;
  ASSERT_TRUE(client_side.write(w, join_service_sample({77, 9}, reset_request(1)), &error)) << error;
  std::vector<ServiceSample> replies;
  while (replies.empty() && std::chrono::steady_clock::now() < give_up) {
    client_side.wait_reader(r, 100ms);
    client_side.take(r, [&](std::span<const std::uint8_t> bytes) { replies.push_back(*split_service_sample(bytes)); });
  }
  // a reliable writer delivers in order: the malformed request was seen before the good one
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].header, (RequestHeader{77, 9}));
  EXPECT_EQ(replies[0].body, reset_response(5));
  EXPECT_EQ(handled.load(), 1);
  EXPECT_EQ(server.malformed(), 1u);
  EXPECT_EQ(registry.malformed(), 1u);
  EXPECT_EQ(server.requests(), 1u);
}

TEST_F(DdsServicesTest, ARegistryListsItsEndpointsAndRefusesANameTwice) {
  DdsParticipant dds(domain(), participant_user_data());
  ServiceRegistry registry(dds);
  int changes = 0;
  registry.set_on_change([&] { ++changes; });
  ServiceServer& reset = registry.add_service("/reset_simulation", "simulation_interfaces/srv/ResetSimulation",
                                              [](const RequestHeader&, auto, ReplyHandle) {});
  ActionCallbacks callbacks;
  callbacks.on_goal = [](GoalHandle) {};
  callbacks.unknown_result_response = {0x00, 0x01, 0x00, 0x00, 0x00};
  ActionServer& steps = registry.add_action("/simulate_steps", "simulation_interfaces/action/SimulateSteps", callbacks);
  EXPECT_EQ(changes, 2);
  EXPECT_EQ(registry.size(), 2u);
  // a service: reader and writer; an action: three readers, five writers (three replies, feedback, status)
  const std::vector<Guid> readers = registry.reader_guids(), writers = registry.writer_guids();
  EXPECT_EQ(readers.size(), 4u);
  EXPECT_EQ(writers.size(), 6u);
  EXPECT_EQ(readers[0], reset.request_reader_guid());
  EXPECT_EQ(writers[0], reset.reply_writer_guid());
  EXPECT_EQ(std::vector<Guid>(readers.begin() + 1, readers.end()), steps.reader_guids());
  const auto message = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { registry.add_service("reset_simulation", "std_srvs/srv/Empty", [](const RequestHeader&, auto, ReplyHandle) {}); })
                .find("service /reset_simulation is registered already"),
            std::string::npos);
  EXPECT_NE(message([&] {
              registry.add_service("/simulate_steps/_action/get_result", "std_srvs/srv/Empty",
                                   [](const RequestHeader&, auto, ReplyHandle) {});
            }).find("taken by action /simulate_steps"),
            std::string::npos);
  ActionCallbacks none;
  EXPECT_NE(message([&] { registry.add_action("/other", "pkg/action/A", none); }).find("on_goal is required"), std::string::npos);
  EXPECT_EQ(changes, 2);
}

TEST_F(DdsServicesTest, AReplyAfterTheServerIsGoneGoesNowhere) {
  DdsParticipant dds(domain(), participant_user_data());
  ReplyHandle kept;
  {
    ServiceServer server(dds, reset_topics(), [&](const RequestHeader&, auto, ReplyHandle r) { kept = r; });
    // a request from this participant itself, taken by poll()
    const int w = dds.create_raw_writer(reset_topics().request_topic, reset_topics().request_type, service_qos());
    std::string error;
    const auto give_up = std::chrono::steady_clock::now() + 10s;
    while (dds.matched_readers(w) == 0 && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(dds.write(w, join_service_sample({1, 1}, reset_request(0)), &error)) << error;
    while (!kept.valid() && std::chrono::steady_clock::now() < give_up) {
      dds.wait(50ms);
      server.poll();
    }
    ASSERT_TRUE(kept.valid());
  }
  std::string why;
  EXPECT_FALSE(kept.send(reset_response(1), &why));
  EXPECT_EQ(why, "the service has stopped");
  EXPECT_FALSE(ReplyHandle().send(reset_response(1)));
}

}  // namespace
}  // namespace rescuesim::ros2
