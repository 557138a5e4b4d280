// HugePageAllocator: a std::allocator for the DP's largest arrays (transition tables of hundreds
// of megabytes, value functions of tens) that asks the kernel for 2 MiB pages. Each first touch
// of a 4 KiB page is a page fault; a 48 km section's table and its price search's value
// functions took about 585 000 of them, a fifth of the run's time on a virtual machine. Blocks
// of at least kHugePageMinBytes are aligned to 2 MiB and advised MADV_HUGEPAGE (Linux; where the
// kernel keeps transparent huge pages to madvised areas, as Debian's does, or has them off, this
// is a hint and nothing else changes); smaller blocks come from operator new. A freed large block
// is kept (up to kHugePageCacheBytes in all) for the next request of its size: a price search
// allocates a value function of the same size for every price, and memory fresh from the kernel
// is cleared page by page first (a fifth of that search's time). Contents, and so every result,
// are what std::allocator gives.
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

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageMinBytes = std::size_t{4} << 20;

inline constexpr std::size_t kHugePageCacheBytes = std::size_t{256} << 20;

namespace huge_pages {
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

// A block of `bytes` (a multiple of kHugePageBytes), from the cache or fresh; never nullptr.
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
  void* block = std::aligned_alloc(kHugePageBytes, bytes);
  if (block == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  ::madvise(block, bytes, MADV_HUGEPAGE);  // a hint: failure leaves ordinary pages
#endif
  return block;
}

// Keeps the block for the next request of its size, or frees it when the cache is full.
inline void release(void* block, std::size_t bytes) noexcept {
  detail::Cache& c = detail::cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    if (c.bytes + bytes <= kHugePageCacheBytes) {
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
}  // namespace huge_pages

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePageMinBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(huge_pages::allocate(rounded(bytes)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePageMinBytes) {
      ::operator delete(p);
    } else {
      huge_pages::release(p, rounded(bytes));
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
    return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

// A vector of the DP's size: millions of grid nodes.
template <typename T>
using BigVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace ecorail
