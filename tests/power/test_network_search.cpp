// The network model's searches and bound (energy/network_bound.hpp, the headway search with the
// network model, pattern_search.hpp) on the small fleet (the reference train on A6 -> A9): the
// bound never exceeds the best timetable found by enumerating every timetable of 3- and 4-train
// fleets (diode supplies with and without auxiliaries, a reversible one, a high-resistance one);
// with zero resistance and no auxiliaries it is the power-flow pair bound's; the optimiser keeps
// peak-hour headway classes, its result evaluates to the same energy and is above the bound;
// the pattern search under the network model is never worse than the headways alone and keeps
// the trip time and the dwell range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "energy/fleet_energy_model.hpp"
#include "energy/network_bound.hpp"
#include "energy/pair_bound.hpp"
#include "energy/window_bound.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet/pattern_search.hpp"
#include "fleet/regime_start.hpp"
#include "power/network_balance.hpp"
#include "tests/fleet/fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

using testing::small_fleet;
using testing::small_library;
using testing::small_pattern;

std::shared_ptr<power::PowerSupply> supply(double r_per_km, double aux_W, bool reversible) {
  auto s = std::make_shared<power::PowerSupply>();
  s->substations = {{"S1", 0.0, 835.0, 0.015, reversible}, {"S2", 2500.0, 835.0, 0.015, false}};
  s->conductors = {{0.0, r_per_km * 0.4, r_per_km * 0.6}};
  s->max_train_voltage_V = 900.0;
  s->min_train_voltage_V = 500.0;
  s->auxiliary_power_W = aux_W;
  return s;
}

EnergyModelOptions network(std::shared_ptr<const power::PowerSupply> s, double step_s) {
  EnergyModelOptions o;
  o.model = "network";
  o.time_step_s = step_s;
  o.power_supply = std::move(s);
  return o;
}

// Every timetable of the problem (whole-second headways in range summing to the span).
void for_each_timetable(const FleetProblem& p, const std::function<void(std::vector<int>)>& f) {
  std::vector<int> h;
  std::function<void(int)> rec = [&](int left) {
    if (static_cast<int>(h.size()) == p.trains - 2) {
      if (left >= p.headway_min_s && left <= p.headway_max_s) {
        h.push_back(left);
        f(departures_from_headways(h));
        h.pop_back();
      }
      return;
    }
    for (int x = p.headway_min_s; x <= p.headway_max_s && x <= left; ++x) {
      h.push_back(x);
      rec(left - x);
      h.pop_back();
    }
  };
  rec(p.span_s);
}

// min over every timetable of substation + curtailed traction energy (J), on a 1 s grid.
double brute_force_minimum(const FleetProblem& p, const power::PowerSupply& s,
                           const NetworkProfile& profile, int* count) {
  NetworkBalance balance(profile, s, 1.0, p.trains,
                         p.span_s + small_pattern().trip.arrival_s() + 10.0, 1);
  double best = std::numeric_limits<double>::infinity();
  *count = 0;
  for_each_timetable(p, [&](const std::vector<int>& t) {
    balance.place_all(t);
    ASSERT_EQ(balance.unsolved_bins(), 0) << "departures " << t[1] << " " << t[2];
    best = std::min(best, to_joules(balance.substation() + balance.total().curtailed_traction));
    ++*count;
  });
  return best;
}

TEST(NetworkBound, NeverAboveTheBruteForceOptimum) {
  const NetworkProfile profile(small_pattern().trip, 1);
  struct Case {
    const char* name;
    std::shared_ptr<power::PowerSupply> s;
    FleetProblem p;
  };
  const std::vector<Case> cases = {
      {"rails, auxiliaries, 4 trains", supply(0.023, 1.5e5, false), small_fleet(4, 50, 100, 225)},
      {"rails, no auxiliaries", supply(0.023, 0.0, false), small_fleet(3, 30, 150, 160)},
      {"reversible substation", supply(0.023, 1.5e5, true), small_fleet(3, 30, 150, 160)},
      {"high resistance", supply(0.15, 5e4, false), small_fleet(3, 30, 150, 160)},
  };
  for (const Case& c : cases) {
    const NetworkBound b = network_substation_bound(profile, *c.s, 1.0, limits_of(c.p));
    int count = 0;
    const double best = brute_force_minimum(c.p, *c.s, profile, &count);
    EXPECT_GT(count, 50) << c.name;
    EXPECT_LE(b.substation_J, best) << c.name;
    // Without auxiliaries (or with few), the window bound is the tighter cap on the reuse.
    if (c.s->auxiliary_power_W < 1e5) {
      EXPECT_TRUE(b.window_bound) << c.name;
    }
    // The bound's parts: the demand is every timetable's, the reuse at most the regeneration.
    EXPECT_NEAR(b.demand_J,
                c.p.trains * (profile.traction_total_J() +
                              c.s->auxiliary_power_W * profile.presence_total_s()),
                1e-6 * b.demand_J)
        << c.name;
    EXPECT_LE(b.reuse_cap_J, b.regen_J * (1 + 1e-12)) << c.name;
    // Not vacuous where losses are modest (the bound has no losses).
    if (c.s->conductors[0].conductor_ohm_per_km < 0.05) {
      EXPECT_GT(b.substation_J, 0.9 * best) << c.name;
    }
  }
  // With a reversible substation only the total regeneration caps the reuse.
  const NetworkBound rev =
      network_substation_bound(profile, *supply(0.023, 1.5e5, true), 1.0, limits_of(cases[2].p));
  EXPECT_FALSE(rev.pair_bound);
  EXPECT_DOUBLE_EQ(rev.substation_J, rev.demand_J - rev.regen_J);
}

TEST(NetworkBound, ZeroResistanceAndNoAuxiliariesIsThePowerFlowBound) {
  // The network is then one bus, the power-flow model exactly: its bound is traction less the
  // tighter of the power-flow pair and window bounds of the same trip on the same grid (dense
  // trains, where the total regeneration caps both, and sparse ones, where the window bound
  // does).
  const NetworkProfile profile(small_pattern().trip, 10);
  const PowerProfile pf(small_pattern().trip, 10, {});
  for (const FleetProblem& p : {small_fleet(8, 40, 120, 550), small_fleet(3, 30, 150, 160)}) {
    const NetworkBound b =
        network_substation_bound(profile, *supply(0.0, 0.0, false), 1.0, limits_of(p));
    const PairBound pair = used_regen_bound(pf, limits_of(p));
    const energy::WindowBound window = energy::window_used_regen_bound(pf, limits_of(p));
    ASSERT_TRUE(window.applicable);
    const double regen_J = p.trains * profile.regen_total_J();
    const double cap = std::min({pair.bound_used_J, window.bound_used_J, regen_J});
    EXPECT_NEAR(b.reuse_cap_J, cap, 1e-6 * cap) << p.trains;
    EXPECT_NEAR(b.substation_J, p.trains * profile.traction_total_J() - cap, 1e-6 * b.substation_J)
        << p.trains;
    if (p.trains == 3) {
      EXPECT_LT(window.bound_used_J, std::min(pair.bound_used_J, regen_J));
    }
  }
}

HeadwayOptimiserOptions cheap_search() {
  HeadwayOptimiserOptions o;
  o.restarts = 1;
  o.moves_per_run = 200;
  o.polish_window_s = 4;
  o.threads = 2;
  return o;
}

TEST(NetworkOptimiser, WindowedDayKeepsTheClassesAndEvaluatesConsistently) {
  FleetProblem p = small_fleet(8, 200, 400, 1800);
  p.trip_time_s = 480.0;
  p.peak_windows = {{300, 700}};
  p.peak_headway_min_s = 120;
  p.peak_headway_max_s = 150;
  const TestFleet models(small_pattern().trip, p, network(supply(0.023, 1.5e5, false), 0.5));
  const HeadwayOptimiserResult r = optimise_headways(models, cheap_search());
  ASSERT_TRUE(r.summary.IsSolutionUsable());
  const std::vector<int>& t = r.evaluation.departures_s;
  EXPECT_EQ(departures_problem(p, t), "");
  int peak = 0;
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const int h = t[k + 1] - t[k];
    const bool in_peak = t[k] < 700 && t[k + 1] > 300;
    peak += in_peak;
    EXPECT_TRUE(in_peak ? (h >= 120 && h <= 150) : (h >= 200 && h <= 400)) << k << " " << h;
  }
  EXPECT_GE(peak, 3);
  EXPECT_EQ(headways_from_departures(t), r.headways_s);
  // The same departures evaluated afresh give the same energy.
  const FleetEvaluation again = models.evaluate(departures_from_headways(r.headways_s));
  EXPECT_EQ(again.network->substation_J, r.evaluation.network->substation_J);
  // Never worse than the uniform timetable it starts from, and above the bound.
  const FleetEvaluation uniform = models.evaluate(departures_from_headways(uniform_headways(p)));
  EXPECT_LE(r.summary.substation_J, uniform.total.substation_J() + 1e-6);
  // It starts from the periodic regimes too, built on the power-flow model (the network's start
  // proxy), so it is never worse than that start evaluated on the network.
  EXPECT_NE(r.summary.method.find("periodic regimes"), std::string::npos) << r.summary.method;
  EXPECT_NE(r.summary.method.find("of the power-flow model"), std::string::npos);
  const std::unique_ptr<energy::FleetEnergyModel> proxy = models.model().start_proxy();
  ASSERT_NE(proxy, nullptr);
  const RegimeStart start =
      build_regime_start(*proxy->on_grid(cheap_search().anneal_step_s), p, 2, proxy.get());
  ASSERT_FALSE(start.departures_s.empty());
  EXPECT_LE(r.summary.substation_J,
            models.evaluate(start.departures_s).total.substation_J() + 1e-6);
  ASSERT_TRUE(std::isfinite(r.summary.bound_substation_J));
  EXPECT_LE(r.summary.bound_substation_J, r.summary.substation_J + r.summary.curtailed_traction_J);
  EXPECT_GE(r.summary.gap_fraction, 0.0);
}

TEST(NetworkPatternSearch, NeverWorseThanHeadwaysAloneAndKeepsTheTrip) {
  FleetProblem p = small_fleet(6, 150, 250, 1000);
  p.trip_time_s = 480.0;
  const EnergyModelOptions model = network(supply(0.023, 1.5e5, false), 1.0);
  PatternSearchOptions o;
  o.headways = cheap_search();
  o.deltas_s = {2.0};
  o.max_moves = 2;
  o.headways.threads = 2;
  const PatternSearchResult r = optimise_pattern(small_library(), p, model, small_pattern(), o);
  const double after = r.timetable.evaluation.total.substation_J();
  EXPECT_LE(after, r.headways_only.total.substation_J() + 1e-6);
  EXPECT_GT(r.patterns_evaluated, 0);
  for (double d : r.pattern.pattern.dwells_s) {
    EXPECT_GE(d, p.dwell_min_s);
    EXPECT_LE(d, p.dwell_max_s);
  }
  EXPECT_NEAR(r.pattern.pattern.trip_time_s(), p.trip_time_s, 0.05);
  EXPECT_NEAR(r.pattern.trip.stops().back().arrival_s, p.trip_time_s, 0.05);
  // The result is the network evaluation of its own pattern and departures.
  const FleetEvaluation again =
      TestFleet(r.pattern.trip, p, model).evaluate(r.timetable.evaluation.departures_s);
  ASSERT_TRUE(again.network);
  EXPECT_EQ(again.network->substation_J, r.timetable.evaluation.network->substation_J);
  // Per-train patterns are refused for this model, with the reason.
  o.per_train_patterns = true;
  EXPECT_THROW(optimise_pattern(small_library(), p, model, small_pattern(), o),
               std::invalid_argument);
}

}  // namespace
}  // namespace ecorail::fleet
