#include "core/thread.h"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include <cstring>

namespace rescuesim {

void name_this_thread(const char* name) {
  char cut[16];
  std::strncpy(cut, name, sizeof cut - 1);
  cut[sizeof cut - 1] = '\0';
  pthread_setname_np(pthread_self(), cut);
}

namespace detail {

void before_thread_start() { (void)spdlog::default_logger_raw(); }

}  // namespace detail

}  // namespace rescuesim
