// The exact headway DPs against brute force: random value and penalty tables, and the overlap
// model of a real pattern (both variants), on instances small enough to enumerate every
// timetable.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "energy/fleet_energy_model.hpp"
#include "fleet/headway_dp.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

// Every headway vector of the domain, in lexicographic order.
void for_each_timetable(const HeadwayDomain& d,
                        const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> h(d.count, d.min_s);
  std::function<void(int, int)> rec = [&](int k, int sum) {
    if (k == d.count) {
      if (sum == d.sum_s) f(h);
      return;
    }
    for (int v = d.min_s; v <= d.max_s; ++v) {
      h[k] = v;
      rec(k + 1, sum + v);
    }
  };
  rec(0, 0);
}

TEST(HeadwayDp, SeparableEqualsBruteForceOnRandomTables) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    HeadwayDomain d{4, 10, 10 + static_cast<int>(rng() % 8), 0};
    d.sum_s = d.count * d.min_s + static_cast<int>(rng() % (d.count * d.width() + 1));
    std::vector<double> value(d.width() + 1);
    for (double& v : value) v = std::uniform_real_distribution<double>(-5, 5)(rng);
    double best = -1e300;
    for_each_timetable(d, [&](const std::vector<int>& h) {
      double s = 0;
      for (int x : h) s += value[x - d.min_s];
      best = std::max(best, s);
    });
    const HeadwayChoice c = maximise_separable(d, value);
    EXPECT_NEAR(c.value, best, 1e-9);
    double check = 0;
    int sum = 0;
    for (int x : c.headways_s) check += value[x - d.min_s], sum += x;
    EXPECT_NEAR(check, c.value, 1e-9);
    EXPECT_EQ(sum, d.sum_s);
  }
}

TEST(HeadwayDp, ChainEqualsBruteForceOnRandomTables) {
  std::mt19937_64 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    HeadwayDomain d{5, 20, 20 + static_cast<int>(rng() % 6), 0};
    d.sum_s = d.count * d.min_s + static_cast<int>(rng() % (d.count * d.width() + 1));
    const int m = d.width() + 1;
    std::vector<double> value(m), penalty(static_cast<std::size_t>(m) * m);
    for (double& v : value) v = std::uniform_real_distribution<double>(0, 5)(rng);
    // Sparse, non-negative penalties (as the double count of the union variant is).
    for (double& p : penalty)
      p = rng() % 3 == 0 ? std::uniform_real_distribution<double>(0, 6)(rng) : 0.0;
    auto score = [&](const std::vector<int>& h) {
      double s = 0;
      for (std::size_t k = 0; k < h.size(); ++k) {
        s += value[h[k] - d.min_s];
        if (k + 1 < h.size()) s -= penalty[(h[k] - d.min_s) * m + (h[k + 1] - d.min_s)];
      }
      return s;
    };
    double best = -1e300;
    for_each_timetable(d, [&](const std::vector<int>& h) { best = std::max(best, score(h)); });
    const HeadwayChoice c = maximise_chain(d, value, penalty);
    EXPECT_NEAR(c.value, best, 1e-9) << trial;
    EXPECT_NEAR(score(c.headways_s), c.value, 1e-9);
  }
}

// Brute force over every timetable of a small fleet in the overlap model, both variants.
TEST(HeadwayDp, OverlapOptimumEqualsBruteForceOnARealPattern) {
  FleetProblem p;
  p.trains = 5;
  p.headway_min_s = 180;  // where a leader's departures meet its follower's braking
  p.headway_max_s = 240;
  p.span_s = 4 * 207;
  for (OverlapVariant variant : {OverlapVariant::Ahead, OverlapVariant::Either}) {
    EnergyModelOptions o;
    o.model = "overlap";
    o.overlap = variant;
    const TestFleet models(testing::small_pattern().trip, p, o);
    double best = -1.0;
    for_each_timetable(
        {p.trains - 1, p.headway_min_s, p.headway_max_s, p.span_s}, [&](const std::vector<int>& h) {
          const auto e = models.overlap().evaluate(departures_from_headways(h), variant);
          best = std::max(best, e.used_regen_J);
        });
    const HeadwayOptimiserResult r = optimise_headways(models, {});
    EXPECT_TRUE(r.summary.exact);
    EXPECT_NEAR(r.summary.used_regen_J, best, 1e-6 * best) << overlap_variant_name(variant);
    EXPECT_GT(best, 0.0);
  }
}

// The overlap model's interval arithmetic against a fine time sampling of the same rule.
TEST(OverlapModel, AgreesWithASampledOverlap) {
  const physics::Trip& trip = testing::small_pattern().trip;
  const OverlapModel model(trip);
  auto in_traction = [&](double t) {
    for (const auto& iv : model.traction())
      if (t >= iv.begin_s && t < iv.end_s) return true;
    return false;
  };
  for (double ahead : {60.0, 97.0, 130.0, 211.0}) {
    double sampled = 0.0;
    for (const auto& p : model.braking()) {
      int hits = 0, n = 0;
      for (double t = p.time.begin_s + 5e-4; t < p.time.end_s; t += 1e-3, ++n)
        hits += in_traction(t + ahead) ? 1 : 0;
      sampled += p.regen_J * hits / std::max(1, n);
    }
    EXPECT_NEAR(model.used_from_ahead_J(ahead), sampled, 2e-3 * model.trip_regen_J()) << ahead;
  }
  EXPECT_NEAR(model.trip_traction_J(), trip.ledger().traction_work_J,
              1e-6 * trip.ledger().traction_work_J);
  EXPECT_NEAR(model.trip_regen_J(), trip.ledger().regen_J, 1e-6 * trip.ledger().regen_J);
}

}  // namespace
}  // namespace ecorail::fleet
