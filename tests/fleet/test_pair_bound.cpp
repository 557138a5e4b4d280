// The power-flow certificate and optimiser on a fleet small enough to enumerate: the pair bound
// is never below the brute-force optimum, the optimiser reaches that optimum, and the same seed
// gives the same timetable on one and two threads.
#include <gtest/gtest.h>

#include <functional>

#include "energy/fleet_energy_model.hpp"
#include "energy/pair_bound.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

FleetProblem small_problem() {
  return testing::small_fleet(4, 80, 140, 330);
}

double brute_force_used(const TestFleet& models) {
  const FleetProblem& p = models.problem();
  auto balance = models.make_balance();
  MicroJoules best = 0;
  for (int h1 = p.headway_min_s; h1 <= p.headway_max_s; ++h1)
    for (int h2 = p.headway_min_s; h2 <= p.headway_max_s; ++h2) {
      const int h3 = p.span_s - h1 - h2;
      if (h3 < p.headway_min_s || h3 > p.headway_max_s) continue;
      balance->place_all({0, h1, h1 + h2, p.span_s});
      best = std::max(best, balance->used());
    }
  return to_joules(best);
}

TEST(PairBound, NeverBelowTheBruteForceOptimumAndTheOptimiserReachesIt) {
  for (const std::string model : {"power-flow", "sections"}) {
    EnergyModelOptions o;
    o.model = model;
    o.time_step_s = 0.1;
    if (model == "sections") o.section_boundaries_m = {2000.0};
    const TestFleet models(testing::small_pattern().trip, small_problem(), o);
    const double best = brute_force_used(models);
    const PairBound bound = used_regen_bound(models.profile(), limits_of(models.problem()));
    EXPECT_GE(bound.bound_used_J, best * (1 - 1e-12));
    HeadwayOptimiserOptions opt;
    opt.moves_per_run = 2000;
    opt.polish_window_s = 60;
    const HeadwayOptimiserResult r = optimise_headways(models, opt);
    EXPECT_NEAR(r.summary.used_regen_J, best, 1e-9 * best) << model;
    EXPECT_GE(r.summary.bound_used_regen_J, r.summary.used_regen_J);
    EXPECT_GT(best, 0.0);
  }
}

TEST(HeadwayOptimiser, SameSeedSameTimetableOnOneAndTwoThreads) {
  const FleetProblem p = testing::small_fleet(10, 80, 200, 9 * 150);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const TestFleet models(testing::small_pattern().trip, p, o);
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 5000;
  opt.seed = 42;
  opt.threads = 1;
  const auto one = optimise_headways(models, opt);
  opt.threads = 2;
  const auto two = optimise_headways(models, opt);
  EXPECT_EQ(one.headways_s, two.headways_s);
  EXPECT_EQ(one.summary.used_regen_J, two.summary.used_regen_J);
  int sum = 0;
  for (int h : one.headways_s) {
    EXPECT_GE(h, p.headway_min_s);
    EXPECT_LE(h, p.headway_max_s);
    sum += h;
  }
  EXPECT_EQ(sum, p.span_s);
}

TEST(HeadwayOptimiser, OptionsNameTheirBadField) {
  std::string why;
  HeadwayOptimiserOptions o;
  o.restarts = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("restarts"), std::string::npos);
  o = {};
  o.time_limit_s = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("time_limit_s"), std::string::npos);
  EnergyModelOptions e;
  e.time_step_s = 0.3;
  EXPECT_FALSE(e.IsValid(&why));
  EXPECT_NE(why.find("time_step_s"), std::string::npos);
  FleetProblem p;
  p.span_s = 100;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("span_s"), std::string::npos);
}

}  // namespace
}  // namespace ecorail::fleet
