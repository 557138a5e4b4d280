// The chain lattice search (dp/chain_lattice_search.hpp): its DP over one lattice against brute
// force over all 3^n combinations of a lattice with arbitrary pair costs, a coupled valley whose
// minimum is known in closed form (followed along its diagonal), +inf pairs, its budget, and
// its costs solved on two threads (the same path, each pair once, an error passed on).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "dp/chain_lattice_search.hpp"

namespace ecorail::dp {
namespace {

// An arbitrary, repeatable cost of a pair (k, a, b): a hash of its arguments in [0, 1).
double hashed_cost(std::size_t k, double a, double b) {
  std::uint64_t h = 1469598103934665603ULL ^ k;
  for (const double x : {a, b}) {
    const auto bits = static_cast<std::int64_t>(std::llround(std::isnan(x) ? -7777.0 : x * 64.0));
    h = (h ^ static_cast<std::uint64_t>(bits)) * 1099511628211ULL;
    h ^= h >> 29;
  }
  return static_cast<double>(h % 1000003ULL) / 1000003.0;
}

TEST(ChainLatticeSearch, TheFirstLatticesBestIsTheBruteForceBest) {
  // Five variables, arbitrary pair costs: the DP's best of the first lattice (steps of 0.25
  // around x0) is the least of all 3^5 sums.
  const std::vector<double> x0{1.0, 2.0, -1.0, 0.5, 3.0};
  const std::size_t n = x0.size();
  const std::vector<double> lo(n, -10.0), hi(n, 10.0);
  const auto sum_at = [&](const std::vector<double>& x) {
    double f = hashed_cost(0, NAN, x[0]);
    for (std::size_t k = 1; k < n; ++k) f += hashed_cost(k, x[k - 1], x[k]);
    return f + hashed_cost(n, x[n - 1], NAN);
  };
  double brute = std::numeric_limits<double>::infinity();
  int combos = 1;
  for (std::size_t k = 0; k < n; ++k) combos *= 3;
  for (int c = 0; c < combos; ++c) {
    std::vector<double> x = x0;
    for (std::size_t k = 0, r = c; k < n; ++k, r /= 3) x[k] += 0.25 * (static_cast<int>(r % 3) - 1);
    brute = std::min(brute, sum_at(x));
  }
  const int one_lattice = 3 + 9 * static_cast<int>(n - 1) + 3;
  const ChainLatticeResult r = chain_lattice_minimum(hashed_cost, x0, lo, hi, 0.25, 1, one_lattice);
  ASSERT_FALSE(r.lattice_bests.empty());
  EXPECT_DOUBLE_EQ(r.lattice_bests.front().first, brute);
  EXPECT_DOUBLE_EQ(sum_at(r.lattice_bests.front().second), brute);
  EXPECT_LE(r.cost_evaluations, one_lattice);
}

TEST(ChainLatticeSearch, FollowsACoupledValleyToItsMinimum) {
  // (x0 + x1 - 2)^2 + 0.01 (x0 - x1)^2 + (x2 - x1)^2 + (x3 + 1)^2 as a chain: minimum at
  // (1, 1, 1, -1), 7 units of the first step from the start along a narrow diagonal valley.
  int calls = 0;
  auto cost = [&](std::size_t k, double a, double b) {
    ++calls;
    switch (k) {
      case 0:
        return 0.0;
      case 1:
        return std::pow(a + b - 2.0, 2) + 0.01 * std::pow(a - b, 2);
      case 2:
        return std::pow(b - a, 2);
      case 3:
        return std::pow(b + 1.0, 2);
      default:
        return 0.0;
    }
  };
  const ChainLatticeResult r =
      chain_lattice_minimum(cost, {4.0, -3.0, 0.0, 2.0}, std::vector<double>(4, -10.0),
                            std::vector<double>(4, 10.0), 0.5, 8, 100000);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.cost_evaluations, calls);  // every pair's cost once
  const double finest = 0.5 / 128.0;
  EXPECT_NEAR(r.x[0], 1.0, 3 * finest);
  EXPECT_NEAR(r.x[1], 1.0, 3 * finest);
  EXPECT_NEAR(r.x[2], 1.0, 3 * finest);
  EXPECT_NEAR(r.x[3], -1.0, 3 * finest);
  EXPECT_LT(r.f, 1e-4);
}

TEST(ChainLatticeSearch, StopsAtACornerOfInfinitePairsAndABound) {
  // (x0 - 2)^2 + (x1 - x0)^2 with x0 + x1 > 2.8 infeasible (+inf) and x1 <= 1.25: the least
  // feasible point is the corner x1 = 1.25, x0 = 1.55, f = 0.2925 (on x0 + x1 = 2.8 alone the
  // least is at x1 = 1.28, beyond the bound).
  auto cost = [](std::size_t k, double a, double b) {
    if (k == 0) return std::pow(b - 2.0, 2);
    if (k == 1) return a + b > 2.8 ? std::numeric_limits<double>::infinity() : std::pow(b - a, 2);
    return 0.0;
  };
  const ChainLatticeResult r =
      chain_lattice_minimum(cost, {0.0, 0.0}, {-5.0, -5.0}, {5.0, 1.25}, 0.5, 6, 100000);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.x[1], 1.25);
  EXPECT_LE(r.x[0] + r.x[1], 2.8);
  EXPECT_NEAR(r.x[0], 1.55, 0.02);
  EXPECT_NEAR(r.x[1], 1.25, 0.02);
  EXPECT_NEAR(r.f, 0.2925, 0.005);
}

TEST(ChainLatticeSearch, KeepsItsBudget) {
  int calls = 0;
  auto cost = [&](std::size_t, double a, double b) {
    ++calls;
    return (std::isnan(a) ? 0.0 : a * a) + (std::isnan(b) ? 0.0 : b * b);
  };
  const ChainLatticeResult r = chain_lattice_minimum(
      cost, {5.0, 5.0, 5.0}, std::vector<double>(3, -9.0), std::vector<double>(3, 9.0), 0.5, 6, 40);
  EXPECT_EQ(r.cost_evaluations, calls);
  EXPECT_LE(calls, 40);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.f, 3 * 25.0 * 2);  // it moved downhill from the start
}

TEST(ChainLatticeSearch, TwoThreadsTakeTheSamePathAndSolveEachPairOnce) {
  // A bumpy valley (a bowl plus the hashed costs), four variables: every lattice's best, the
  // result and the count of costs are the same on one thread and on two, and on two threads
  // no pair is solved twice.
  auto bumpy = [](std::size_t k, double a, double b) {
    const double x = std::isnan(a) ? 0.0 : a, y = std::isnan(b) ? 0.0 : b;
    return 0.2 * (x - 1.5) * (x - 1.5) + 0.1 * (y - x) * (y - x) + 0.05 * hashed_cost(k, a, b);
  };
  const std::vector<double> x0{-2.0, 3.0, 0.0, 4.0}, lo(4, -6.0), hi(4, 6.0);
  const ChainLatticeResult one = chain_lattice_minimum(bumpy, x0, lo, hi, 1.0, 5, 100000, 1);
  std::mutex mutex;
  std::set<std::tuple<std::size_t, double, double>> seen;
  std::atomic<int> calls{0}, repeats{0};
  auto counted = [&](std::size_t k, double a, double b) {
    ++calls;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!seen.emplace(k, std::isnan(a) ? -1e9 : a, std::isnan(b) ? -1e9 : b).second) ++repeats;
    }
    return bumpy(k, a, b);
  };
  const ChainLatticeResult two = chain_lattice_minimum(counted, x0, lo, hi, 1.0, 5, 100000, 2);
  ASSERT_TRUE(one.converged);
  EXPECT_TRUE(two.converged);
  EXPECT_EQ(two.x, one.x);
  EXPECT_EQ(two.f, one.f);
  EXPECT_EQ(two.cost_evaluations, one.cost_evaluations);
  EXPECT_EQ(two.lattice_bests, one.lattice_bests);
  EXPECT_EQ(calls.load(), two.cost_evaluations);
  EXPECT_EQ(repeats.load(), 0);
}

TEST(ChainLatticeSearch, ACostsErrorEndsTheSearchOnAnyThreadCount) {
  // Two pairs of the first stage throw: the search passes on the error of the first in the
  // stage's order, whichever thread met it.
  auto failing = [](std::size_t k, double, double b) -> double {
    if (k == 0 && b == 1.0) throw std::runtime_error("the pair at 1");
    if (k == 0 && b == 3.0) throw std::runtime_error("the pair at 3");
    return 0.0;
  };
  for (const int threads : {1, 2}) {
    try {
      chain_lattice_minimum(failing, {2.0, 2.0}, {-9.0, -9.0}, {9.0, 9.0}, 1.0, 2, 1000, threads);
      ADD_FAILURE() << "no error on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "the pair at 1") << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace ecorail::dp
