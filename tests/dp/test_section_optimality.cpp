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

class SectionOptimality : public ::testing::TestWithParam<Case> {};

TEST_P(SectionOptimality, DpIsNeverWorseThanTheIndependentSearch) {
  const Case c = GetParam();
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(data::default_line(), c.from, c.to, train);
  const dp::SectionSolution sol = dp::solve_section(train, route, c.time_s, {});
  const auto& sim = sol.run.sim;
  EXPECT_TRUE(sol.summary.converged());
  EXPECT_NEAR(sim.running_time_s, c.time_s, 0.1);
  EXPECT_LT(std::abs(sim.stop_error_m), 0.5);
  EXPECT_LT(units::ms_to_kmh(sim.max_overspeed_ms), 0.05);

  const physics::SpeedEnvelope envelope(train, route);
  const physics::Motion motion(train, route, envelope);
  const test::RegimeSearchResult ref = test::search_regimes(motion, c.time_s, 800.0);
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
                         [](const auto& info) {
                           return std::string(info.param.from) + info.param.to + "_" +
                                  std::to_string(static_cast<int>(info.param.time_s));
                         });

}  // namespace
}  // namespace ecorail
