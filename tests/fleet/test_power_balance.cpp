// The power balance (power-flow and sections models): bins that conserve the trip's energy,
// integer totals that do not drift under a million moves, the bookkeeping limits (used never
// above regenerated or traction power in any bin, nothing used with regeneration off or with one
// train) and the sections model with one section equal to power-flow.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "energy/fleet_energy_model.hpp"
#include "energy/power_flow_balance.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

using testing::small_pattern;

// The small pattern's section runs laid out as a trip with these dwells and this regeneration
// efficiency (the runs live as long as the library's cache: a static store here).
physics::Trip small_pattern_trip(double dwell_s, double regen_efficiency) {
  static const std::vector<dp::SectionTimeSolve> solves = [] {
    const auto& lib = testing::small_library();
    std::vector<dp::SectionTimeSolve> out;
    for (std::size_t i = 0; i < lib.size(); ++i)
      out.push_back(lib.solve(i, small_pattern().pattern.running_times_s[i]));
    return out;
  }();
  const auto& lib = testing::small_library();
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < lib.size(); ++i)
    sections.push_back(
        {&lib.route(i), &solves[i].search.run.sim, i + 1 < lib.size() ? dwell_s : 0.0});
  return physics::Trip(sections, 0.0, regen_efficiency);
}

TEST(PowerProfile, BinsAddUpToTheTripLedgerForEveryStep) {
  const physics::Trip& trip = small_pattern().trip;
  for (int tps : {1, 3, 10, 100, 1000}) {
    const PowerProfile p(trip, tps, {});
    const double traction = trip.ledger().traction_work_J;
    const double regen = trip.ledger().regen_J;
    // Quantisation: at most half a micro-joule per bin.
    const double slack = 1e-6 * static_cast<double>(p.bins().size());
    EXPECT_NEAR(to_joules(p.traction_total()), traction, slack + 1e-9 * traction) << tps;
    EXPECT_NEAR(to_joules(p.regen_total()), regen, slack + 1e-9 * regen) << tps;
    EXPECT_GT(regen, 0.0);
  }
}

TEST(PowerBalance, AMillionMovesLeaveExactlyTheTotalsOfAFreshEvaluation) {
  const FleetProblem problem = testing::small_fleet(12, 60, 300, 11 * 150);
  EnergyModelOptions o;
  o.time_step_s = 1.0;  // coarse, so a million moves run in seconds; the arithmetic is the same
  const TestFleet models(small_pattern().trip, problem, o);
  auto moved = models.make_balance();
  std::vector<int> t;
  for (int k = 0; k < problem.trains; ++k) t.push_back(150 * k);
  moved->place_all(t);
  std::mt19937_64 rng(7);
  for (int m = 0; m < 1'000'000; ++m) {
    const int k = 1 + static_cast<int>(rng() % (problem.trains - 2));
    const int lo = std::max(t[k - 1] + 60, t[k + 1] - 300);
    const int hi = std::min(t[k - 1] + 300, t[k + 1] - 60);
    t[k] = lo + static_cast<int>(rng() % (hi - lo + 1));
    moved->move(k, t[k]);
  }
  auto fresh = models.make_balance();
  fresh->place_all(t);
  EXPECT_EQ(moved->used(), fresh->used());
  EXPECT_EQ(moved->used(), moved->recount_used());
  EXPECT_EQ(moved->traction(), fresh->traction());
  EXPECT_GT(fresh->used(), 0);
}

// The searches price moves without making them (the annealing's proposals, the polish's window
// of departures, a candidate trip under every train): each read-only price is exactly the
// integer change the move makes, on one supply section and on two (bins of one offset in
// different sections), for shifts that overlap the train's old bins and shifts that do not.
TEST(PowerBalance, PricesWithoutMovingAreExactlyTheMovesChanges) {
  const FleetProblem problem = testing::small_fleet(8, 60, 200, 7 * 101);
  for (const bool sections : {false, true}) {
    EnergyModelOptions o;
    o.time_step_s = 0.1;
    if (sections) o.model = "sections", o.section_boundaries_m = {2000.0};
    const TestFleet models(small_pattern().trip, problem, o);
    auto b = models.make_balance();
    std::vector<int> t;
    for (int k = 0; k < problem.trains; ++k) t.push_back(101 * k);
    b->place_all(t);
    std::mt19937_64 rng(11);
    for (int m = 0; m < 300; ++m) {
      const int k = static_cast<int>(rng() % problem.trains);
      const int shift = static_cast<int>(rng() % 1201) - 600;     // beyond the trip time too
      const int d = std::clamp(t[k] + shift, 0, problem.span_s);  // within the horizon
      const MicroJoules priced = b->used_change_if_moved(k, d);
      const MicroJoules before = b->used();
      ASSERT_EQ(b->move(k, d), priced) << "sections " << sections << " move " << m;
      ASSERT_EQ(b->used() - before, priced);
      if (rng() % 2)
        b->move(k, t[k]);  // undo half of them
      else
        t[k] = d;
    }
    EXPECT_EQ(b->used(), b->recount_used());
    // A window of departures for one train, priced at once; the balance is left as it was.
    const std::vector<int> window{0, std::max(0, t[3] - 1), std::min(t[3] + 30, problem.span_s),
                                  problem.span_s};
    std::vector<MicroJoules> used_at;
    const MicroJoules kept = b->used();
    b->used_at(3, window, used_at);
    EXPECT_EQ(b->used(), kept);
    EXPECT_THROW(b->used_at(3, {0, problem.span_s + 10000}, used_at), std::out_of_range);
    EXPECT_EQ(b->used(), kept);
    for (std::size_t i = 0; i < window.size(); ++i) {
      b->move(3, window[i]);
      EXPECT_EQ(used_at[i], b->used()) << "departure " << window[i];
    }
    b->move(3, t[3]);
    // Every train on another profile (the same runs with half the regeneration and shorter
    // dwells), laid afresh and one train at a time.
    const PowerProfile other(small_pattern_trip(23.0, 0.5), o.ticks_per_second(),
                             o.section_boundaries_m);
    auto one_by_one = models.make_balance();
    one_by_one->place_all(t);
    for (int k = 0; k < problem.trains; ++k) one_by_one->set_profile(k, &other);
    b->set_profile_all(&other);
    EXPECT_EQ(b->used(), one_by_one->used());
    EXPECT_EQ(b->traction(), one_by_one->traction());
    EXPECT_EQ(b->regen(), one_by_one->regen());
    EXPECT_EQ(b->used(), b->recount_used());
    EXPECT_GT(b->used(), 0);
  }
}

TEST(PowerBalance, UsedNeverExceedsRegenOrTractionInAnyBin) {
  const FleetProblem problem = testing::small_fleet(6, 60, 200, 5 * 97);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const TestFleet models(small_pattern().trip, problem, o);
  auto b = models.make_balance();
  b->place_all({0, 97, 194, 291, 388, 485});
  const auto trace = b->trace(0.0, 2000.0);
  double used = 0.0;
  for (std::size_t i = 0; i < trace.used_W.size(); ++i) {
    ASSERT_LE(trace.used_W[i], trace.regen_W[i] + 1e-6);
    ASSERT_LE(trace.used_W[i], trace.traction_W[i] + 1e-6);
    used += trace.used_W[i] * trace.step_s;
  }
  EXPECT_NEAR(used, b->energy().used_regen_J, 1e-6 * b->energy().used_regen_J);
  EXPECT_GT(used, 0.0);
}

TEST(PowerBalance, WithoutRegenerationTheSubstationSuppliesAllTraction) {
  // One set of section runs laid out twice: regeneration efficiency 0.95 and 0.
  const physics::Trip with = small_pattern_trip(30.0, 0.95),
                      without = small_pattern_trip(30.0, 0.0);
  const FleetProblem problem = testing::small_fleet(4, 60, 250, 600);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const std::vector<int> t{0, 200, 400, 600};
  const FleetEvaluation off = TestFleet(without, problem, o).evaluate(t);
  EXPECT_EQ(off.total.used_regen_J, 0.0);
  EXPECT_EQ(off.total.regen_J, 0.0);
  EXPECT_DOUBLE_EQ(off.total.substation_J(), off.total.traction_J);
  const FleetEvaluation on = TestFleet(with, problem, o).evaluate(t);
  EXPECT_GT(on.total.used_regen_J, 0.0);
  EXPECT_EQ(on.total.traction_J, off.total.traction_J);
}

TEST(PowerBalance, OneTrainUsesNothing) {
  FleetProblem problem;
  problem.trains = 1;
  problem.span_s = 0;
  for (double step : {1.0, 0.1, 0.01}) {
    EnergyModelOptions o;
    o.time_step_s = step;
    const FleetEvaluation e = TestFleet(small_pattern().trip, problem, o).evaluate({0});
    EXPECT_EQ(e.total.used_regen_J, 0.0) << step;
    EXPECT_GT(e.total.regen_J, 0.0);
  }
}

TEST(PowerBalance, SectionsWithOneSectionIsPowerFlowAndSplittingNeverUsesMore) {
  const FleetProblem problem = testing::small_fleet(8, 60, 200, 7 * 101);
  std::vector<int> t;
  for (int k = 0; k < 8; ++k) t.push_back(101 * k);
  EnergyModelOptions flow;
  flow.time_step_s = 0.1;
  EnergyModelOptions one = flow;
  one.model = "sections";
  one.section_boundaries_m = {1e7};  // beyond the line: everything in the first section
  EnergyModelOptions two = one;
  two.section_boundaries_m = {2000.0};
  const auto& trip = small_pattern().trip;
  const FleetEvaluation a = TestFleet(trip, problem, flow).evaluate(t);
  const FleetEvaluation b = TestFleet(trip, problem, one).evaluate(t);
  const FleetEvaluation c = TestFleet(trip, problem, two).evaluate(t);
  EXPECT_EQ(a.total.used_regen_J, b.total.used_regen_J);
  EXPECT_LE(c.total.used_regen_J, a.total.used_regen_J);
  ASSERT_EQ(c.per_section.size(), 2u);
  EXPECT_NEAR(c.per_section[0].used_regen_J + c.per_section[1].used_regen_J, c.total.used_regen_J,
              1e-6);
  EXPECT_NEAR(c.per_section[0].traction_J + c.per_section[1].traction_J, c.total.traction_J,
              1e-6 * c.total.traction_J);
}

}  // namespace
}  // namespace ecorail::fleet
