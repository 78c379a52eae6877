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

// Hardware threads of this process not running a parallel_for job: a nested parallel_for
// takes its helpers from them, so a job whose side-by-side siblings have ended gets their
// cores for its own inner loops, without more threads than cores. May dip below zero for a
// moment while a caller takes its core back.
inline std::atomic<int>& idle_cores() {
  static std::atomic<int> idle{int(std::max(1u, std::thread::hardware_concurrency())) - 1};
  return idle;
}

// Takes up to `wanted` idle cores; returns how many it took.
inline size_t take_idle_cores(size_t wanted) {
  int have = idle_cores().load();
  while (wanted > 0 && have > 0) {
    const int take = int(std::min<size_t>(size_t(have), wanted));
    if (idle_cores().compare_exchange_weak(have, have - take)) return size_t(take);
  }
  return 0;
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
// threads; the calling thread is one of them), as many as idle cores allow; a thread hands
// its core back as soon as no job is left for it. Returns when every job has finished. An
// exception from a job (std::bad_alloc included) ends the loop and is rethrown here, on the
// calling thread, once every thread has stopped: it never escapes a thread into
// std::terminate.
template <class Job>
void parallel_for(size_t count, int threads, Job job) {
  std::atomic<size_t> next{0};
  FirstException thrown;
  auto work = [&]() {
    try {
      for (size_t i = next++; i < count && !thrown.failed(); i = next++) job(i);
    } catch (...) {
      thrown.record(std::current_exception());
    }
    ++idle_cores();
  };
  const size_t helpers = take_idle_cores(std::min(thread_count(threads), std::max<size_t>(count, 1)) - 1);
  std::vector<std::thread> pool;
  try {
    for (size_t k = 0; k < helpers; ++k) pool.emplace_back(work);
  } catch (...) {  // a thread that cannot start (std::system_error) fails the loop like a job
    thrown.record(std::current_exception());
  }
  idle_cores() += int(helpers - pool.size());  // the cores of threads that did not start
  work();  // counts the calling thread's core idle once its jobs are done, until the joins
  for (std::thread& t : pool) t.join();
  --idle_cores();
  thrown.rethrow();
}

}  // namespace dcurve
