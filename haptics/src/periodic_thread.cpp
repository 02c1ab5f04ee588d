#include "filum/haptics/periodic_thread.hpp"

#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace filum::haptics {

namespace {

constexpr double kMaxRate = 1e5;    // Hz: a 10 µs period is below the sleep granularity of Linux
constexpr int kServoPriority = 80;  // SCHED_FIFO: above interrupts' threads (50), below watchdogs (99)

}  // namespace

void PeriodicThread::start(ServoTick tick, double rate) {
  if (!(rate > 0.0) || rate > kMaxRate)
    throw std::invalid_argument("a servo rate in (0, 1e5] Hz, found " + std::to_string(rate));
  if (running()) throw std::logic_error("PeriodicThread::start: already running");
  stop_.store(false);
  missed_.store(0);
  note_.clear();
  thread_ = std::thread(&PeriodicThread::run, this, std::move(tick), 1.0 / rate);
  sched_param param{};
  param.sched_priority = kServoPriority;
  if (const int error = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &param); error != 0)
    note_ = std::string("real-time scheduling (SCHED_FIFO) refused: ") + std::strerror(error) +
            "; the servo loop runs at normal priority and its period may jitter under load (grant it with "
            "`ulimit -r 99` for the user, an rtprio line in /etc/security/limits.conf, or run as root)";
}

void PeriodicThread::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void PeriodicThread::run(ServoTick tick, double period) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto step = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period));
  auto due = start;
  while (!stop_.load(std::memory_order_relaxed)) {
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    if (!tick(t)) break;
    due += step;
    const auto now = Clock::now();
    if (now > due) {  // late: skip the ticks whose time has passed, keep the grid
      const auto behind = (now - due) / step;
      missed_.fetch_add(static_cast<long>(behind) + 1, std::memory_order_relaxed);
      due += (behind + 1) * step;
    }
    std::this_thread::sleep_until(due);
  }
}

}  // namespace filum::haptics
