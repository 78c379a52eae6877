// The encoder's one way to spread independent jobs over threads. Jobs write only their own
// outputs, so results never depend on the thread count or on scheduling.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace dcurve {

// How many threads `threads` means: itself when > 0, else every hardware thread (>= 1).
inline size_t thread_count(int threads) {
  return threads > 0 ? size_t(threads) : size_t(std::max(1u, std::thread::hardware_concurrency()));
}

// Threads each of `jobs` side-by-side jobs may use when they share `threads` (as above): an
// equal share, at least one.
inline int threads_per_job(int threads, size_t jobs) {
  return int(std::max<size_t>(1, thread_count(threads) / std::max<size_t>(jobs, 1)));
}

// Calls job(i) once for every i in [0, count), on up to `threads` threads (0: all hardware
// threads; the calling thread is one of them). Returns when every job has finished.
template <class Job>
void parallel_for(size_t count, int threads, Job job) {
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t i = next++; i < count; i = next++) job(i);
  };
  const size_t n = std::min(thread_count(threads), std::max<size_t>(count, 1));
  std::vector<std::thread> pool;
  for (size_t k = 1; k < n; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace dcurve
