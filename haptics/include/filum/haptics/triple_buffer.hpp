// TripleBuffer<T>: the latest value from one writer thread to one reader thread, without locks
// and without either ever waiting.
//
// Three slots: the writer owns one (back), the reader one (front), the third is the middle,
// exchanged through one atomic byte holding its slot index and a "fresh" bit. write() fills the
// back slot and swaps it with the middle (marking it fresh); read() swaps the middle with the
// front if it is fresh. The writer's exchange is a release, the reader's an acquire, so the
// reader sees every byte the writer wrote into the slot it receives; no slot is ever used by both
// threads at once. The reader always gets the newest complete value (older ones are dropped:
// the servo loop wants the latest local model, not a queue of them). T is copied by assignment:
// keep it trivially copyable and small (no allocation in the servo tick).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace filum::haptics {

template <typename T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  explicit TripleBuffer(const T& initial) { slots_.fill(initial); }

  /// Writer thread: publishes `value` as the newest.
  void write(const T& value) {
    slots_[back_] = value;
    const std::uint8_t old = middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = old & kIndex;
  }

  /// Reader thread: whether a value newer than the last read arrived; if so it is in latest().
  bool read() {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint8_t old = middle_.exchange(static_cast<std::uint8_t>(front_), std::memory_order_acq_rel);
    front_ = old & kIndex;
    return true;
  }

  /// Reader thread: the value read last (the initial value before any write).
  const T& latest() const { return slots_[front_]; }

 private:
  static constexpr std::uint8_t kIndex = 0x3;
  static constexpr std::uint8_t kFresh = 0x4;
  std::array<T, 3> slots_{};
  std::uint8_t back_ = 0;                // writer's slot
  std::atomic<std::uint8_t> middle_{1};  // exchanged slot and the fresh bit
  std::uint8_t front_ = 2;               // reader's slot
};

}  // namespace filum::haptics
