#include "filum/haptics/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace filum::haptics {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

extern "C" void onInterrupt(int) { g_interrupted.store(true); }

}  // namespace

void installInterruptHandler() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    return true;
  }();
  (void)installed;
}

bool interruptRequested() { return g_interrupted.load(); }

void clearInterrupt() { g_interrupted.store(false); }

}  // namespace filum::haptics
