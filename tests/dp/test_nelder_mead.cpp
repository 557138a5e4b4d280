// The Nelder-Mead search (dp/nelder_mead.hpp) against closed forms: a narrow valley whose
// coordinates are coupled (where one coordinate at a time crawls), Rosenbrock's function, a
// minimum on the edge of an infeasible region scored +inf, and its evaluation budget.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "dp/nelder_mead.hpp"

namespace ecorail::dp {
namespace {

TEST(NelderMead, FindsTheMinimumOfACoupledValley) {
  // (x0 + x1 - 2)^2 + 0.01 (x0 - x1)^2 + (x2 - x1)^2 + (x3 + 1)^2: minimum at (1, 1, 1, -1).
  int calls = 0;
  auto f = [&](const std::vector<double>& x) {
    ++calls;
    return std::pow(x[0] + x[1] - 2.0, 2) + 0.01 * std::pow(x[0] - x[1], 2) +
           std::pow(x[2] - x[1], 2) + std::pow(x[3] + 1.0, 2);
  };
  const NelderMeadResult r =
      nelder_mead_minimum(f, {4.0, -3.0, 0.0, 2.0}, {0.5, 0.5, 0.5, 0.5}, 1e-6, 4000);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.evaluations, calls);
  EXPECT_NEAR(r.x[0], 1.0, 1e-3);
  EXPECT_NEAR(r.x[1], 1.0, 1e-3);
  EXPECT_NEAR(r.x[2], 1.0, 1e-3);
  EXPECT_NEAR(r.x[3], -1.0, 1e-3);
  EXPECT_LT(r.f, 1e-8);
}

TEST(NelderMead, FindsRosenbrocksMinimum) {
  auto f = [](const std::vector<double>& x) {
    return 100.0 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1.0 - x[0], 2);
  };
  const NelderMeadResult r = nelder_mead_minimum(f, {-1.2, 1.0}, {0.1, 0.1}, 1e-8, 2000);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x[0], 1.0, 1e-4);
  EXPECT_NEAR(r.x[1], 1.0, 1e-4);
}

TEST(NelderMead, StopsAtAnInfeasibleEdge) {
  // (x - 3)^2 for x <= 2, +inf beyond: the least feasible value is at x = 2.
  auto f = [](const std::vector<double>& x) {
    return x[0] <= 2.0 ? std::pow(x[0] - 3.0, 2) : std::numeric_limits<double>::infinity();
  };
  const NelderMeadResult r = nelder_mead_minimum(f, {0.0}, {0.5}, 1e-6, 500);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(r.x[0], 2.0);
  EXPECT_GT(r.x[0], 2.0 - 1e-5);
}

TEST(NelderMead, KeepsToItsBudget) {
  int calls = 0;
  auto f = [&](const std::vector<double>& x) {
    ++calls;
    return 100.0 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1.0 - x[0], 2);
  };
  const NelderMeadResult r = nelder_mead_minimum(f, {-1.2, 1.0}, {0.1, 0.1}, 1e-12, 30);
  EXPECT_FALSE(r.converged);
  EXPECT_GE(calls, 30);
  EXPECT_LE(calls, 30 + 2);  // a shrink under way is finished: at most n more
  EXPECT_EQ(r.evaluations, calls);
  EXPECT_LT(r.f, f({-1.2, 1.0}));  // and the best point found, not the last
}

}  // namespace
}  // namespace ecorail::dp
