// What the fleet's searches share: wall-clock seconds for time limits and progress, and
// counter-based random numbers. A draw depends only on what it is for (seed, run, move and the
// draw within the move, plus a salt naming the search), never on which thread makes it or in
// which order, so a search gives the same result for any thread count.
#pragma once

#include <chrono>
#include <cstdint>

namespace ecorail::fleet {

using SearchClock = std::chrono::steady_clock;

inline double seconds_since(SearchClock::time_point t0) {
  return std::chrono::duration<double>(SearchClock::now() - t0).count();
}

// SplitMix64's finaliser: a bijection of 64-bit words that scrambles every bit.
inline std::uint64_t counter_mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Draw k (0..3) of move `move` of run `run`.
inline std::uint64_t counter_draw(std::uint64_t seed, std::uint64_t run, std::uint64_t move,
                                  std::uint64_t k, std::uint64_t salt = 0) {
  return counter_mix(counter_mix(counter_mix(seed ^ salt) ^ run) ^ (move * 4 + k));
}

// A draw as a uniform number in [0, 1) (its top 53 bits).
inline double uniform01(std::uint64_t r) {
  return static_cast<double>(r >> 11) * 0x1.0p-53;
}

}  // namespace ecorail::fleet
