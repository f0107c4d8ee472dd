#pragma once
// Test support: a ServiceRegistry polled on a thread of its own, as the ROS 2 bridge's receive
// thread polls it, for tests that serve services without a bridge.

#include <atomic>
#include <chrono>
#include <thread>

#include "bridges/ros2/service_registry.h"

namespace rescuesim::testing {

/// Polls `registry` until destroyed.
class RegistrySpinner {
 public:
  explicit RegistrySpinner(ros2::ServiceRegistry& registry) : thread_([this, &registry] {
    while (!stop_) registry.spin_once(std::chrono::milliseconds(20));
  }) {}
  ~RegistrySpinner() {
    stop_ = true;
    thread_.join();
  }
  RegistrySpinner(const RegistrySpinner&) = delete;
  RegistrySpinner& operator=(const RegistrySpinner&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rescuesim::testing
