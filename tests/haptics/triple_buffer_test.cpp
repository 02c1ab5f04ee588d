// TripleBuffer under a stress of concurrent reads and writes (run under ThreadSanitizer by
// scripts/sanitize.sh --tsan): the reader never sees a torn value, and sees the sequence grow.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <thread>

#include "filum/haptics/triple_buffer.hpp"

namespace filum::haptics {
namespace {

/// A value whose fields must agree: any mix of two writes breaks the check.
struct Stamped {
  long sequence = 0;
  std::array<long, 15> copies{};
  bool consistent() const {
    for (long c : copies)
      if (c != sequence) return false;
    return true;
  }
};

TEST(TripleBuffer, SingleThreadedItHandsOverTheNewestValue) {
  TripleBuffer<int> buffer(7);
  EXPECT_FALSE(buffer.read());
  EXPECT_EQ(buffer.latest(), 7);
  buffer.write(1);
  buffer.write(2);
  ASSERT_TRUE(buffer.read());
  EXPECT_EQ(buffer.latest(), 2);  // the older value was dropped
  EXPECT_FALSE(buffer.read());
  EXPECT_EQ(buffer.latest(), 2);
}

TEST(TripleBuffer, ConcurrentReadsNeverSeeATornOrOlderValue) {
  TripleBuffer<Stamped> buffer;
  constexpr long kWrites = 2000000;
  std::atomic<bool> done{false};
  long reads = 0, torn = 0, backwards = 0, last = 0;
  std::thread reader([&] {
    while (!done.load(std::memory_order_acquire)) {
      if (!buffer.read()) continue;
      const Stamped& v = buffer.latest();
      ++reads;
      torn += !v.consistent();
      backwards += v.sequence <= last;
      last = v.sequence;
    }
  });
  Stamped value;
  for (long k = 1; k <= kWrites; ++k) {
    value.sequence = k;
    value.copies.fill(k);
    buffer.write(value);
  }
  done.store(true, std::memory_order_release);
  reader.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_GT(reads, 0);
  // The last value written is the one the reader gets next.
  if (buffer.read()) last = buffer.latest().sequence;
  EXPECT_EQ(last, kWrites);
}

}  // namespace
}  // namespace filum::haptics
