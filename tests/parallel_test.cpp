// The encoder's parallel_for (encoder/parallel.h): nested loops share the idle cores.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <set>
#include <thread>

#include "encoder/parallel.h"

namespace dcurve {
namespace {

// Jobs running at once, and the most seen.
struct Occupancy {
  std::atomic<int> now{0}, most{0};
  void enter() {
    const int n = ++now;
    int seen = most.load();
    while (n > seen && !most.compare_exchange_weak(seen, n)) {
    }
  }
  void leave() { --now; }
};

void busy_for(std::chrono::milliseconds d) {
  const auto end = std::chrono::steady_clock::now() + d;
  while (std::chrono::steady_clock::now() < end) {
  }
}

// Loops inside loops, each asking for every thread, never run more jobs than cores, and
// hand every core back.
TEST(ParallelFor, NestedLoopsStayWithinTheCores) {
  const int cores = int(thread_count(0));
  const int idle_before = idle_cores().load();
  Occupancy inner;
  std::atomic<int> done{0};
  parallel_for(4, 0, [&](size_t) {
    parallel_for(4, 0, [&](size_t) {
      inner.enter();
      busy_for(std::chrono::milliseconds(2));
      inner.leave();
      ++done;
    });
  });
  EXPECT_EQ(done.load(), 16);
  EXPECT_LE(inner.most.load(), cores);
  EXPECT_EQ(idle_cores().load(), idle_before);
}

// A job that outlasts its sibling gets the sibling's core for its own inner loop.
TEST(ParallelFor, AnOutlastingJobTakesTheFreedCore) {
  if (thread_count(0) < 2) GTEST_SKIP() << "one core";
  std::mutex m;
  std::set<std::thread::id> inner_threads;
  parallel_for(2, 2, [&](size_t i) {
    if (i == 0) return;  // ends at once, on whichever thread took it
    while (idle_cores().load() < 1) std::this_thread::yield();
    parallel_for(16, 2, [&](size_t) {
      busy_for(std::chrono::milliseconds(10));
      std::lock_guard<std::mutex> lock(m);
      inner_threads.insert(std::this_thread::get_id());
    });
  });
  EXPECT_EQ(inner_threads.size(), 2u);
}

// One thread asked for: no helper, whatever is idle.
TEST(ParallelFor, OneThreadRunsOnTheCaller) {
  std::set<std::thread::id> seen;
  parallel_for(8, 1, [&](size_t) { seen.insert(std::this_thread::get_id()); });
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(*seen.begin(), std::this_thread::get_id());
}

}  // namespace
}  // namespace dcurve
