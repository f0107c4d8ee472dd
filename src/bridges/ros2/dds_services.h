#pragma once
/// ROS 2 services on a DdsParticipant, byte for byte as rmw_cyclonedds_cpp serves and calls them
/// (dds_service_wire.h has the wire): a ServiceServer reads requests on rq/<name>Request and
/// answers on rr/<name>Reply; a ServiceClient is the other side, for tests and `rescuesim bench`.
/// Both move bytes only: bodies are standalone CDR messages (encapsulation header included) that
/// the codecs above encode and decode; this layer knows no service type. A body that crossed the
/// network may end in up to 3 zero bytes more than were sent (samples travel in multiples of 4
/// bytes; dds_service_wire.h), which the codecs accept.
///
/// Threads: a server is polled by one thread (the ROS 2 bridge's receive thread), which takes
/// requests and runs the handler. The handler may answer at once or later from any thread (the
/// simulation thread) through its ReplyHandle: the reply is queued, the polling thread woken, and
/// the reply sent from there, after the client's reply reader has matched (found by the clientid
/// in its USER_DATA, as rmw_cyclonedds waits for it), or at once when the client announces no
/// clientid, or after at most 100 ms whatever the match. Nothing a handler or a reply does waits
/// on the network.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_service_wire.h"
#include "core/throttle.h"

namespace rescuesim::ros2 {

namespace detail {
struct ReplyQueue;
}

/// Where one request's reply goes. Copyable; send() works once, from any thread, also after the
/// server is gone (then it does nothing and returns false). A request whose handle is dropped
/// unanswered gets no reply (the client times out).
class ReplyHandle {
 public:
  ReplyHandle() = default;
  /// Queues `body` (the response: a CDR message with its encapsulation header) for the client.
  /// False, with `why`, when this request was answered already, the body is not a CDR message,
  /// or the server has stopped.
  bool send(std::span<const std::uint8_t> body, std::string* why = nullptr) const;
  /// The request's header (the client's guid and sequence number).
  const RequestHeader& header() const { return header_; }
  /// True for a handle a server made.
  bool valid() const { return queue_ != nullptr; }

 private:
  friend class ServiceServer;
  std::shared_ptr<detail::ReplyQueue> queue_;
  std::shared_ptr<std::atomic<bool>> answered_;
  RequestHeader header_;
  std::uint64_t client_writer_ = 0;  ///< the request writer's publication handle
};

/// Handles one request: `header` is its client's guid and sequence number, `body` the request as
/// a CDR message (valid during the call only), `reply` answers it, now or later.
using ServiceHandler = std::function<void(const RequestHeader& header, std::span<const std::uint8_t> body, ReplyHandle reply)>;

/// One service: a request reader and a reply writer with `serviceid=<id>;` in their USER_DATA,
/// QoS rmw_qos_profile_services_default. See the file comment for threads.
class ServiceServer {
 public:
  /// Throws Error when the endpoints cannot be made (see DdsParticipant).
  ServiceServer(DdsParticipant& dds, ServiceTopics topics, ServiceHandler handler);
  ~ServiceServer();
  ServiceServer(const ServiceServer&) = delete;
  ServiceServer& operator=(const ServiceServer&) = delete;

  /// Takes the requests that arrived, runs the handler on each, and sends the replies that are
  /// ready. On the polling thread only.
  void poll(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());
  /// When poll() must run again for a queued reply still waiting for its client's reader to
  /// match (nullopt: nothing waits).
  std::optional<std::chrono::steady_clock::time_point> next_poll() const;

  const ServiceTopics& topics() const { return topics_; }
  /// The id in the endpoints' USER_DATA ("serviceid=<id>;").
  const std::string& service_id() const { return id_; }
  Guid request_reader_guid() const;
  Guid reply_writer_guid() const;

  /// Requests handed to the handler.
  std::uint64_t requests() const { return requests_.load(); }
  /// Requests dropped unanswered because their bytes were malformed (shorter than the
  /// encapsulation and request headers, not XCDR1).
  std::uint64_t malformed() const { return malformed_.load(); }
  /// Replies written.
  std::uint64_t replies() const { return replies_.load(); }
  /// Replies not written: the client's request writer was gone, or DDS refused the write.
  std::uint64_t replies_lost() const { return replies_lost_.load(); }

  /// Longest a reply waits for its client's reply reader to match (rmw_cyclonedds: 100 ms).
  static constexpr std::chrono::milliseconds kMatchWait{100};

 private:
  void handle(std::span<const std::uint8_t> sample, std::uint64_t writer);
  void flush(std::chrono::steady_clock::time_point now);
  /// Whether the client behind request writer `writer` can hear a reply now (its reply reader
  /// matched, or it announces no clientid); nullopt when that writer is gone.
  std::optional<bool> client_ready(std::uint64_t writer);

  DdsParticipant& dds_;
  ServiceTopics topics_;
  ServiceHandler handler_;
  std::string id_;
  int request_reader_ = -1, reply_writer_ = -1;
  std::shared_ptr<detail::ReplyQueue> queue_;
  std::map<std::uint64_t, std::string> client_of_writer_;  ///< request writer -> its clientid ("" for none)
  std::set<std::string> matched_clients_;                  ///< clientids whose reply reader matched
  std::atomic<std::uint64_t> requests_{0}, malformed_{0}, replies_{0}, replies_lost_{0};
  Throttle warning_;
};

/// The calling side of a service, as rmw_cyclonedds's client: a request writer and a reply reader
/// with `clientid=<id>;` in their USER_DATA; requests carry the writer's instance handle as guid
/// and a sequence number counting from 1; replies for other clients are ignored. For one thread
/// at a time (tests, the bench).
class ServiceClient {
 public:
  ServiceClient(DdsParticipant& dds, ServiceTopics topics);

  /// True when a server's request reader and reply writer are both matched.
  bool server_ready() const;
  /// Waits up to `timeout` for server_ready().
  bool wait_for_server(std::chrono::milliseconds timeout) const;

  /// Sends a request (`body`: a CDR message with its encapsulation header); returns its sequence
  /// number, or nullopt with `why` when it could not be written.
  std::optional<std::int64_t> send(std::span<const std::uint8_t> body, std::string* why = nullptr);
  /// Waits up to `timeout` for the reply to request `seq`; its body (a CDR message), or nullopt
  /// with `why` on timeout.
  std::optional<std::vector<std::uint8_t>> wait_reply(std::int64_t seq, std::chrono::milliseconds timeout,
                                                      std::string* why = nullptr);
  /// send() then wait_reply().
  std::optional<std::vector<std::uint8_t>> call(std::span<const std::uint8_t> body, std::chrono::milliseconds timeout,
                                                std::string* why = nullptr);

  const ServiceTopics& topics() const { return topics_; }
  const std::string& client_id() const { return id_; }
  /// The guid this client's requests carry.
  std::uint64_t guid() const { return guid_; }
  Guid request_writer_guid() const;
  Guid reply_reader_guid() const;

 private:
  void take_replies();

  DdsParticipant& dds_;
  ServiceTopics topics_;
  std::string id_;
  int request_writer_ = -1, reply_reader_ = -1;
  std::uint64_t guid_ = 0;
  std::int64_t next_seq_ = 1;
  std::map<std::int64_t, std::vector<std::uint8_t>> replies_;  ///< arrived, not yet collected (bounded)
};

}  // namespace rescuesim::ros2
