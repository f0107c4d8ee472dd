#pragma once
/// The services and actions a ROS 2 node offers on one DdsParticipant: the ROS 2 bridge owns one,
/// lets register_control_services() (control_services.h) fill it at start, and polls it on its
/// receive thread; every endpoint it makes is listed in the node's ros_discovery_info, so
/// `ros2 service list` / `ros2 action list` / `ros2 node info` attribute them to the node.
///
///   void register_control_services(ros2::ServiceRegistry& services, BridgeHost& host, const Ros2Options& options) {
///     services.add_service("/reset_simulation", "simulation_interfaces/srv/ResetSimulation",
///                          [&host](const ros2::RequestHeader&, std::span<const std::uint8_t> body, ros2::ReplyHandle reply) {
///                            auto request = decode_reset(body);              // the codec validates
///                            host.control()->post([request, reply](control::SimControl& c) {
///                              reply.send(encode_reset_response(c.reset(request.scope)));  // on the simulation thread
///                            });
///                          });
///   }
///
/// Threads: add_*() from any thread (the bridge's start() normally; endpoints added later are
/// announced through set_on_change()); poll() and poll_within() from the polling thread only.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "bridges/ros2/dds_actions.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_services.h"

namespace rescuesim::ros2 {

class ServiceRegistry {
 public:
  /// Services on `dds`; `now_ns` is the clock of action goal stamps (ns; the bridge gives sim
  /// time; unset: the system clock).
  explicit ServiceRegistry(DdsParticipant& dds, std::function<std::int64_t()> now_ns = {});
  ~ServiceRegistry();
  ServiceRegistry(const ServiceRegistry&) = delete;
  ServiceRegistry& operator=(const ServiceRegistry&) = delete;

  /// A server for service `ros_name` ("/reset_simulation", or relative to the root namespace) of
  /// type `srv_type` ("simulation_interfaces/srv/ResetSimulation"). Throws Error for a bad name
  /// or type, or a name already served here.
  ServiceServer& add_service(const std::string& ros_name, const std::string& srv_type, ServiceHandler handler);
  /// As above, for topics and types given in full (types without a srv/ package path).
  ServiceServer& add_service(ServiceTopics topics, ServiceHandler handler);
  /// A server for action `ros_name` of type `action_type` ("simulation_interfaces/action/SimulateSteps").
  /// `options.now_ns` defaults to the registry's clock. Throws Error as add_service does.
  ActionServer& add_action(const std::string& ros_name, const std::string& action_type, ActionCallbacks callbacks,
                           ActionOptions options = {});

  /// Serves what arrived and sends what is ready, on every service and action.
  void poll();
  /// How long the polling thread may wait for new data before poll() is due anyway: `longest`,
  /// or less while a reply waits for its client or a result expires.
  std::chrono::milliseconds poll_within(std::chrono::milliseconds longest) const;
  /// Waits on the participant (DdsParticipant::wait) for up to poll_within(max_wait), then polls:
  /// a loop of these serves a registry that no bridge runs (tests, tools).
  void spin_once(std::chrono::milliseconds max_wait);

  /// Every reader and writer of every service and action, for ros_discovery_info.
  std::vector<Guid> reader_guids() const;
  std::vector<Guid> writer_guids() const;
  /// Malformed requests dropped, over all services and actions.
  std::uint64_t malformed() const;
  /// Services and actions registered (an action counts once).
  std::size_t size() const;
  /// Called after every add_*() (on the caller's thread), so the owner can announce the new
  /// endpoints; set it after the first announcement.
  void set_on_change(std::function<void()> f);

  DdsParticipant& participant() { return dds_; }

 private:
  void check_new(const std::string& name) const;
  void changed();

  DdsParticipant& dds_;
  std::function<std::int64_t()> now_ns_;
  mutable std::mutex mutex_;  ///< guards the lists (entries are never removed)
  std::vector<std::unique_ptr<ServiceServer>> services_;
  std::vector<std::unique_ptr<ActionServer>> actions_;
  std::function<void()> on_change_;
};

}  // namespace rescuesim::ros2
