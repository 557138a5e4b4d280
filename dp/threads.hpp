// ThreadScope: the number of OpenMP threads as an option rather than a process-wide setting.
// Every entry point of the engine that opens parallel regions (building an engine, a sweep, a
// section solve, a journey, a library's side-by-side builds, a frontier) holds one for the
// threads its options ask for: it sets the calling thread's OpenMP thread count for the scope
// and restores the previous count at its end, so two callers with different options do not
// disturb each other. threads <= 0 leaves OpenMP's default (all cores, or OMP_NUM_THREADS).
// Counts above kMaxThreads are bounded to it: libgomp allocates per-thread state up front, and
// a billion threads once aborted the program asking for 224 GB (options refuse such counts).
#pragma once

#include <algorithm>

#include <omp.h>

namespace ecorail::dp {

inline constexpr int kMaxThreads = 1024;

class ThreadScope {
 public:
  explicit ThreadScope(int threads) : previous_(omp_get_max_threads()), set_(threads > 0) {
    if (set_) omp_set_num_threads(std::min(threads, kMaxThreads));
  }
  ~ThreadScope() {
    if (set_) omp_set_num_threads(previous_);
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int previous_;
  bool set_;
};

}  // namespace ecorail::dp
