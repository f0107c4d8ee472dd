#include "bridges/ros2/dds_services.h"

#include <algorithm>
#include <exception>
#include <thread>

#include "core/error.h"
#include "core/log.h"

namespace rescuesim::ros2 {

namespace detail {

/// Replies on their way from any thread to the polling thread.
struct ReplyQueue {
  struct Item {
    RequestHeader header;
    std::uint64_t client_writer = 0;
    std::vector<std::uint8_t> sample;  ///< the whole reply sample (header and body)
    std::chrono::steady_clock::time_point queued;
  };

  std::mutex mutex;
  std::deque<Item> items;
  DdsParticipant* dds = nullptr;  ///< to wake the polling thread; null once the server is gone

  bool push(Item item) {
    std::lock_guard lock(mutex);
    if (dds == nullptr) return false;
    items.push_back(std::move(item));
    dds->wake();
    return true;
  }
};

}  // namespace detail

bool ReplyHandle::send(std::span<const std::uint8_t> body, std::string* why) const {
  const auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!queue_) return fail("not a request's reply handle");
  detail::ReplyQueue::Item item;
  try {
    item.sample = join_service_sample(header_, body);
  } catch (const Error& e) {
    return fail(e.message());
  }
  if (answered_->exchange(true)) return fail("this request was answered already");
  item.header = header_;
  item.client_writer = client_writer_;
  item.queued = std::chrono::steady_clock::now();
  if (!queue_->push(std::move(item))) return fail("the service has stopped");
  return true;
}

ServiceServer::ServiceServer(DdsParticipant& dds, ServiceTopics topics, ServiceHandler handler)
    : dds_(dds), topics_(std::move(topics)), handler_(std::move(handler)), queue_(std::make_shared<detail::ReplyQueue>()) {
  id_ = client_service_id(dds_.participant_guid(), dds_.next_client_service_counter());
  const std::string user_data = service_user_data(id_);
  request_reader_ = dds_.create_raw_reader(topics_.request_topic, topics_.request_type, service_qos(), user_data);
  reply_writer_ = dds_.create_raw_writer(topics_.reply_topic, topics_.reply_type, service_qos(), user_data);
  queue_->dds = &dds_;
}

ServiceServer::~ServiceServer() {
  // replies that come later find the server gone
  std::lock_guard lock(queue_->mutex);
  queue_->dds = nullptr;
  queue_->items.clear();
}

Guid ServiceServer::request_reader_guid() const { return dds_.reader_guid(request_reader_); }
Guid ServiceServer::reply_writer_guid() const { return dds_.writer_guid(reply_writer_); }

void ServiceServer::poll(std::chrono::steady_clock::time_point now) {
  dds_.take_with_info(request_reader_, [&](std::span<const std::uint8_t> sample, const DdsParticipant::SampleInfo& info) {
    handle(sample, info.publication_handle);
  });
  flush(now);
}

void ServiceServer::handle(std::span<const std::uint8_t> sample, std::uint64_t writer) {
  std::string why;
  std::optional<ServiceSample> request = split_service_sample(sample, &why);
  if (!request) {
    // dropped and counted: a malformed request gets no reply
    ++malformed_;
    std::uint64_t held = 0;
    if (warning_.allow(&held)) {
      log::warn("ROS 2 bridge: service {}: dropped a malformed request: {} ({} more problems held back)", topics_.name, why, held);
    }
    return;
  }
  ++requests_;
  ReplyHandle reply;
  reply.queue_ = queue_;
  reply.answered_ = std::make_shared<std::atomic<bool>>(false);
  reply.header_ = request->header;
  reply.client_writer_ = writer;
  try {
    handler_(request->header, request->body, std::move(reply));
  } catch (const std::exception& e) {
    log::warn("ROS 2 bridge: service {}: the handler failed: {}", topics_.name, e.what());
  }
}

std::optional<bool> ServiceServer::client_ready(std::uint64_t writer) {
  // the caches only grow with the number of clients; a long run with many come-and-go clients
  // starts them afresh now and then
  if (client_of_writer_.size() > 4096) client_of_writer_.clear();
  if (matched_clients_.size() > 4096) matched_clients_.clear();
  auto it = client_of_writer_.find(writer);
  if (it == client_of_writer_.end()) {
    const std::optional<std::string> user_data = dds_.matched_writer_user_data(request_reader_, writer);
    if (!user_data) return std::nullopt;  // the request writer is gone, and its client with it
    it = client_of_writer_.emplace(writer, user_data_value(*user_data, "clientid").value_or("")).first;
  }
  const std::string& client = it->second;
  // a client that announces no clientid cannot be paired with its reader: assume all is well
  if (client.empty() || matched_clients_.contains(client)) return true;
  for (const std::string& user_data : dds_.matched_reader_user_data(reply_writer_)) {
    if (user_data_value(user_data, "clientid") == client) {
      matched_clients_.insert(client);
      return true;
    }
  }
  return false;
}

void ServiceServer::flush(std::chrono::steady_clock::time_point now) {
  std::deque<detail::ReplyQueue::Item> items;
  {
    std::lock_guard lock(queue_->mutex);
    items.swap(queue_->items);
  }
  std::deque<detail::ReplyQueue::Item> waiting;
  for (detail::ReplyQueue::Item& item : items) {
    const std::optional<bool> ready = client_ready(item.client_writer);
    if (!ready) {
      ++replies_lost_;
      continue;
    }
    // rmw_cyclonedds gives up after 100 ms; a reply sent then still reaches a reader that
    // matched without announcing itself, and costs nothing otherwise
    if (!*ready && now - item.queued < kMatchWait) {
      waiting.push_back(std::move(item));
      continue;
    }
    std::string error;
    if (dds_.write(reply_writer_, item.sample, &error)) {
      ++replies_;
    } else {
      ++replies_lost_;
      std::uint64_t held = 0;
      if (warning_.allow(&held)) {
        log::warn("ROS 2 bridge: service {}: cannot send a reply: {} ({} more problems held back)", topics_.name, error, held);
      }
    }
  }
  if (!waiting.empty()) {
    // back in front of anything queued meanwhile, in their order
    std::lock_guard lock(queue_->mutex);
    queue_->items.insert(queue_->items.begin(), std::make_move_iterator(waiting.begin()), std::make_move_iterator(waiting.end()));
  }
}

std::optional<std::chrono::steady_clock::time_point> ServiceServer::next_poll() const {
  std::lock_guard lock(queue_->mutex);
  if (queue_->items.empty()) return std::nullopt;
  // re-check the match every 10 ms (as rmw_cyclonedds does), and at the latest when the wait ends
  const auto oldest = std::min_element(queue_->items.begin(), queue_->items.end(),
                                       [](const auto& a, const auto& b) { return a.queued < b.queued; });
  return std::min(std::chrono::steady_clock::now() + std::chrono::milliseconds(10), oldest->queued + kMatchWait);
}

ServiceClient::ServiceClient(DdsParticipant& dds, ServiceTopics topics) : dds_(dds), topics_(std::move(topics)) {
  id_ = client_service_id(dds_.participant_guid(), dds_.next_client_service_counter());
  const std::string user_data = client_user_data(id_);
  request_writer_ = dds_.create_raw_writer(topics_.request_topic, topics_.request_type, service_qos(), user_data);
  reply_reader_ = dds_.create_raw_reader(topics_.reply_topic, topics_.reply_type, service_qos(), user_data,
                                         DdsParticipant::Wake::own);
  guid_ = dds_.writer_instance_handle(request_writer_);
}

Guid ServiceClient::request_writer_guid() const { return dds_.writer_guid(request_writer_); }
Guid ServiceClient::reply_reader_guid() const { return dds_.reader_guid(reply_reader_); }

bool ServiceClient::server_ready() const {
  return dds_.matched_readers(request_writer_) > 0 && dds_.matched_writers(reply_reader_) > 0;
}

bool ServiceClient::wait_for_server(std::chrono::milliseconds timeout) const {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (!server_ready()) {
    if (std::chrono::steady_clock::now() >= give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

std::optional<std::int64_t> ServiceClient::send(std::span<const std::uint8_t> body, std::string* why) {
  const std::int64_t seq = next_seq_++;
  std::vector<std::uint8_t> sample;
  try {
    sample = join_service_sample({guid_, seq}, body);
  } catch (const Error& e) {
    if (why) *why = e.message();
    return std::nullopt;
  }
  std::string error;
  if (!dds_.write(request_writer_, sample, &error)) {
    if (why) *why = "service " + topics_.name + ": cannot send the request: " + error;
    return std::nullopt;
  }
  return seq;
}

void ServiceClient::take_replies() {
  dds_.take(reply_reader_, [&](std::span<const std::uint8_t> sample) {
    std::optional<ServiceSample> reply = split_service_sample(sample);
    // every client of the service reads every reply: keep this client's own
    if (!reply || reply->header.guid != guid_) return;
    replies_[reply->header.seq] = std::move(reply->body);
    if (replies_.size() > 256) replies_.erase(replies_.begin());  // replies nobody waits for any more
  });
}

std::optional<std::vector<std::uint8_t>> ServiceClient::wait_reply(std::int64_t seq, std::chrono::milliseconds timeout,
                                                                   std::string* why) {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    take_replies();
    if (const auto it = replies_.find(seq); it != replies_.end()) {
      std::vector<std::uint8_t> body = std::move(it->second);
      replies_.erase(it);
      return body;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(give_up - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    dds_.wait_reader(reply_reader_, left);
  }
  if (why) {
    *why = "service " + topics_.name + ": no reply to request " + std::to_string(seq) + " within " +
           std::to_string(timeout.count()) + " ms" + (server_ready() ? "" : " (no server is matched)");
  }
  return std::nullopt;
}

std::optional<std::vector<std::uint8_t>> ServiceClient::call(std::span<const std::uint8_t> body, std::chrono::milliseconds timeout,
                                                             std::string* why) {
  const std::optional<std::int64_t> seq = send(body, why);
  if (!seq) return std::nullopt;
  return wait_reply(*seq, timeout, why);
}

}  // namespace rescuesim::ros2
