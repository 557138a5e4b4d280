// The DP's large arrays (base/huge_pages.hpp): a BigVector holds what a std::vector holds after
// the same operations, whatever the block sizes (below and above the huge-page threshold), and a
// freed large block is what the next request of its size gets (the reuse that spares a price
// search its page clearing).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "base/huge_pages.hpp"

namespace ecorail {
namespace {

TEST(HugePages, ABigVectorHoldsWhatAStdVectorHoldsAfterTheSameOperations) {
  std::mt19937_64 rng(7);
  BigVector<double> big;
  std::vector<double> plain;
  // Sizes from a few elements to 3 M doubles (24 MB, above kHugePageMinBytes).
  for (int round = 0; round < 40; ++round) {
    const std::size_t n = std::uniform_int_distribution<std::size_t>(0, 3'000'000)(rng);
    const double value = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
    switch (round % 4) {
      case 0:
        big.assign(n, value), plain.assign(n, value);
        break;
      case 1:
        for (std::size_t k = 0; k < n % 100'000; ++k) {
          big.push_back(value + static_cast<double>(k));
          plain.push_back(value + static_cast<double>(k));
        }
        break;
      case 2:
        big.resize(n / 2, value), plain.resize(n / 2, value);
        break;
      default: {
        BigVector<double> copy = big;
        big = std::move(copy);
      }
    }
    ASSERT_EQ(big.size(), plain.size()) << round;
    for (std::size_t k = 0; k < plain.size(); k += 997) ASSERT_EQ(big[k], plain[k]) << k;
    if (!plain.empty()) {
      ASSERT_EQ(big.back(), plain.back()) << round;
    }
  }
}

TEST(HugePages, AFreedLargeBlockIsTheNextRequestOfItsSize) {
  HugePageAllocator<std::uint8_t> alloc;
  const std::size_t n = 6 * kHugePageBytes + 123;  // above the threshold, not a page multiple
  std::uint8_t* first = alloc.allocate(n);
  ASSERT_EQ(reinterpret_cast<std::uintptr_t>(first) % kHugePageBytes, 0u);
  first[0] = 1, first[n - 1] = 2;  // the whole block is writable
  alloc.deallocate(first, n);
  std::uint8_t* again = alloc.allocate(n);
  EXPECT_EQ(again, first);
  alloc.deallocate(again, n);
  // A block of another size does not take it (it is kept for its own size) ...
  std::uint8_t* other = alloc.allocate(n + 2 * kHugePageBytes);
  EXPECT_NE(other, first);
  // ... and is itself the next request of its size, the first block still the next of n.
  alloc.deallocate(other, n + 2 * kHugePageBytes);
  EXPECT_EQ(alloc.allocate(n + 2 * kHugePageBytes), other);
  EXPECT_EQ(alloc.allocate(n), first);
  alloc.deallocate(other, n + 2 * kHugePageBytes);
  alloc.deallocate(first, n);
  // Below the threshold the allocator is operator new's.
  std::uint8_t* small = alloc.allocate(1000);
  small[999] = 3;
  alloc.deallocate(small, 1000);
}

}  // namespace
}  // namespace ecorail
