// The time-expanded label search (dp/timing_label_search.hpp), the last resort of a part of a
// timing-point journey whose price searches missed a window. Its DP is checked against a brute
// force over every sequence of its controls (with buckets too fine to merge any two labels,
// the DP must find exactly the brute force's optimum, windows, end speed and arrival included),
// and a part held back twice and then made fast (an earliest bound just before a latest one,
// twice, around a witness run: the shape the price search missed in docs/ttobench.md) is met on
// the re-simulation, every window checked here on the run's trace.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "data/train_io.hpp"
#include "dp/objective.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "dp/timing_journey_part.hpp"
#include "dp/timing_label_search.hpp"
#include "physics/units.hpp"
#include "timing_tracks.hpp"

namespace ecorail::dp::timing {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr physics::Control kControls[] = {physics::Control::MaxTraction, physics::Control::Hold,
                                          physics::Control::Coast, physics::Control::MaxBrake};

// Every sequence of the four controls over stages of stage_m, integrated as the label search
// integrates (Heun, substep_m), keeping those that pass the window at window_m, end inside
// [end_min, end_max] and arrive in [t_lo, t_hi]; the least cost, +infinity when none.
double brute_force(const SectionEngine& engine, double v0, double stage_m, double substep_m,
                   double window_m, const LabelWindow& w, double end_min, double end_max,
                   double t_lo, double t_hi) {
  const double length = engine.route().length_m();
  const int stages = static_cast<int>(std::lround(length / stage_m));
  int combos = 1;
  for (int j = 0; j < stages; ++j) combos *= 4;
  double best = kInfinity;
  for (int code = 0; code < combos; ++code) {
    double e = 0.5 * v0 * v0, t = 0.0, traction = 0.0;
    bool ok = true;
    int rest = code;
    for (int j = 0; j < stages && ok; ++j) {
      const physics::Control c = kControls[rest % 4];
      rest /= 4;
      const physics::Advance a =
          engine.motion().advance(j * stage_m, e, (j + 1) * stage_m, c, {substep_m, 2});
      if (a.stalled) ok = false;
      e = a.e_end;
      t += a.time_s;
      traction += a.traction_work_J;
      if (std::fabs((j + 1) * stage_m - window_m) < 1e-9) {
        const double v = physics::speed_from_e(e);
        ok = ok && t >= w.earliest_s && t <= w.latest_s && v >= w.min_ms && v <= w.max_ms;
      }
    }
    const double v_end = physics::speed_from_e(e);
    if (!ok || v_end < end_min || v_end > end_max || t < t_lo || t > t_hi) continue;
    best = std::min(best, traction / engine.train().traction_efficiency);
  }
  return best;
}

TEST(LabelSearch, EqualsBruteForceOverItsControlsWhenNoLabelsMerge) {
  const physics::Train train = data::default_train();
  // 60 m of level track (6 stages of 10 m: 4096 control sequences) inside a long envelope, so
  // that a run may end moving.
  const physics::Route part = timing_test::rise_track(20.0, 40.0, 60.0, 0.0, "P0", "P1");
  const physics::Route envelope = timing_test::rise_track(20.0, 40.0, 3000.0, 0.0, "P0", "P9");
  EngineOptions engine_options;
  engine_options.grid.ds_m = 10.0;
  engine_options.grid.dv_kmh = 0.5;
  const SectionEngine engine(train, part, engine_options, envelope);
  LabelSearchOptions o;
  o.speed_bucket_ms = 1e-9;  // no two labels share a bucket
  o.time_bucket_s = 1e-9;
  o.time_margin_s = 0.0;
  o.speed_margin_ms = 0.0;
  o.crawl_ms = 0.0;
  o.repair_s = 0.0;
  o.repair_ms = 0.0;
  const double v0 = 8.0;
  int compared = 0, found = 0;
  // Windows at 30 m that bind differently: open, an earliest bound, a latest one, a speed band.
  for (const LabelWindow w : {LabelWindow{30.0, -kInfinity, kInfinity, 0.0, kInfinity},
                              LabelWindow{30.0, 4.2, kInfinity, 0.0, kInfinity},
                              LabelWindow{30.0, -kInfinity, 3.6, 0.0, kInfinity},
                              LabelWindow{30.0, 3.7, 4.0, 7.0, 8.2}}) {
    for (const auto& [end_min, end_max, t_lo, t_hi] :
         {std::array<double, 4>{6.0, 9.0, 0.0, 9.0}, std::array<double, 4>{7.5, 8.5, 7.2, 7.8},
          std::array<double, 4>{9.0, 12.0, 0.0, 6.8}}) {
      EndCheck end;
      end.moving = true;
      end.min_ms = end_min;
      end.max_ms = end_max;
      const double expected =
          brute_force(engine, v0, o.stage_m, o.substep_m, 30.0, w, end_min, end_max, t_lo, t_hi);
      const LabelSearchResult r = label_search(engine, {0.0, v0}, end, t_lo, t_hi, {w}, o);
      ++compared;
      if (!std::isfinite(expected)) {
        EXPECT_FALSE(r.run.has_value()) << "window at " << w.earliest_s << "-" << w.latest_s;
        continue;
      }
      ++found;
      ASSERT_TRUE(r.run.has_value()) << "window at " << w.earliest_s << "-" << w.latest_s;
      EXPECT_NEAR(r.dp_cost_J, expected, 1e-9 * expected + 1e-6);
    }
  }
  EXPECT_EQ(compared, 12);
  EXPECT_GE(found, 6);  // most of the cases have a run; the comparison is not vacuous
}

// A run on the 3 km test track with a rise over 1000-1800 m that is held back twice and then
// fast: each hold-back becomes an earliest bound at one point and a latest bound 100 m on, each
// kSlack_s beyond the witness's times, and the stop kSlack_s after the witness's arrival.
constexpr double kSlack_s = 0.5;
TEST(LabelSearch, MeetsAPartHeldBackTwiceThenFast) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const TimingJourneyOptions options = timing_test::coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  using physics::Control;
  const physics::ControlProgram witness_program = {
      {0.0, Control::MaxTraction}, {120.0, Control::Coast},        {520.0, Control::MaxTraction},
      {820.0, Control::Coast},     {1600.0, Control::MaxTraction}, {1950.0, Control::Coast}};
  const physics::SimulationResult witness = engine.simulate(witness_program);
  ASSERT_TRUE(run_arrives(witness));
  auto at = [&](double s) { return passing_at(witness.trace, s); };
  std::vector<TimingWindow> windows = {{0.0, 0.0, 0.0, 0.0, 0.0}};
  windows.push_back({700.0, at(700.0).t_s - kSlack_s, kInfinity, 0.0, kInfinity});
  windows.push_back({800.0, -kInfinity, at(800.0).t_s + kSlack_s, 0.0, kInfinity});
  windows.push_back({1850.0, at(1850.0).t_s - kSlack_s, kInfinity, 0.0, kInfinity});
  windows.push_back({1950.0, -kInfinity, at(1950.0).t_s + kSlack_s, 0.0, kInfinity});
  windows.push_back({3000.0, -kInfinity, witness.running_time_s + kSlack_s, 0.0, 0.0});
  std::vector<PartPoint> points;
  for (int i = 1; i <= 4; ++i) {
    PartPoint p;
    p.index = i;
    p.s_m = windows[i].position_m;
    p.stage = static_cast<int>(p.s_m / options.engine.grid.ds_m);
    p.earliest_s = windows[i].earliest_s;
    p.latest_s = windows[i].latest_s;
    points.push_back(p);
  }
  const PartOutcome o = solve_part(engine, {}, EndCheck{}, witness.running_time_s, 0.0, points,
                                   windows, options, false, /*by_labels=*/true);
  std::string notes;
  for (const std::string& note : o.notes) notes += note + "\n";
  ASSERT_TRUE(o.holds) << notes;
  const physics::SimulationResult& sim = o.run.sim;
  EXPECT_TRUE(run_arrives(sim));
  EXPECT_LE(sim.running_time_s, witness.running_time_s + options.time_tolerance_s);
  for (int i = 1; i <= 4; ++i) {
    const Passing p = passing_at(sim.trace, windows[i].position_m);
    EXPECT_GE(p.t_s, windows[i].earliest_s - options.time_tolerance_s) << "point " << i;
    EXPECT_LE(p.t_s, windows[i].latest_s + options.time_tolerance_s) << "point " << i;
  }
  const double witness_J = engine.energy_cost_J(witness);
  std::printf("label search: %.1f kJ against the witness's %.1f kJ (%.4f)\n", o.run.cost_J / 1e3,
              witness_J / 1e3, o.run.cost_J / witness_J);
}

}  // namespace
}  // namespace ecorail::dp::timing

namespace ecorail::dp {
namespace {

// Journey 5 of the random-windows bench's zero-width journeys at the default grid, seed 72
// (bench/bench_timing_windows.cpp, printed to three decimals): a moving start, a zero-width
// time at 161.3 m, the state pinned at 1068.3 m, a zero-width time at 1944.4 m, the stop at one
// time. The price search for the point at 161.3 m found no run meeting it and the journey was
// missed; the first part now goes to the label search, its passing time repaired and its pinned
// end restored on the switches after it. Every window is met exactly on the re-simulation.
TEST(LabelSearch, MeetsAZeroWidthJourneyThePriceSearchMissed) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<TimingWindow> w = {{0.0, 0.0, 0.0, 2.456, 2.456},
                                       {161.3, 16.203, 16.203, -inf, inf},
                                       {1068.3, 88.684, 88.684, 10.687, 10.687},
                                       {1944.4, 165.139, 165.139, -inf, inf},
                                       {3000.0, 279.781, 279.781, 0.0, 0.0}};
  const TimingJourneySolution sol = solve_timing_journey(train, track, w, TimingJourneyOptions{});
  ASSERT_TRUE(sol.windows_met) << sol.summary.FullReport();
  ASSERT_EQ(sol.windows.size(), w.size());
  for (std::size_t i = 1; i < w.size(); ++i) {
    EXPECT_NEAR(sol.windows[i].time_s, w[i].earliest_s, timing::kZeroWidthTime_s) << "point " << i;
    if (std::isfinite(w[i].min_speed_ms)) {
      EXPECT_NEAR(sol.windows[i].speed_ms, w[i].min_speed_ms, timing::kZeroWidthSpeed_ms)
          << "point " << i;
    }
  }
  bool labelled = false;
  for (const std::string& warning : sol.summary.warnings) {
    labelled = labelled || warning.find("time-expanded label search") != std::string::npos;
  }
  EXPECT_TRUE(labelled);
}

}  // namespace
}  // namespace ecorail::dp
