// StageBarrier: a light barrier for the stage-by-stage sweep. Each thread announces the end of
// a stage by incrementing one counter and waits until every thread has done so; the counter
// only grows, so there is nothing to reset between stages. Waiting spins briefly and then
// yields the core, so a sweep sharing a busy machine does not burn a time slice per stage
// waiting for a descheduled partner (OpenMP's own barrier did, by orders of magnitude).
#pragma once

#include <sched.h>

#include <atomic>

namespace ecorail::dp {

class StageBarrier {
 public:
  explicit StageBarrier(int threads) : threads_(threads) {}
  // Called by every thread once per stage; stage_index counts from 0.
  void arrive_and_wait(long stage_index) {
    arrived_.fetch_add(1, std::memory_order_acq_rel);
    const long target = static_cast<long>(threads_) * (stage_index + 1);
    int spins = 0;
    while (arrived_.load(std::memory_order_acquire) < target) {
      if (++spins > 64) {
        sched_yield();
        spins = 0;
      }
    }
  }

 private:
  int threads_;
  std::atomic<long> arrived_{0};
};

}  // namespace ecorail::dp
