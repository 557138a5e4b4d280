// StageWork: scheduling of the backward sweep over threads without a barrier per stage. Each
// stage's nodes are cut into chunks of kSweepChunk nodes. A chunk may be computed as soon as
// the chunks of the next stage it reads are done (its dependency range, known from the
// transition table and independent of lambda), so threads flow from stage to stage and wait
// only where their work really meets. Each thread owns a contiguous block of every stage (its
// share of the speed range), so what it reads was mostly written by itself, and computes the
// chunk bordering another thread's block first, so the neighbour, which reads it one stage
// later, rarely waits for it; when its block is done it
// steals unclaimed chunks, so a thread the system deschedules holds up the others by at most
// the one chunk it is computing. Which thread computes a node does not change its value, so
// results do not depend on the thread count.
#pragma once

#include <sched.h>

#include <atomic>
#include <memory>
#include <vector>

namespace ecorail::dp {

inline constexpr int kSweepChunk = 64;

// For each stage and chunk: the first and last chunk of the next stage that it reads.
struct ChunkDependencies {
  std::vector<int> chunk_offset;  // per stage: index of its first chunk (size stages + 1)
  std::vector<int> first, last;   // per chunk (global chunk index), in next-stage chunk numbers
  int chunks(int stage) const { return chunk_offset[stage + 1] - chunk_offset[stage]; }
};

class StageWork {
 public:
  StageWork(const ChunkDependencies& deps, int threads)
      : deps_(&deps),
        threads_(threads),
        claims_(static_cast<std::size_t>(deps.chunk_offset.size()) * threads),
        done_(new std::atomic<unsigned char>[deps.chunk_offset.back()]) {
    for (int c = 0; c < deps.chunk_offset.back(); ++c) done_[c].store(0, std::memory_order_relaxed);
  }

  // The next chunk of stage i for `thread`: from its own block (border first), else stolen
  // from another block; -1 when every chunk of the stage is claimed.
  int take(int i, int thread) {
    const int chunks = deps_->chunks(i);
    for (int k = 0; k < threads_; ++k) {
      const int owner = (thread + k) % threads_;
      const int first = static_cast<int>(static_cast<long>(chunks) * owner / threads_);
      const int last = static_cast<int>(static_cast<long>(chunks) * (owner + 1) / threads_);
      std::atomic<int>& next = claims_[static_cast<std::size_t>(i) * threads_ + owner].next;
      if (next.load(std::memory_order_relaxed) >= last - first) continue;
      const int n = next.fetch_add(1, std::memory_order_relaxed);
      if (n >= last - first) continue;
      // The chunk on the border with the next block up comes first (the neighbour reads it one
      // stage later, by when it is long done), then the block in memory order.
      if (owner + 1 == threads_) return first + n;
      return n == 0 ? last - 1 : first + n - 1;
    }
    return -1;
  }
  // Waits until every chunk that chunk c of stage i reads (in stage i + 1) is done.
  void wait_for_inputs(int i, int c) const {
    const int g = deps_->chunk_offset[i] + c;
    const int base = deps_->chunk_offset[i + 1];
    for (int d = deps_->first[g]; d <= deps_->last[g]; ++d) {
      int spins = 0;
      while (done_[base + d].load(std::memory_order_acquire) == 0) {
        if (++spins > 64) {
          sched_yield();
          spins = 0;
        }
      }
    }
  }
  void finish(int i, int c) {
    done_[deps_->chunk_offset[i] + c].store(1, std::memory_order_release);
  }
  // The final stage (the stop) is given, not computed.
  void mark_stage_done(int i) {
    for (int c = 0; c < deps_->chunks(i); ++c) finish(i, c);
  }

 private:
  struct alignas(64) Claim {
    std::atomic<int> next{0};
  };
  const ChunkDependencies* deps_;
  int threads_;
  std::vector<Claim> claims_;
  std::unique_ptr<std::atomic<unsigned char>[]> done_;
};

}  // namespace ecorail::dp
