#include "bridges/ros1/ros1_console.h"

#include <ros/console.h>
#include <ros/console_backend.h>

#include <string>

#include "core/log.h"

namespace rescuesim {

namespace {

void print(void*, ros::console::Level level, const char* text, const char*, const char*, int) {
  // rosconsole ends some lines with a newline of its own
  std::string s = text ? text : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  switch (level) {
    case ros::console::levels::Debug: log::debug("roscpp: {}", s); break;
    case ros::console::levels::Info: log::info("roscpp: {}", s); break;
    case ros::console::levels::Warn: log::warn("roscpp: {}", s); break;
    default: log::error("roscpp: {}", s); break;
  }
}

}  // namespace

void route_rosconsole_to_log() {
  // rosconsole installs its own printer when it initialises: initialise first, then replace it
  ros::console::initialize();
  ros::console::backend::function_print = &print;
}

}  // namespace rescuesim
