#include "uavmot/core/shutdown.hpp"

#include <atomic>
#include <csignal>

namespace uavmot {
namespace {
std::atomic<bool> g_shutdown{false};
extern "C" void on_signal(int) { g_shutdown.store(true); }
}  // namespace

void install_shutdown_handler() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool shutdown_requested() { return g_shutdown.load(); }
void request_shutdown() { g_shutdown.store(true); }

}  // namespace uavmot
