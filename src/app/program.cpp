#include "app/program.h"

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "app/data_dir.h"
#include "core/error.h"
#include "core/log.h"
#include "core/parallel.h"

namespace rescuesim::app {

int run_program(CLI::App& app, int argc, char** argv, const std::string& log_level, const int& threads, const Action& action,
                const char* program) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  log::set_level(log_level);
  if (threads > 0) set_worker_threads(threads);
  try {
    // a RESCUESIM_DATA_DIR that is not a data folder is a mistake worth stopping for at once
    if (const char* d = std::getenv("RESCUESIM_DATA_DIR"); d && *d) data_dir();
    return action ? action() : kExitOk;
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: failed: %s\n", program, e.what());
    return kExitFailure;
  }
}

}  // namespace rescuesim::app
