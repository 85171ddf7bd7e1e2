#include "common/app/run_driver.h"

#include <atomic>
#include <csignal>

namespace cosim::app {

namespace {
std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted = true; }
}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupted() { return g_interrupted; }

}  // namespace cosim::app
