// Properties of the single-section engine that must hold whatever the grid: energy falls
// strictly with the allowed time, results do not depend on the thread count, coasting arcs are
// the closed-form coasting curve, impossible times are refused with the minimum named.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_solve.hpp"
#include "physics/coasting.hpp"
#include "physics/units.hpp"

namespace ecorail {
namespace {

struct Fixture {
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
};

TEST(SectionProperties, EnergyFallsStrictlyAsTimeGrows) {
  const Fixture f;
  double previous = INFINITY;
  for (double t : {100.0, 110.0, 120.0, 130.0}) {
    const auto sol = dp::solve_section(f.train, f.route, t, {});
    const double e = sol.run.sim.energy.traction_work_J;
    EXPECT_LT(e, previous * 0.99) << t;  // strictly, and by a visible margin
    previous = e;
  }
}

TEST(SectionProperties, SameAnswerWithOneAndTwoThreads) {
  const Fixture f;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = dp::solve_section(f.train, f.route, 110.0, {});
  omp_set_num_threads(2);
  const auto two = dp::solve_section(f.train, f.route, 110.0, {});
  omp_set_num_threads(saved);
  EXPECT_EQ(one.run.lambda, two.run.lambda);
  EXPECT_EQ(one.run.sim.energy.traction_work_J, two.run.sim.energy.traction_work_J);
  EXPECT_EQ(one.run.sim.running_time_s, two.run.sim.running_time_s);
  ASSERT_EQ(one.run.program.size(), two.run.program.size());
  for (std::size_t k = 0; k < one.run.program.size(); ++k) {
    EXPECT_EQ(one.run.program[k].from_m, two.run.program[k].from_m);
  }
}

TEST(SectionProperties, TimeBelowMinimumIsRefusedNamingTheMinimum) {
  const Fixture f;
  dp::SectionEngine engine(f.train, f.route, {});
  const double t_min = engine.min_time_run().running_time_s;
  EXPECT_GT(t_min, 80.0);
  EXPECT_LT(t_min, 90.0);
  try {
    dp::solve_for_time(engine, t_min - 1.0, {});
    FAIL() << "expected InfeasibleTimeError";
  } catch (const dp::InfeasibleTimeError& e) {
    EXPECT_NEAR(e.minimum_s(), t_min, 1e-9);
    EXPECT_NE(std::string(e.what()).find("minimum running time"), std::string::npos);
  }
  // Just above the minimum is feasible and lands on time.
  const auto near = dp::solve_for_time(engine, t_min + 0.5, {});
  EXPECT_NEAR(near.run.sim.running_time_s, t_min + 0.5, 0.1);
}

TEST(SectionProperties, CoastingArcsFollowTheClosedFormCurve) {
  const Fixture f;
  const auto sol = dp::solve_section(f.train, f.route, 120.0, {});
  int checked = 0;
  for (const auto& span : sol.regimes) {
    if (span.regime != physics::Regime::Coast || span.end_m - span.start_m < 100.0) continue;
    // Within each route segment crossed by the coast, predict the speed from the first trace
    // point inside it with the closed form.
    for (const auto& seg : f.route.segments()) {
      const double a = std::max(seg.start_m, span.start_m) + 1.0;
      const double b = std::min(seg.end_m, span.end_m) - 1.0;
      if (b - a < 20.0) continue;
      const physics::CoastingCurve curve(f.train, seg.track_N_per_kN());
      const physics::TracePoint* first = nullptr;
      for (const auto& p : sol.run.sim.trace) {
        if (p.s_m < a || p.s_m > b) continue;
        if (!first) {
          first = &p;
          continue;
        }
        const double v = curve.speed_after_m(first->v_ms, p.s_m - first->s_m);
        ASSERT_NEAR(p.v_ms, v, 1e-6 * v) << "at " << p.s_m << " m";
        const double t = curve.time_after_m(first->v_ms, p.s_m - first->s_m);
        ASSERT_NEAR(p.t_s - first->t_s, t, 1e-6 * std::max(1.0, t));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);  // a long coast was found and checked point by point
}

TEST(SectionProperties, NetObjectiveNeverCostsMoreNetEnergy) {
  const Fixture f;
  dp::SectionSolveOptions net;
  net.engine.objective = dp::Objective::Net;
  const auto a = dp::solve_section(f.train, f.route, 110.0, {});
  const auto b = dp::solve_section(f.train, f.route, 110.0, net);
  EXPECT_LE(b.run.sim.energy.net_J(), a.run.sim.energy.net_J() * (1.0 + 1e-4));
  EXPECT_NEAR(b.run.sim.running_time_s, 110.0, 0.1);
}

TEST(SectionProperties, CoarseGridIsWithinATenthOfAPercentOfTheDefault) {
  const Fixture f;
  dp::SectionSolveOptions coarse;
  coarse.engine.grid = {10.0, 0.5, 5.0};
  const auto a = dp::solve_section(f.train, f.route, 110.0, {});
  const auto b = dp::solve_section(f.train, f.route, 110.0, coarse);
  EXPECT_NEAR(b.run.sim.energy.traction_work_J, a.run.sim.energy.traction_work_J,
              1e-3 * a.run.sim.energy.traction_work_J);
}

}  // namespace
}  // namespace ecorail
