// Deterministic parallel loop for the encoder's independent trials.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace dcurve {

// Calls job(i) for every i in [0, n) on up to `threads` threads (0: all hardware
// threads). Each job must write only its own result slot, so the outcome never depends on
// the thread count or the order the jobs ran in.
template <class Job>
void parallel_for(size_t n, int threads, const Job& job) {
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t i = next++; i < n; i = next++) job(i);
  };
  size_t count = threads > 0 ? size_t(threads) : size_t(std::max(1u, std::thread::hardware_concurrency()));
  count = std::min(count, std::max<size_t>(n, 1));
  std::vector<std::thread> pool;
  for (size_t k = 1; k < count; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace dcurve
