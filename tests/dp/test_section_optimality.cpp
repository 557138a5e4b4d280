// The single-section engine against an independent regime-switch search, on the reference line.
// Acceptance: running time within 0.1 s after re-simulation, stop within 0.5 m,
// overspeed under 0.05 km/h, and energy never more than 0.1 % above the independent optimum.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <cstdio>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_solve.hpp"
#include "physics/units.hpp"
#include "regime_search.hpp"

namespace ecorail {
namespace {

struct Case {
  const char* from;
  const char* to;
  double time_s;
};

// Printed in test listings as "A6 -> A7 in 110 s", not as raw bytes.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.from << " -> " << c.to << " in " << c.time_s << " s";
}

// The case's section, its solve by the engine with its defaults, and the simulator's motion on
// it for the independent search.
struct SolvedCase {
  physics::Train train = data::default_train();
  physics::Route route;
  dp::SectionSolution sol;
  physics::SpeedEnvelope envelope;
  physics::Motion motion;
  explicit SolvedCase(const Case& c)
      : route(data::build_route(data::default_line(), c.from, c.to, train)),
        sol(dp::solve_section(train, route, c.time_s, {})),
        envelope(train, route),
        motion(train, route, envelope) {}
};

// The test's name for a case: "A6A7_100".
std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.from) + info.param.to + "_" +
         std::to_string(static_cast<int>(info.param.time_s));
}

class SectionOptimality : public ::testing::TestWithParam<Case> {};

TEST_P(SectionOptimality, DpIsNeverWorseThanTheIndependentSearch) {
  const Case c = GetParam();
  const SolvedCase solved(c);
  const dp::SectionSolution& sol = solved.sol;
  const auto& sim = sol.run.sim;
  EXPECT_TRUE(sol.summary.converged());
  EXPECT_NEAR(sim.running_time_s, c.time_s, 0.1);
  EXPECT_LT(std::abs(sim.stop_error_m), 0.5);
  EXPECT_LT(units::ms_to_kmh(sim.max_overspeed_ms), 0.05);

  const test::RegimeSearchResult ref = test::search_regimes(solved.motion, c.time_s, 800.0);
  ASSERT_TRUE(std::isfinite(ref.traction_energy_J));
  EXPECT_NEAR(ref.running_time_s, c.time_s, 0.01);
  const double dp_kJ = units::J_to_kJ(sim.energy.traction_work_J);
  const double ref_kJ = units::J_to_kJ(ref.traction_energy_J);
  std::printf("%s->%s %.0f s: DP %.3f kJ (%.4f s), independent %.3f kJ (%.4f s), diff %+.4f %%\n",
              c.from, c.to, c.time_s, dp_kJ, sim.running_time_s, ref_kJ, ref.running_time_s,
              100.0 * (dp_kJ - ref_kJ) / ref_kJ);
  EXPECT_LE(dp_kJ, ref_kJ * 1.001) << c.from << "->" << c.to << " " << c.time_s << " s";
}

INSTANTIATE_TEST_SUITE_P(ReferenceLine, SectionOptimality,
                         ::testing::Values(Case{"A6", "A7", 100.0}, Case{"A6", "A7", 110.0},
                                           Case{"A6", "A7", 120.0}, Case{"A6", "A7", 130.0},
                                           Case{"A3", "A4", 150.0}, Case{"A12", "A13", 110.0}),
                         case_name);

// Issue 24, item 5: within 0.01 % of the same independent search, at running times where the
// grid's run was polished badly or not at all (frontier version 12 stood 0.013 % to 0.066 %
// above it there, docs/journeys.md): A13 -> A14 at 164 s and 173 s (coasts that touch a lower
// limit and run on below it), A6 -> A7 at 140 s, A7 -> A8 at 135 s and A1 -> A2 at 127 s (a
// cruise broken into holds of a few metres to 150 m among short coasts, none 200 m long),
// A1 -> A2 at 89 s (one short hold), A11 -> A12 at 153 s (a hold's speed and its coast's start
// searched one at a time); A2 -> A3 at 120 s (version 13: +0.011 %, a blip of traction 5 m before
// a limit's rise taken as the acceleration to the higher limit, its cruise polished as a coast).
// The search meets its time to 0.1 ms; the DP's run to its 1 ms tolerance, so its energy is
// compared at the target time by its price (energy + lambda * (time - target), the first-order
// change along the frontier).
class SectionFamilyOptimum : public ::testing::TestWithParam<Case> {};

TEST_P(SectionFamilyOptimum, WithinAHundredthOfAPercentOfTheIndependentSearch) {
  const Case c = GetParam();
  const SolvedCase solved(c);
  const dp::SectionSolution& sol = solved.sol;
  const auto& sim = sol.run.sim;
  ASSERT_TRUE(sol.summary.converged());
  ASSERT_NEAR(sim.running_time_s, c.time_s, 0.001);
  const test::RegimeSearchResult ref =
      test::search_regimes(solved.motion, c.time_s, solved.route.length_m(), 0.5);
  ASSERT_TRUE(std::isfinite(ref.traction_energy_J));
  ASSERT_NEAR(ref.running_time_s, c.time_s, 1e-4);
  const double dp_at_target_J =
      sim.energy.traction_work_J + sol.summary.lambda_J_per_s * (sim.running_time_s - c.time_s);
  std::printf(
      "%s->%s %.0f s: DP %.3f kJ at %.4f s (%.3f kJ at the target), independent %.3f kJ, "
      "diff %+.4f %%\n",
      c.from, c.to, c.time_s, units::J_to_kJ(sim.energy.traction_work_J), sim.running_time_s,
      units::J_to_kJ(dp_at_target_J), units::J_to_kJ(ref.traction_energy_J),
      100.0 * (dp_at_target_J - ref.traction_energy_J) / ref.traction_energy_J);
  EXPECT_LE(dp_at_target_J, ref.traction_energy_J * 1.0001);
}

INSTANTIATE_TEST_SUITE_P(ReferenceLine, SectionFamilyOptimum,
                         ::testing::Values(Case{"A13", "A14", 164.0}, Case{"A13", "A14", 173.0},
                                           Case{"A6", "A7", 140.0}, Case{"A7", "A8", 135.0},
                                           Case{"A1", "A2", 89.0}, Case{"A1", "A2", 127.0},
                                           Case{"A11", "A12", 153.0}, Case{"A2", "A3", 120.0}),
                         case_name);

}  // namespace
}  // namespace ecorail
