#pragma once
// Test support: what the project logs (spdlog's default logger) while a LogCapture lives.

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <cstddef>
#include <memory>
#include <string>

namespace rescuesim::testing {

/// Collects the last `lines` lines logged while it lives (the pattern "%v": the message only).
class LogCapture {
 public:
  explicit LogCapture(std::size_t lines = 200)
      : sink_(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(lines)), previous_(spdlog::default_logger()) {
    auto logger = std::make_shared<spdlog::logger>("capture", sink_);
    logger->set_pattern("%v");
    spdlog::set_default_logger(logger);
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;
  std::string text() const {
    std::string s;
    for (const auto& line : sink_->last_formatted()) s += line;
    return s;
  }

 private:
  std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> sink_;
  std::shared_ptr<spdlog::logger> previous_;
};

}  // namespace rescuesim::testing
