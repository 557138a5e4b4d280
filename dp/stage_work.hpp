// StageWork: self-scheduling of the stage-by-stage sweep. Each stage's nodes are cut into small
// chunks; threads take chunks from an atomic counter and report them done, and nobody starts a
// stage before every chunk of the previous one is done. A thread that the operating system
// deschedules holds up a stage by at most the one chunk it holds, so a sweep sharing a busy
// machine degrades gracefully instead of waiting a time slice per stage (as a fixed split with
// a barrier does). Which thread computes a node does not change its value, so results do not
// depend on the thread count.
#pragma once

#include <sched.h>

#include <atomic>
#include <memory>

namespace ecorail::dp {

class StageWork {
 public:
  explicit StageWork(int stages)
      : next_(new std::atomic<int>[stages]), done_(new std::atomic<int>[stages]) {
    for (int i = 0; i < stages; ++i) {
      next_[i].store(0, std::memory_order_relaxed);
      done_[i].store(0, std::memory_order_relaxed);
    }
  }
  // Next chunk of stage i to compute, or -1 when all are taken.
  int take(int i, int chunks) {
    const int c = next_[i].fetch_add(1, std::memory_order_relaxed);
    return c < chunks ? c : -1;
  }
  void finish(int i) { done_[i].fetch_add(1, std::memory_order_release); }
  // Waits until every chunk of stage i is done.
  void wait(int i, int chunks) {
    int spins = 0;
    while (done_[i].load(std::memory_order_acquire) < chunks) {
      if (++spins > 64) {
        sched_yield();
        spins = 0;
      }
    }
  }

 private:
  std::unique_ptr<std::atomic<int>[]> next_;
  std::unique_ptr<std::atomic<int>[]> done_;
};

}  // namespace ecorail::dp
