// The encoder's one way to spread independent jobs over threads. Jobs write only their own
// outputs, so results never depend on the thread count or on scheduling.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
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

// The first exception any worker threw; the others stop taking jobs once there is one.
class FirstException {
 public:
  void record(std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!first_) first_ = e;
    failed_ = true;
  }
  bool failed() const { return failed_; }
  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr first_;
  std::atomic<bool> failed_{false};
};

// Calls job(i) once for every i in [0, count), on up to `threads` threads (0: all hardware
// threads; the calling thread is one of them). Returns when every job has finished. An
// exception from a job (std::bad_alloc included) ends the loop and is rethrown here, on the
// calling thread, once every thread has stopped: it never escapes a thread into
// std::terminate.
template <class Job>
void parallel_for(size_t count, int threads, Job job) {
  std::atomic<size_t> next{0};
  FirstException thrown;
  auto worker = [&]() {
    try {
      for (size_t i = next++; i < count && !thrown.failed(); i = next++) job(i);
    } catch (...) {
      thrown.record(std::current_exception());
    }
  };
  const size_t n = std::min(thread_count(threads), std::max<size_t>(count, 1));
  std::vector<std::thread> pool;
  try {
    for (size_t k = 1; k < n; ++k) pool.emplace_back(worker);
  } catch (...) {  // a thread that cannot start (std::system_error) fails the loop like a job
    thrown.record(std::current_exception());
  }
  worker();
  for (std::thread& t : pool) t.join();
  thrown.rethrow();
}

}  // namespace dcurve
