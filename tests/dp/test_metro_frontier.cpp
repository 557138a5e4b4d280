// A metro section's frontier against an independent optimum (issue 24, item 5). A5 -> A6 on the
// reference line: 55 km/h for the first 120 m, 80 km/h, then 70 km/h from 397 m to 1047 m and
// 80 km/h again, over a 6 per mille descent into the lower limit. Its energy-optimal runs are
// "full traction, hold, coast to reach the lower limit at its start, ride it, full traction
// after the rise, hold, coast, brake". The independent optimum is that family searched with the
// simulator alone: for a first hold start h1 (the end of traction, which sets its speed) the
// coast start is bisected so that the run meets the lower limit at its start without braking;
// for a second hold start h2 the final coast is bisected to meet the time; (h1, h2) by a grid
// and then a pattern search down to 1 cm. The solver's frontier (grid, then cruise polish) is
// checked on a dense sweep of times against that optimum.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"
#include "regime_search.hpp"

namespace ecorail {
namespace {

struct MetroCase {
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(data::default_line(), "A5", "A6", train);
  physics::SpeedEnvelope envelope{train, route};
  physics::Motion motion{train, route, envelope};
  double drop_m = 0.0, rise_m = 0.0;
  MetroCase() {
    const auto& segs = route.segments();
    for (std::size_t i = 1; i < segs.size(); ++i) {
      if (drop_m == 0.0 && segs[i].speed_limit_ms < segs[i - 1].speed_limit_ms - 1e-9 &&
          segs[i].start_m > 200.0)
        drop_m = segs[i].start_m;
      if (drop_m > 0.0 && rise_m == 0.0 && segs[i].speed_limit_ms > segs[i - 1].speed_limit_ms)
        rise_m = segs[i].start_m;
    }
  }
};

physics::SimulationResult run(const MetroCase& m, double h1, double c1, double h2, double c2,
                              double step_m) {
  using physics::Control;
  physics::SimulationOptions opt;
  opt.step_m = step_m;
  const physics::ControlProgram p = {{0.0, Control::MaxTraction},
                                     {h1, Control::Hold},
                                     {c1, Control::Coast},
                                     {m.drop_m, Control::Hold},
                                     {m.rise_m, Control::MaxTraction},
                                     {h2, Control::Hold},
                                     {c2, Control::Coast}};
  return physics::simulate(m.motion, p, opt);
}

// The latest coast start after a hold from h1 that does not brake before the lower limit.
double tied_coast_m(const MetroCase& m, double h1, double step_m) {
  const double far_m = m.route.length_m() - 1.0, h2 = m.rise_m + 1.0;
  double lo = h1, hi = m.drop_m - 1e-3;
  if (!test::brakes_by(run(m, h1, hi, h2, far_m, step_m), m.drop_m)) return hi;
  for (int it = 0; it < 20; ++it) {  // 400 m / 2^20: 0.4 mm
    const double mid = 0.5 * (lo + hi);
    (test::brakes_by(run(m, h1, mid, h2, far_m, step_m), m.drop_m) ? hi : lo) = mid;
  }
  return lo;
}

// The energy of the family's run for (h1, h2) that meets target_s (inf when none does).
double family_J(const MetroCase& m, double h1, double c1, double h2, double target_s,
                double step_m) {
  if (!(h1 > 1.0 && h1 < m.drop_m - 1.0 && h2 > m.rise_m && h2 < m.route.length_m() - 2.0))
    return INFINITY;
  auto time_at = [&](double c2) {
    const auto sim = run(m, h1, c1, h2, c2, step_m);
    return dp::run_arrives(sim) ? sim.running_time_s : INFINITY;
  };
  double a = h2, b = m.route.length_m() - 1.0;
  if (!(time_at(a) >= target_s && time_at(b) <= target_s)) return INFINITY;
  for (int it = 0; it < 20; ++it) {  // 1300 m / 2^20: about a millimetre
    const double mid = 0.5 * (a + b);
    (time_at(mid) > target_s ? a : b) = mid;
  }
  return run(m, h1, c1, h2, b, step_m).energy.traction_work_J;
}

struct Optimum {
  double J = INFINITY, h1 = 0.0, h2 = 0.0;
};

// A grid over (h1, h2) with runs at 1 m, then a pattern search down to 1 cm with runs at
// 0.25 m.
Optimum family_optimum(const MetroCase& m, double target_s) {
  Optimum best;
  for (double h1 = 150.0; h1 < m.drop_m - 1.0; h1 += 15.0) {
    const double c1 = tied_coast_m(m, h1, 1.0);
    for (double h2 = m.rise_m + 1.0; h2 < m.rise_m + 400.0; h2 += 25.0) {
      const double e = family_J(m, h1, c1, h2, target_s, 1.0);
      if (e < best.J) best = {e, h1, h2};
    }
  }
  constexpr double kFine_m = 0.25;
  best.J = family_J(m, best.h1, tied_coast_m(m, best.h1, kFine_m), best.h2, target_s, kFine_m);
  for (double step = 8.0; step >= 0.01;) {
    bool moved = false;
    for (const double d1 : {step, -step}) {
      const double h1 = best.h1 + d1;
      const double e = family_J(m, h1, tied_coast_m(m, h1, kFine_m), best.h2, target_s, kFine_m);
      if (e < best.J) best = {e, h1, best.h2}, moved = true;
    }
    const double c1 = tied_coast_m(m, best.h1, kFine_m);
    for (const double d2 : {step, -step}) {
      const double e = family_J(m, best.h1, c1, best.h2 + d2, target_s, kFine_m);
      if (e < best.J) best = {e, best.h1, best.h2 + d2}, moved = true;
    }
    if (!moved) step *= 0.5;
  }
  return best;
}

// Every second from 136 s (the flat-out run takes 134.35 s) to 160 s: each point meets its
// time and the frontier is convex to within 0.001 % of its energy. Before the polish ran on
// this section, 150 s stood 0.26 % above the run found now and the frontier was not convex
// there; before the cruise that rides the lower limit at full traction was polished, 140 s to
// 143 s stood 0.10 % to 0.16 % above it.
TEST(MetroFrontier, EverySecondOfALimitDropSectionIsOnTimeAndConvex) {
  const MetroCase m;
  const dp::SectionEngine engine(m.train, m.route, {});
  dp::FrontierOptions fo;
  fo.t_min_s = 136.0;
  fo.t_max_s = 160.0;
  fo.step_s = 1.0;
  const dp::Frontier f = dp::compute_frontier(engine, fo);
  ASSERT_EQ(f.points.size(), 25u);
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    const dp::FrontierPoint& p = f.points[i];
    EXPECT_TRUE(p.converged) << p.target_time_s;
    EXPECT_NEAR(p.running_time_s, p.target_time_s, 0.01);
    if (i > 0 && i + 1 < f.points.size()) {
      const double second_difference = f.points[i - 1].traction_work_J - 2.0 * p.traction_work_J +
                                       f.points[i + 1].traction_work_J;
      EXPECT_GE(second_difference, -1e-5 * p.traction_work_J)
          << "not convex at " << p.target_time_s;
    }
  }
}

// At every fourth second from 138 s to 158 s the solver's run (a frontier point is the
// stand-alone solve, MinRegime.FrontierPointsAreTheStandAloneSolves) costs no more than the
// family's optimum plus 0.01 %, as issue 24 asks. Measured on every second from 135 s to
// 160 s: +0.0004 % to +0.0036 % (docs/journeys.md, "Cruise polish").
TEST(MetroFrontier, RunsAreWithinAHundredthOfAPercentOfTheFamilyOptimum) {
  const MetroCase m;
  ASSERT_GT(m.drop_m, 0.0);
  ASSERT_GT(m.rise_m, m.drop_m);
  const dp::SectionEngine engine(m.train, m.route, {});
  for (double t = 138.0; t <= 158.0; t += 4.0) {
    const dp::TimeSearchResult r = dp::solve_for_time(engine, t, {});
    const double solver_J = r.run.sim.energy.traction_work_J;
    ASSERT_TRUE(r.converged) << t;
    EXPECT_NEAR(r.run.sim.running_time_s, t, 0.01);
    const Optimum ref = family_optimum(m, t);
    std::printf("%.0f s: solver %.3f kJ (%.4f s), family %.3f kJ (h1 %.2f, h2 %.2f), %+.4f %%\n", t,
                solver_J / 1e3, r.run.sim.running_time_s, ref.J / 1e3, ref.h1, ref.h2,
                100.0 * (solver_J - ref.J) / ref.J);
    ASSERT_TRUE(std::isfinite(ref.J)) << t;
    EXPECT_LE(solver_J, ref.J * (1.0 + 1e-4)) << t << " s";
  }
}

}  // namespace
}  // namespace ecorail
