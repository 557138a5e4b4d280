// SectionLibrary and FrontierCurve: interpolation that keeps the frontier's shape and is within
// 0.01 % of exact solves at the default step, prices that invert exactly, engines and frontiers
// built once (a second solve rebuilds nothing), a frontier store that is used only when sound,
// and options checked before any work.
#include <gtest/gtest.h>

#include <iterator>

#include <cmath>
#include <map>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"

namespace ecorail::dp {
namespace {

// A frontier of points on a known convex, decreasing function E = a / (T - c) + b.
Frontier synthetic_frontier(double step) {
  Frontier f;
  for (double t = 80.0; t <= 140.0 + 1e-9; t += step) {
    FrontierPoint p;
    p.running_time_s = p.target_time_s = t;
    p.cost_J = 4e8 / (t - 60.0) + 1e7;
    f.points.push_back(p);
  }
  return f;
}

TEST(FrontierCurve, KeepsShapeAndIsCloseOnAKnownCurve) {
  const FrontierCurve curve(synthetic_frontier(1.0));
  double previous_e = INFINITY, previous_slope = -INFINITY;
  for (double t = 80.0; t <= 140.0; t += 0.05) {
    const double e = curve.energy_at(t);
    const double slope = -curve.marginal_at(t);
    EXPECT_LT(e, previous_e + 1e-6) << t;          // decreasing
    EXPECT_GE(slope, previous_slope - 1e-6) << t;  // convex: the slope never falls
    EXPECT_LE(slope, 0.0);
    EXPECT_NEAR(e, 4e8 / (t - 60.0) + 1e7, 1e-4 * e) << t;
    previous_e = e;
    previous_slope = slope;
  }
}

TEST(FrontierCurve, TimeForMarginalInvertsMarginalAt) {
  const FrontierCurve curve(synthetic_frontier(1.0));
  for (double t = 80.5; t < 140.0; t += 3.7) {
    EXPECT_NEAR(curve.time_for_marginal(curve.marginal_at(t)), t, 1e-6) << t;
  }
  EXPECT_EQ(curve.time_for_marginal(1e12), curve.t_min_s());
  EXPECT_EQ(curve.time_for_marginal(0.0), curve.t_max_s());
  EXPECT_THROW(curve.energy_at(70.0), std::out_of_range);
}

// The first points of A3 -> A4's frontier (s, kJ; the first is the flat-out run): the energy
// falls little over the first 0.11 s and then steeply, so the curve is not convex there and its
// marginal dips just after t_min. The time for a price must still minimise E(t) + lambda t
// (checked against a fine scan) and fall as the price rises; it once returned t_min + 0.01 s
// for every price from 0.5 to 20 MJ/s.
TEST(FrontierCurve, TimeForMarginalMinimisesTheLagrangianWhereTheCurveWobbles) {
  const double t[] = {118.339, 118.450, 118.589, 118.784, 118.999, 119.339, 119.700,
                      120.339, 121.339, 122.339, 124.339, 128.339, 134.339, 142.339};
  const double e_kJ[] = {70983.1, 69986.1, 67180.2, 66022.6, 65015.3, 63709.3, 62533.2,
                         60783.1, 58500.0, 56663.0, 53197.3, 47227.9, 39994.1, 32567.6};
  Frontier f;
  f.min_time_s = t[0];
  for (std::size_t i = 0; i < std::size(t); ++i) {
    FrontierPoint p;
    p.target_time_s = p.running_time_s = t[i];
    p.cost_J = e_kJ[i] * 1e3;
    p.lambda_J_per_s = i == 0 ? INFINITY : 1.0;
    p.converged = true;
    f.points.push_back(p);
  }
  const FrontierCurve curve(f);
  double previous = curve.t_max_s();
  for (double lambda : {300e3, 500e3, 1000e3, 1700e3, 3000e3, 9000e3, 20000e3}) {
    const double found = curve.time_for_marginal(lambda);
    double best = INFINITY;
    for (double x = curve.t_min_s(); x <= curve.t_max_s(); x += 0.001)
      best = std::min(best, curve.energy_at(x) + lambda * x);
    EXPECT_LE(curve.energy_at(found) + lambda * found, best + 1e-6 * std::abs(best)) << lambda;
    EXPECT_LE(found, previous + 1e-9) << lambda;  // a higher price never buys a longer time
    previous = found;
  }
  EXPECT_GT(curve.time_for_marginal(1700e3), 120.0);  // not stuck at t_min
}

TEST(FrontierCurve, RejectsTimesThatDoNotIncrease) {
  Frontier f = synthetic_frontier(1.0);
  f.points[3].running_time_s = f.points[2].running_time_s;
  EXPECT_THROW(FrontierCurve{f}, std::invalid_argument);
}

std::vector<physics::Route> library_routes(const physics::Train& train,
                                           const std::vector<std::string>& stops) {
  return data::build_routes(data::default_line(), stops, train);
}

// Between frontier points (default 1 s step) the curve is within 0.01 % of an exact solve.
TEST(SectionLibrary, FrontierInterpolationWithinOneBasisPointOfExactSolves) {
  const physics::Train train = data::default_train();
  SectionLibraryOptions options;
  options.frontier_span_s = 30.0;
  const SectionLibrary library(train, library_routes(train, {"A6", "A7", "A8"}), options);
  library.build_frontiers(0, 2, nullptr);
  for (std::size_t i = 0; i < 2; ++i) {
    const FrontierCurve& curve = library.frontier(i);
    const double t_min = library.min_time_s(i);
    EXPECT_NEAR(curve.t_min_s(), t_min, 1e-9);
    EXPECT_GT(curve.t_max_s(), t_min + 29.0);  // the last whole step within the span
    EXPECT_LE(curve.t_max_s(), t_min + 30.0 + 0.01);
    for (double offset : {0.5, 1.2, 1.5, 2.5, 4.5, 12.5, 27.5}) {
      const double t = std::floor(t_min) + offset;
      const SectionTimeSolve exact = library.solve(i, t);
      ASSERT_TRUE(exact.search.converged);
      const double e = library.engine(i).energy_cost_J(exact.search.run.sim);
      EXPECT_NEAR(curve.energy_at(exact.search.run.sim.running_time_s), e, 1e-4 * e)
          << library.route(i).from_name() << " at " << t << " s";
    }
  }
}

TEST(SectionLibrary, SecondSolveRebuildsNothing) {
  const physics::Train train = data::default_train();
  const SectionLibrary library(train, library_routes(train, {"A6", "A7"}), {});
  EXPECT_EQ(library.engine_builds(), 0);  // nothing before first use
  const SectionTimeSolve first = library.solve(0, 110.0);
  EXPECT_EQ(library.engine_builds(), 1);
  const SectionTimeSolve second = library.solve(0, 120.0);
  EXPECT_EQ(library.engine_builds(), 1);
  EXPECT_LT(library.engine(0).energy_cost_J(second.search.run.sim),
            library.engine(0).energy_cost_J(first.search.run.sim));
  // The trip of an exact-time solve is the run itself.
  EXPECT_NEAR(first.trip.arrival_s(), first.search.run.sim.running_time_s, 1e-9);
  EXPECT_NEAR(first.trip.ledger().traction_work_J, first.search.run.sim.energy.traction_work_J,
              1e-6);
}

// An in-memory store that can also hand out a damaged entry.
class MemoryStore : public FrontierStore {
 public:
  std::optional<Frontier> load(const std::string& key) override {
    ++loads;
    auto it = entries.find(key);
    if (it == entries.end()) return std::nullopt;
    return it->second;
  }
  void save(const std::string& key, const Frontier& f) override { entries[key] = f; }
  std::map<std::string, Frontier> entries;
  int loads = 0;
};

TEST(SectionLibrary, StoredFrontierIsUsedUnderItsKeyAndDamagedOneIsRebuilt) {
  const physics::Train train = data::default_train();
  SectionLibraryOptions options;
  options.frontier_span_s = 6.0;
  MemoryStore store;
  const SectionLibrary first(train, library_routes(train, {"A6", "A7"}), options, "line|train");
  const double e = first.frontier(0, &store).energy_at(first.min_time_s(0) + 3.0);
  EXPECT_EQ(first.frontier_computations(), 1);
  ASSERT_EQ(store.entries.size(), 1u);

  const SectionLibrary second(train, library_routes(train, {"A6", "A7"}), options, "line|train");
  EXPECT_DOUBLE_EQ(second.frontier(0, &store).energy_at(second.min_time_s(0) + 3.0), e);
  EXPECT_EQ(second.frontier_computations(), 0);
  EXPECT_TRUE(second.frontier_from_store(0));

  // Another train (key) does not see it; a damaged entry is recomputed.
  const SectionLibrary other(train, library_routes(train, {"A6", "A7"}), options,
                             "line|other-train");
  EXPECT_NE(other.frontier_key(0), first.frontier_key(0));
  store.entries.begin()->second.points[1].running_time_s = -1.0;
  const SectionLibrary third(train, library_routes(train, {"A6", "A7"}), options, "line|train");
  EXPECT_NEAR(third.frontier(0, &store).energy_at(third.min_time_s(0) + 3.0), e, 1e-9 * e);
  EXPECT_EQ(third.frontier_computations(), 1);
  EXPECT_FALSE(third.frontier_from_store(0));
}

TEST(SectionLibraryOptions, EachBadValueIsNamed) {
  struct Case {
    const char* field;
    void (*spoil)(SectionLibraryOptions&);
  };
  const Case cases[] = {
      {"ds_m", [](SectionLibraryOptions& o) { o.engine.grid.ds_m = 0.0; }},
      {"dv_kmh", [](SectionLibraryOptions& o) { o.engine.grid.dv_kmh = NAN; }},
      {"substep_m", [](SectionLibraryOptions& o) { o.engine.grid.substep_m = 50.0; }},
      {"resim_step_m", [](SectionLibraryOptions& o) { o.engine.resim_step_m = -1.0; }},
      {"tolerance_s", [](SectionLibraryOptions& o) { o.search.tolerance_s = INFINITY; }},
      {"frontier_span_s", [](SectionLibraryOptions& o) { o.frontier_span_s = 0.0; }},
      {"frontier_step_s", [](SectionLibraryOptions& o) { o.frontier_step_s = 100.0; }},
  };
  std::string why;
  EXPECT_TRUE(SectionLibraryOptions{}.IsValid(&why));
  for (const Case& c : cases) {
    SectionLibraryOptions o;
    c.spoil(o);
    EXPECT_FALSE(o.IsValid(&why)) << c.field;
    EXPECT_NE(why.find(c.field), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace ecorail::dp
