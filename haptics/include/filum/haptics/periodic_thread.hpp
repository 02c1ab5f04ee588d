// PeriodicThread: calls a tick at a fixed rate on a thread of its own, the servo thread of the
// devices that have no scheduler of their own (scripted, simulated, mouse).
//
// Each tick is due at t_k = t_0 + k T on the steady clock; the thread sleeps until the next due
// time (absolute deadlines: a late tick does not shift the later ones, so the mean rate stays
// 1/T), and a tick more than one period late is not repeated (missed() counts them). The thread
// asks for real-time scheduling (SCHED_FIFO, priority 80) where the OS grants it; where it does
// not (no CAP_SYS_NICE, no rtprio limit) it runs at normal priority and schedulingNote() says so
// and how to grant it.
#pragma once

#include <atomic>
#include <string>
#include <thread>

#include "filum/haptics/haptic_device.hpp"

namespace filum::haptics {

class PeriodicThread {
 public:
  PeriodicThread() = default;
  ~PeriodicThread() { stop(); }
  PeriodicThread(const PeriodicThread&) = delete;
  PeriodicThread& operator=(const PeriodicThread&) = delete;

  /// Starts calling tick(t), t the seconds since start, at `rate` Hz (> 0, at most 100 kHz).
  /// Throws std::invalid_argument on a bad rate, std::logic_error when already running.
  void start(ServoTick tick, double rate);
  /// Asks the thread to end after its current tick and joins it. Idempotent.
  void stop();
  bool running() const { return thread_.joinable(); }
  /// Ticks skipped because the previous one ended after their due time.
  long missed() const { return missed_.load(std::memory_order_relaxed); }
  const std::string& schedulingNote() const { return note_; }

 private:
  void run(ServoTick tick, double period);
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<long> missed_{0};
  std::string note_;
};

}  // namespace filum::haptics
