// Journeys over several sections: the total running time is met after re-simulation, the
// optimal split equalises the sections' measured marginal energy per second with the common
// lambda, it beats the proportional split, and it is no worse than an independent scan over
// the split built from each section's own frontier.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/journey.hpp"

namespace ecorail {
namespace {

std::vector<physics::Route> routes_between(const physics::Train& train, const char* from,
                                           const char* to) {
  const data::Line line = data::default_line();
  const auto stops = data::stops_between(line, from, to);
  std::vector<physics::Route> routes;
  for (std::size_t i = 0; i + 1 < stops.size(); ++i) {
    routes.push_back(data::build_route(line, stops[i], stops[i + 1], train));
  }
  return routes;
}

TEST(Journey, A6ToA8OptimalSplitEqualisesMarginalsAndBeatsProportional) {
  const physics::Train train = data::default_train();
  const auto routes = routes_between(train, "A6", "A8");
  ASSERT_EQ(routes.size(), 2u);
  const dp::JourneySolution opt = dp::solve_journey(train, routes, {45.0}, 220.0, {});
  EXPECT_TRUE(opt.converged());
  EXPECT_NEAR(opt.running_time_s, 220.0, 0.1);
  for (const auto& s : opt.sections) {
    EXPECT_LT(std::abs(s.run.sim.stop_error_m), 0.5);
    ASSERT_TRUE(std::isfinite(s.marginal_J_per_s));
    // Each section's measured marginal energy per second agrees with the common lambda.
    EXPECT_NEAR(s.marginal_J_per_s / opt.lambda_J_per_s, 1.0, 0.05);
  }
  // ... and with each other, more tightly.
  EXPECT_NEAR(opt.sections[0].marginal_J_per_s / opt.sections[1].marginal_J_per_s, 1.0, 0.02);

  dp::JourneyOptions prop;
  prop.split = dp::Split::Proportional;
  prop.measure_marginals = false;
  const dp::JourneySolution p = dp::solve_journey(train, routes, {45.0}, 220.0, prop);
  EXPECT_NEAR(p.running_time_s, 220.0, 0.1);
  EXPECT_LE(opt.traction_work_J, p.traction_work_J);
  std::printf("A6->A8 220 s: optimal %.3f kJ (%.3f + %.3f s), proportional %.3f kJ\n",
              opt.traction_work_J / 1e3, opt.sections[0].run.sim.running_time_s,
              opt.sections[1].run.sim.running_time_s, p.traction_work_J / 1e3);
}

TEST(Journey, A6ToA8IsNoWorseThanAScanOverTheSplit) {
  // Independent of the lambda coupling: tabulate each section's frontier at 0.5 s steps and
  // take the best split of 220 s between them, refined by a parabola through the best three.
  const physics::Train train = data::default_train();
  const auto routes = routes_between(train, "A6", "A8");
  std::vector<dp::Frontier> fronts;
  for (const auto& r : routes) {
    const dp::SectionEngine engine(train, r, {});
    dp::FrontierOptions fo;
    fo.t_min_s = 100.0;
    fo.t_max_s = 120.0;
    fo.step_s = 0.5;
    fronts.push_back(dp::compute_frontier(engine, fo));
  }
  auto energy_at = [](const dp::Frontier& f, double t) -> double {
    for (const auto& p : f.points) {
      if (std::abs(p.target_time_s - t) < 1e-6) return p.traction_work_J;
    }
    return INFINITY;
  };
  double best = INFINITY, best_t = 0.0;
  std::vector<std::pair<double, double>> scan;
  for (double t1 = 100.0; t1 <= 120.0 + 1e-9; t1 += 0.5) {
    const double e = energy_at(fronts[0], t1) + energy_at(fronts[1], 220.0 - t1);
    scan.emplace_back(t1, e);
    if (e < best) best = e, best_t = t1;
  }
  ASSERT_TRUE(std::isfinite(best));
  ASSERT_GT(best_t, 100.0);  // an interior minimum
  ASSERT_LT(best_t, 120.0);
  const dp::JourneySolution opt = dp::solve_journey(train, routes, {45.0}, 220.0, {});
  EXPECT_LE(opt.traction_work_J, best * 1.001);
  EXPECT_NEAR(opt.sections[0].run.sim.running_time_s, best_t, 1.0);
  std::printf("split scan: best %.3f kJ at %.1f s; journey %.3f kJ at %.3f s\n", best / 1e3, best_t,
              opt.traction_work_J / 1e3, opt.sections[0].run.sim.running_time_s);
}

TEST(Journey, FullLineOptimalSplitSavesSeveralPercent) {
  const physics::Train train = data::default_train();
  const auto routes = routes_between(train, "A1", "A14");
  ASSERT_EQ(routes.size(), 13u);
  const std::vector<double> dwells(12, 30.0);
  dp::JourneyOptions options;
  options.measure_marginals = false;
  const auto opt = dp::solve_journey(train, routes, dwells, 1726.0, options);
  EXPECT_TRUE(opt.converged());
  EXPECT_NEAR(opt.running_time_s, 1726.0, 0.1);
  ASSERT_EQ(opt.sections.size(), 13u);
  for (const auto& s : opt.sections) EXPECT_LT(std::abs(s.run.sim.stop_error_m), 0.5);
  options.split = dp::Split::Proportional;
  const auto prop = dp::solve_journey(train, routes, dwells, 1726.0, options);
  EXPECT_NEAR(prop.running_time_s, 1726.0, 0.1);
  const double gap = prop.traction_work_J / opt.traction_work_J - 1.0;
  EXPECT_GT(gap, 0.02);  // several per cent, not rounding
  std::printf("A1->A14 1726 s: optimal %.1f kJ, proportional %.1f kJ (+%.2f %%)\n",
              opt.traction_work_J / 1e3, prop.traction_work_J / 1e3, 100.0 * gap);
}

TEST(Journey, TooShortATotalTimeIsRefused) {
  const physics::Train train = data::default_train();
  const auto routes = routes_between(train, "A6", "A8");
  EXPECT_THROW(dp::solve_journey(train, routes, {45.0}, 150.0, {}), dp::InfeasibleTimeError);
}

}  // namespace
}  // namespace ecorail
