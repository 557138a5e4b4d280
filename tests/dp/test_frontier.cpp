// Energy-time frontiers: decreasing, convex where the optimum is unique, starting at the
// flat-out run, every point on time after re-simulation, and the cache format round-trips.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "output/frontier_io.hpp"

namespace ecorail {
namespace {

TEST(Frontier, DecreasingConvexAndOnTime) {
  const physics::Train train = data::default_train();
  for (auto [from, to] : {std::pair{"A6", "A7"}, std::pair{"A3", "A4"}}) {
    const physics::Route route = data::build_route(data::default_line(), from, to, train);
    const dp::SectionEngine engine(train, route, {});
    dp::FrontierOptions fo;
    fo.t_max_s = engine.min_time_run().running_time_s + 40.0;
    fo.step_s = 2.0;
    const dp::Frontier f = dp::compute_frontier(engine, fo);
    ASSERT_GE(f.points.size(), 20u);
    EXPECT_NEAR(f.points.front().running_time_s, f.min_time_s, 1e-9);
    EXPECT_TRUE(f.monotone) << from;
    for (std::size_t k = 1; k < f.points.size(); ++k) {
      const auto& p = f.points[k];
      EXPECT_TRUE(p.converged) << from << " " << p.target_time_s;
      EXPECT_NEAR(p.running_time_s, p.target_time_s, 0.1);
      EXPECT_LT(p.cost_J, f.points[k - 1].cost_J) << from << " " << p.target_time_s;
    }
    // Convex: the slopes rise, to within 0.01 % of the energy per step.
    for (std::size_t k = 1; k + 1 < f.points.size(); ++k) {
      const auto& a = f.points[k - 1];
      const auto& b = f.points[k];
      const auto& c = f.points[k + 1];
      const double left = (b.cost_J - a.cost_J) / (b.running_time_s - a.running_time_s);
      const double right = (c.cost_J - b.cost_J) / (c.running_time_s - b.running_time_s);
      EXPECT_GE(right - left, -1e-4 * b.cost_J / (c.running_time_s - b.running_time_s))
          << from << " at " << b.target_time_s;
    }
  }
}

TEST(Frontier, CacheFormatRoundTrips) {
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(data::default_line(), "A9", "A10", train);
  const dp::SectionEngine engine(train, route, {});
  dp::FrontierOptions fo;
  fo.t_max_s = engine.min_time_run().running_time_s + 6.0;
  output::LabelledFrontier lf{"A9", "A10", dp::compute_frontier(engine, fo)};
  const output::LabelledFrontier back = output::frontier_from_json(output::frontier_json(lf));
  ASSERT_EQ(back.frontier.points.size(), lf.frontier.points.size());
  for (std::size_t k = 0; k < lf.frontier.points.size(); ++k) {
    EXPECT_NEAR(back.frontier.points[k].cost_J, lf.frontier.points[k].cost_J, 1e-6);
    EXPECT_EQ(back.frontier.points[k].running_time_s, lf.frontier.points[k].running_time_s);
  }
  EXPECT_TRUE(std::isinf(back.frontier.points.front().lambda_J_per_s));
}

TEST(Frontier, ShapeCheckFlagsAWobble) {
  dp::Frontier f;
  f.points = {{100, 100, 0, 0, 0, 30e6, 0, true, 1},
              {101, 101, 0, 0, 0, 29e6, 0, true, 1},
              {102, 102, 0, 0, 0, 29.1e6, 0, true, 1},
              {103, 103, 0, 0, 0, 27e6, 0, true, 1}};
  dp::check_frontier_shape(f, 1e-5);
  EXPECT_FALSE(f.monotone);
  EXPECT_FALSE(f.convex);
  EXPECT_GE(f.wobbles.size(), 2u);
}

}  // namespace
}  // namespace ecorail
