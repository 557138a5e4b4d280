// BigBlockAllocator: a std::allocator for the DP's largest arrays (transition tables of hundreds
// of megabytes, value functions of tens, simulation traces of a million points). Memory fresh
// from the kernel is cleared page by page on first touch: a price search that allocated a new
// value function for every price spent a fifth of its time there. So a freed block of at least
// kBigBlockMinBytes is kept (up to kBigBlockCacheBytes in all) for the next request of its size,
// sizes rounded up to kBigBlockGranuleBytes so that vectors of nearly the same length share
// blocks; smaller blocks come from operator new. Big blocks are advised MADV_NOHUGEPAGE (Linux):
// on the 2-core virtual machine we measure on, clearing 2 MiB pages took 3.7-4.0 s of system
// time on the GPOPS-II case against 0.8 s for 4 KiB pages (docs/performance.md, "Memory the
// kernel clears"), so the arrays are kept on ordinary pages whatever the kernel's default.
// Contents, and so every result, are what std::allocator gives.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ecorail {

inline constexpr std::size_t kBigBlockGranuleBytes = std::size_t{2} << 20;
inline constexpr std::size_t kBigBlockMinBytes = std::size_t{4} << 20;
inline constexpr std::size_t kBigBlockCacheBytes = std::size_t{256} << 20;
// Where a big block starts: a page, so that madvise can take it.
inline constexpr std::size_t kBigBlockAlignBytes = 4096;

namespace big_blocks {
namespace detail {

struct Cache {
  std::mutex mutex;
  std::vector<std::pair<void*, std::size_t>> blocks;  // (block, bytes), most recent last
  std::size_t bytes = 0;
};

// Never destroyed: a static object holding a BigVector may be destroyed after any other static,
// and its blocks come back here. What the cache holds at exit stays reachable through it.
inline Cache& cache() {
  static Cache* c = new Cache;
  return *c;
}

}  // namespace detail

// A block of `bytes` (a multiple of kBigBlockGranuleBytes), from the cache or fresh; never
// nullptr.
inline void* allocate(std::size_t bytes) {
  {
    detail::Cache& c = detail::cache();
    const std::lock_guard<std::mutex> lock(c.mutex);
    for (std::size_t k = c.blocks.size(); k-- > 0;) {
      if (c.blocks[k].second != bytes) continue;
      void* block = c.blocks[k].first;
      c.blocks.erase(c.blocks.begin() + static_cast<std::ptrdiff_t>(k));
      c.bytes -= bytes;
      return block;
    }
  }
  void* block = std::aligned_alloc(kBigBlockAlignBytes, bytes);
  if (block == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_NOHUGEPAGE)
  ::madvise(block, bytes, MADV_NOHUGEPAGE);  // a hint: failure leaves the kernel's default
#endif
  return block;
}

// Keeps the block for the next request of its size, or frees it when the cache is full.
inline void release(void* block, std::size_t bytes) noexcept {
  detail::Cache& c = detail::cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    if (c.bytes + bytes <= kBigBlockCacheBytes) {
      try {
        c.blocks.emplace_back(block, bytes);
        c.bytes += bytes;
        return;
      } catch (...) {
        // No room to remember it: free it below.
      }
    }
  }
  std::free(block);
}
}  // namespace big_blocks

template <typename T>
struct BigBlockAllocator {
  using value_type = T;
  BigBlockAllocator() = default;
  template <typename U>
  BigBlockAllocator(const BigBlockAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kBigBlockMinBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(big_blocks::allocate(rounded(bytes)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kBigBlockMinBytes) {
      ::operator delete(p);
    } else {
      big_blocks::release(p, rounded(bytes));
    }
  }
  // resize() default-initialises, as new T[n] does: elements of a trivially constructible T are
  // left unwritten for their owner to fill (the transition table fills every entry in its
  // parallel build, so its pages are first touched there, on every thread).
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  static std::size_t rounded(std::size_t bytes) {
    return (bytes + kBigBlockGranuleBytes - 1) / kBigBlockGranuleBytes * kBigBlockGranuleBytes;
  }
  template <typename U>
  bool operator==(const BigBlockAllocator<U>&) const noexcept {
    return true;
  }
};

// A vector of the DP's size: millions of grid nodes.
template <typename T>
using BigVector = std::vector<T, BigBlockAllocator<T>>;

}  // namespace ecorail
