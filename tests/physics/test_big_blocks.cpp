// The DP's large arrays (base/big_blocks.hpp): a BigVector holds what a std::vector holds after
// the same operations, whatever the block sizes (below and above the big-block threshold), and a
// freed large block is what the next request of its size gets (the reuse that spares a price
// search its page clearing), and on Linux a big block lies in a mapping the kernel keeps on
// ordinary pages (VmFlags "nh").
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "base/big_blocks.hpp"

namespace ecorail {
namespace {

TEST(BigBlocks, ABigVectorHoldsWhatAStdVectorHoldsAfterTheSameOperations) {
  std::mt19937_64 rng(7);
  BigVector<double> big;
  std::vector<double> plain;
  // Sizes from a few elements to 3 M doubles (24 MB, above kBigBlockMinBytes).
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

TEST(BigBlocks, AFreedLargeBlockIsTheNextRequestOfItsSize) {
  BigBlockAllocator<std::uint8_t> alloc;
  const std::size_t n =
      6 * kBigBlockGranuleBytes + 123;  // above the threshold, not a granule multiple
  std::uint8_t* first = alloc.allocate(n);
  ASSERT_EQ(reinterpret_cast<std::uintptr_t>(first) % kBigBlockAlignBytes, 0u);
  first[0] = 1, first[n - 1] = 2;  // the whole block is writable
  alloc.deallocate(first, n);
  std::uint8_t* again = alloc.allocate(n);
  EXPECT_EQ(again, first);
  alloc.deallocate(again, n);
  // A block of another size does not take it (it is kept for its own size) ...
  std::uint8_t* other = alloc.allocate(n + 2 * kBigBlockGranuleBytes);
  EXPECT_NE(other, first);
  // ... and is itself the next request of its size, the first block still the next of n.
  alloc.deallocate(other, n + 2 * kBigBlockGranuleBytes);
  EXPECT_EQ(alloc.allocate(n + 2 * kBigBlockGranuleBytes), other);
  EXPECT_EQ(alloc.allocate(n), first);
  alloc.deallocate(other, n + 2 * kBigBlockGranuleBytes);
  alloc.deallocate(first, n);
  // Below the threshold the allocator is operator new's.
  std::uint8_t* small = alloc.allocate(1000);
  small[999] = 3;
  alloc.deallocate(small, 1000);
}

#if defined(__linux__) && defined(MADV_NOHUGEPAGE)
// The VmFlags line of the mapping of /proc/self/smaps that holds address p ("" if none).
std::string vm_flags_of(const void* p) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= at && at < hi;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "";
}

TEST(BigBlocks, ABigBlockIsKeptOnOrdinaryPages) {
  BigBlockAllocator<std::uint8_t> alloc;
  const std::size_t n = 5 * kBigBlockGranuleBytes;
  std::uint8_t* block = alloc.allocate(n);
  block[0] = 1, block[n - 1] = 2;
  const std::string flags = vm_flags_of(block + n / 2);
  if (flags.empty()) {
    alloc.deallocate(block, n);
    GTEST_SKIP() << "no VmFlags in /proc/self/smaps";
  }
  EXPECT_NE(flags.find(" nh"), std::string::npos) << flags;
  EXPECT_EQ(flags.find(" hg"), std::string::npos) << flags;
  alloc.deallocate(block, n);
}
#endif

}  // namespace
}  // namespace ecorail
