// Timing-point journeys whose windows bind exactly (dp/timing_journey.hpp): zero-width windows
// in time at several passing points of one part, and random feasible windows built around a
// witness run. The solver's runs are checked on their re-simulation (time within 1 ms and speed
// within 0.01 km/h for a zero-width window) and against an independent brute force on the
// simulator alone: a switch-point search over programs of full traction, hold and coast in each
// stretch between timing points, each coast onset bisected so the stretch ends at its time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "data/train_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "dp/timing_journey.hpp"
#include "physics/units.hpp"
#include "timing_tracks.hpp"

namespace ecorail::dp {
namespace {

using timing_test::coarse_timing;
using timing_test::kExactSpeed_ms;
using timing_test::kExactTime_s;
using timing_test::kOpen;
using timing_test::stop_at;
constexpr double kShortTrack_m = 2000.0;

// A 2 km track: level, a 5 per mille rise from 800 m to 1300 m, limit 80 km/h.
physics::Route short_track() {
  return timing_test::rise_track(800.0, 1300.0, kShortTrack_m, 5.0, "X0", "X1");
}

// Time and speed where a run passes s_m (linear between trace points; NaN if it never does).
struct At {
  double t_s = NAN, v_ms = NAN;
};
At at_position(const physics::SimulationResult& sim, double s_m) {
  const auto& tr = sim.trace;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    if (tr[k].s_m < s_m) continue;
    if (k == 0) return {tr[0].t_s, tr[0].v_ms};
    const double w = (s_m - tr[k - 1].s_m) / (tr[k].s_m - tr[k - 1].s_m);
    return {tr[k - 1].t_s + w * (tr[k].t_s - tr[k - 1].t_s),
            tr[k - 1].v_ms + w * (tr[k].v_ms - tr[k - 1].v_ms)};
  }
  return {};
}

// A program from phases that may be empty (from_m not above the previous one's: dropped).
physics::ControlProgram program_of(const std::vector<physics::ProgramStep>& phases) {
  physics::ControlProgram p;
  for (const auto& step : phases) {
    if (!p.empty() && step.from_m <= p.back().from_m + 1e-9) {
      p.back().control = step.control;  // the earlier phase has no length
      continue;
    }
    if (!p.empty() && p.back().control == step.control) continue;
    p.push_back(step);
  }
  return p;
}

// The brute force. Stretch k runs from ends_m[k-1] (or 0) to ends_m[k]: full traction to a, a
// hold to b, a coast to the stretch's end (the last stretch's coast ends on the braking curve of
// the speed envelope, at rest at the stop), and it must end at times_s[k] (the last: the running
// time). In each stretch one of the two switches is taken from a lattice over the stretch and
// the other bisected for the stretch's time (both ways round, or no traction and the coast
// onset bisected), stretch after stretch (a tree);
// then the best run's lattice values are refined coordinate-wise by halving steps. Returns the
// least traction work of a run that meets every time to 0.5 ms (+infinity: none).
class BruteForce {
 public:
  BruteForce(const SectionEngine& engine, std::vector<double> ends_m, std::vector<double> times_s)
      : engine_(engine), ends_m_(std::move(ends_m)), times_s_(std::move(times_s)) {}

  double best_J(int lattice) {
    const std::size_t n = ends_m_.size();
    // Per stretch: which switch is the lattice's (0: a, 1: b) and where (fraction of it).
    std::vector<int> mode(n);
    std::vector<double> frac(n), best_frac;
    std::vector<int> best_mode;
    double best = kOpen;
    std::vector<double> a(n), b(n);
    std::function<void(std::size_t)> tree = [&](std::size_t k) {
      for (int m = 0; m < 3; ++m) {
        for (int i = 0; i < (m == 2 ? 1 : lattice); ++i) {
          mode[k] = m;
          frac[k] = (i + 0.5) / lattice;
          physics::SimulationResult sim;
          if (!stretch(k, mode[k], frac[k], a, b, &sim)) continue;
          if (k + 1 < n) {
            tree(k + 1);
          } else if (sim.energy.traction_work_J < best) {
            best = sim.energy.traction_work_J, best_mode = mode, best_frac = frac;
          }
        }
      }
    };
    tree(0);
    if (!std::isfinite(best)) return best;
    for (double step = 0.5 / lattice; step > 0.004; step *= 0.5) {
      bool gained = true;
      while (gained) {
        gained = false;
        for (std::size_t k = 0; k < n; ++k) {
          for (double d : {-step, step}) {
            std::vector<double> f = best_frac;
            f[k] += d;
            if (best_mode[k] == 2 || f[k] <= 0.0 || f[k] >= 1.0) continue;
            const double e = chain_J(best_mode, f, a, b);
            if (e < best - 1.0) best = e, best_frac = f, gained = true;
          }
        }
      }
    }
    return best;
  }

  int simulations() const { return sims_; }

 private:
  // The program for stretches 0..k (a coast after the last of them).
  physics::ControlProgram program(const std::vector<double>& a, const std::vector<double>& b,
                                  std::size_t k) const {
    std::vector<physics::ProgramStep> out;
    for (std::size_t j = 0; j <= k; ++j) {
      const double from = j == 0 ? 0.0 : ends_m_[j - 1];
      out.push_back({from, physics::Control::MaxTraction});
      out.push_back({a[j], physics::Control::Hold});
      out.push_back({b[j], physics::Control::Coast});
    }
    return program_of(out);
  }

  // The time stretch k ends at (the running time for the last) minus its target.
  double late_s(const physics::SimulationResult& sim, std::size_t k) const {
    if (k + 1 == ends_m_.size()) {
      return run_arrives(sim) ? sim.running_time_s - times_s_[k] : kOpen;
    }
    const At at = at_position(sim, ends_m_[k]);
    return std::isfinite(at.t_s) ? at.t_s - times_s_[k] : kOpen;
  }

  // Stretch k with stretches 0..k-1 set in a and b: the lattice switch at frac of the stretch
  // (mode 0: the traction end a, the coast onset b bisected in [a, end]; mode 1: b, with a
  // bisected in [start, b]; mode 2: no traction, a hold at the entry speed and b bisected);
  // false when no bisected switch meets the stretch's time.
  bool stretch(std::size_t k, int mode, double frac, std::vector<double>& a, std::vector<double>& b,
               physics::SimulationResult* out) {
    const double from = k == 0 ? 0.0 : ends_m_[k - 1], to = ends_m_[k];
    const double fixed = mode == 2 ? from : from + frac * (to - from);
    double lo = mode == 1 ? from + 1e-3 : fixed, hi = mode == 1 ? fixed : to;
    (mode == 1 ? b[k] : a[k]) = fixed;
    double& x = mode == 1 ? a[k] : b[k];
    physics::SimulationResult sim;
    auto f = [&](double v) {  // falling in v: a later switch is faster
      x = v;
      sim = engine_.simulate(program(a, b, k), {}, 1.0);
      ++sims_;
      return late_s(sim, k);
    };
    if (!(f(lo) >= 0.0) || !(f(hi) <= 0.0)) return false;
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (lo + hi);
      const double fm = f(m);
      if (std::abs(fm) <= 5e-4) {
        *out = std::move(sim);
        return true;
      }
      (fm > 0.0 ? lo : hi) = m;
    }
    return false;
  }

  double chain_J(const std::vector<int>& mode, const std::vector<double>& frac,
                 std::vector<double>& a, std::vector<double>& b) {
    physics::SimulationResult sim;
    for (std::size_t k = 0; k < ends_m_.size(); ++k) {
      if (!stretch(k, mode[k], frac[k], a, b, &sim)) return kOpen;
    }
    return sim.energy.traction_work_J;
  }

  const SectionEngine& engine_;
  std::vector<double> ends_m_, times_s_;
  int sims_ = 0;
};

// A witness run through passing points s1 < s2: full traction to x1 (before s1), a coast, and
// in each later stretch a coast, a burst of full traction and a coast again; at rest at the
// stop on the braking curve.
physics::SimulationResult witness(const SectionEngine& engine, std::mt19937& rng, double s1,
                                  double s2) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double x1 = (0.3 + 0.5 * u(rng)) * s1;
  const double y2 = s1 + (0.1 + 0.4 * u(rng)) * (s2 - s1), x2 = y2 + 30.0 + 60.0 * u(rng);
  const double y3 = s2 + (0.05 + 0.3 * u(rng)) * (kShortTrack_m - s2),
               x3 = y3 + 20.0 + 40.0 * u(rng);
  return engine.simulate({{0.0, physics::Control::MaxTraction},
                          {x1, physics::Control::Coast},
                          {y2, physics::Control::MaxTraction},
                          {x2, physics::Control::Coast},
                          {y3, physics::Control::MaxTraction},
                          {x3, physics::Control::Coast}},
                         {}, 1.0);
}

// A random journey around a witness run (feasible for it by construction): passing points at
// s[0] in [lo0, lo0 + span0] and s[1] in [lo1, lo1 + span1], each given at random a window of
// zero width at the witness's time there, a latest or an earliest bound at that time, or (its
// fourth kind) bounds a few seconds either side of it, or its time and speed exactly
// (pin_state); the stop at the witness's time exactly or in a 10 s window ending there.
struct RandomJourney {
  physics::SimulationResult witness;
  double s[2] = {0.0, 0.0};
  std::vector<double> witness_times;  // at s[0], s[1] and the stop
  std::vector<TimingWindow> windows;
};
RandomJourney random_journey(const SectionEngine& engine, std::mt19937& rng, double lo0,
                             double span0, double lo1, double span1, bool pin_state) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 3);
  RandomJourney j;
  j.s[0] = lo0 + span0 * u(rng);
  j.s[1] = lo1 + span1 * u(rng);
  j.witness = witness(engine, rng, j.s[0], j.s[1]);
  j.windows = {stop_at(0, 0, 0)};
  for (double sk : j.s) {
    const At at = at_position(j.witness, sk);
    j.witness_times.push_back(at.t_s);
    const int k = kind(rng);
    TimingWindow pw{sk, -kOpen, kOpen, -kOpen, kOpen};
    if (k == 0) pw.earliest_s = pw.latest_s = at.t_s;
    if (k == 1) pw.latest_s = at.t_s;
    if (k == 2) pw.earliest_s = at.t_s;
    if (k == 3 && pin_state) {
      pw.earliest_s = pw.latest_s = at.t_s;
      pw.min_speed_ms = pw.max_speed_ms = at.v_ms;
    }
    if (k == 3 && !pin_state)
      pw.earliest_s = at.t_s - 3.0 * u(rng), pw.latest_s = at.t_s + 3.0 * u(rng);
    j.windows.push_back(pw);
  }
  const double arrive = j.witness.running_time_s;
  j.witness_times.push_back(arrive);
  j.windows.push_back(kind(rng) < 2 ? stop_at(kShortTrack_m, arrive, arrive)
                                    : stop_at(kShortTrack_m, arrive - 10.0, arrive));
  return j;
}

// "instance i: [position m: earliest, latest, min speed m/s] ..." for a failure's trace.
testing::Message describe(int instance, const std::vector<TimingWindow>& windows) {
  testing::Message what;
  what << "instance " << instance << ":";
  for (const auto& x : windows) {
    what << " [" << x.position_m << " m: " << x.earliest_s << ", " << x.latest_s << ", "
         << x.min_speed_ms << " m/s]";
  }
  return what;
}

// Zero-width time windows at two passing points and at the arrival, taken from random witness
// runs: every one is met exactly on the re-simulation, and the run costs no more than the
// witness (a feasible run) and than the brute force's best (within 0.2 %, the grid's
// raggedness).
TEST(TimingJourneyExact, ZeroWidthWindowsAtTwoPassingPointsAreMetExactlyAndBeatTheBruteForce) {
  const physics::Train train = data::default_train();
  const physics::Route track = short_track();
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  std::mt19937 rng(24001);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int instance = 0; instance < 2; ++instance) {
    const double s1 = 500.0 + 300.0 * u(rng), s2 = 1200.0 + 400.0 * u(rng);
    const physics::SimulationResult w = witness(engine, rng, s1, s2);
    ASSERT_TRUE(run_arrives(w));
    const double t1 = at_position(w, s1).t_s, t2 = at_position(w, s2).t_s;
    const double arrive = w.running_time_s;
    const std::vector<TimingWindow> windows = {stop_at(0, 0, 0),
                                               {s1, t1, t1, -kOpen, kOpen},
                                               {s2, t2, t2, -kOpen, kOpen},
                                               stop_at(kShortTrack_m, arrive, arrive)};
    const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
    SCOPED_TRACE(testing::Message()
                 << "instance " << instance << ": " << s1 << " m at " << t1 << " s, " << s2
                 << " m at " << t2 << " s, arrival " << arrive << " s");
    ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
    ASSERT_TRUE(sol.windows_met);
    const physics::SimulationResult& sim = sol.journey.sections.at(0).run.sim;
    EXPECT_NEAR(at_position(sim, s1).t_s, t1, kExactTime_s);
    EXPECT_NEAR(at_position(sim, s2).t_s, t2, kExactTime_s);
    EXPECT_NEAR(sim.running_time_s, arrive, kExactTime_s);
    const double energy = sim.energy.traction_work_J;
    EXPECT_LE(energy, w.energy.traction_work_J * (1.0 + 1e-3));
    BruteForce bf(engine, {s1, s2, kShortTrack_m}, {t1, t2, arrive});
    const double best = bf.best_J(3);
    ASSERT_TRUE(std::isfinite(best));
    EXPECT_LE(energy, best * (1.0 + 2e-3)) << energy << " J against the brute force's " << best
                                           << " J (" << bf.simulations() << " simulations)";
  }
}

// Random feasible windows around witness runs: at each of two passing points a window of zero
// width, a latest bound only, an earliest bound only, or both bounds a few seconds either side
// of the witness's time; the arrival at the witness's time exactly or in a window ending
// there. Every window holds on the re-simulation (zero-width ones exactly), the run is no
// dearer than the witness, and no dearer than the brute force's best run through the witness's
// times (each inside its window, so the optimum of the windows can only undercut it).
TEST(TimingJourneyExact, RandomFeasibleWindowsAreMetAndNoDearerThanTheBruteForce) {
  const physics::Train train = data::default_train();
  const physics::Route track = short_track();
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  std::mt19937 rng(24002);
  for (int instance = 0; instance < 3; ++instance) {
    const RandomJourney j = random_journey(engine, rng, 500.0, 300.0, 1200.0, 400.0, false);
    const physics::SimulationResult& w = j.witness;
    const std::vector<TimingWindow>& windows = j.windows;
    ASSERT_TRUE(run_arrives(w));
    SCOPED_TRACE(describe(instance, windows));
    const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
    ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
    ASSERT_TRUE(sol.windows_met);
    const physics::SimulationResult& sim = sol.journey.sections.at(0).run.sim;
    for (std::size_t i = 1; i < windows.size(); ++i) {
      const TimingWindow& x = windows[i];
      const double t =
          i + 1 == windows.size() ? sim.running_time_s : at_position(sim, x.position_m).t_s;
      const double tol = x.earliest_s == x.latest_s ? kExactTime_s : options.time_tolerance_s;
      EXPECT_GE(t, x.earliest_s - tol) << i;
      EXPECT_LE(t, x.latest_s + tol) << i;
    }
    const double energy = sim.energy.traction_work_J;
    EXPECT_LE(energy, w.energy.traction_work_J * (1.0 + 1e-3));
    BruteForce bf(engine, {j.s[0], j.s[1], kShortTrack_m}, j.witness_times);
    const double best = bf.best_J(3);
    ASSERT_TRUE(std::isfinite(best));
    EXPECT_LE(energy, best * (1.0 + 2e-3))
        << energy << " J against the brute force's " << best << " J";
  }
}

// A zero-width speed window at the arrival of a run that ends moving with a zero-width passing
// window before it binding: both exact.
TEST(TimingJourneyExact, AZeroWidthPassingWindowBeforeAMovingEndIsMetExactly) {
  const physics::Train train = data::default_train();
  const physics::Route track = short_track();
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  std::mt19937 rng(24003);
  const physics::SimulationResult w = witness(engine, rng, 1000.0, 1500.0);
  const double s1 = 1000.0, t1 = at_position(w, s1).t_s;
  const double arrive = w.running_time_s;
  const std::vector<TimingWindow> windows = {{0.0, 0.0, 0.0, 1.0, 1.0},
                                             {s1, t1, t1, -kOpen, kOpen},
                                             {kShortTrack_m, arrive, arrive, 1.0, 1.0}};
  const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
  ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
  ASSERT_TRUE(sol.windows_met);
  const physics::SimulationResult& sim = sol.journey.sections.at(0).run.sim;
  EXPECT_NEAR(at_position(sim, s1).t_s, t1, kExactTime_s);
  EXPECT_NEAR(sim.running_time_s, arrive, kExactTime_s);
  EXPECT_NEAR(sim.end_speed_ms, 1.0, kExactSpeed_ms);
}

}  // namespace
}  // namespace ecorail::dp

namespace ecorail::dp {
namespace {

// A passing window of zero width in time and in speed (a witness run's time and speed at the
// point), with the arrival at the witness's time: the point pins the run's state, so it ends
// one part (moving, at that speed) and starts the next; every window is met exactly on the
// re-simulation, and the two parts together are no dearer than the witness.
TEST(TimingJourneyExact, AZeroWidthTimeAndSpeedPassingWindowIsMetExactly) {
  const physics::Train train = data::default_train();
  const physics::Route track = short_track();
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  std::mt19937 rng(24004);
  const double s1 = 900.0;
  const physics::SimulationResult w = witness(engine, rng, s1, 1500.0);
  ASSERT_TRUE(run_arrives(w));
  const At at = at_position(w, s1);
  const double arrive = w.running_time_s;
  const std::vector<TimingWindow> windows = {stop_at(0, 0, 0),
                                             {s1, at.t_s, at.t_s, at.v_ms, at.v_ms},
                                             stop_at(kShortTrack_m, arrive, arrive)};
  const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
  ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
  ASSERT_TRUE(sol.windows_met);
  ASSERT_EQ(sol.parts.size(), 2u);
  const physics::SimulationResult& first = sol.journey.sections.at(0).run.sim;
  const physics::SimulationResult& second = sol.journey.sections.at(1).run.sim;
  EXPECT_NEAR(first.running_time_s, at.t_s, kExactTime_s);
  EXPECT_NEAR(first.end_speed_ms, at.v_ms, kExactSpeed_ms);
  EXPECT_DOUBLE_EQ(second.trace.front().v_ms, at.v_ms);
  EXPECT_NEAR(sol.windows[1].time_s, at.t_s, kExactTime_s);
  EXPECT_NEAR(sol.windows[1].speed_ms, at.v_ms, kExactSpeed_ms);
  EXPECT_NEAR(sol.windows[2].time_s, arrive, kExactTime_s);
  EXPECT_LE(first.energy.traction_work_J + second.energy.traction_work_J,
            w.energy.traction_work_J * (1.0 + 1e-3));
}

// Random windows around witness runs, with points whose time and speed are both pinned among
// them (each of two passing points at random: its time exactly, a latest or an earliest bound
// at the witness's time, or its time and speed exactly; the stop at the witness's time or in a
// 10 s window ending there): every window holds on the re-simulation, zero-width ones exactly.
TEST(TimingJourneyExact, RandomWindowsWithPinnedStatesAreMetExactly) {
  const physics::Train train = data::default_train();
  const physics::Route track = short_track();
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  std::mt19937 rng(777);
  for (int instance = 0; instance < 8; ++instance) {
    const RandomJourney j = random_journey(engine, rng, 400.0, 500.0, 1100.0, 600.0, true);
    const std::vector<TimingWindow>& windows = j.windows;
    ASSERT_TRUE(run_arrives(j.witness));
    SCOPED_TRACE(describe(instance, windows));
    const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
    ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
    ASSERT_TRUE(sol.windows_met);
    for (std::size_t i = 1; i < windows.size(); ++i) {
      const TimingWindow& x = windows[i];
      const WindowResult& r = sol.windows[i];
      const double tt = x.earliest_s == x.latest_s ? kExactTime_s : options.time_tolerance_s;
      EXPECT_GE(r.time_s, x.earliest_s - tt) << i;
      EXPECT_LE(r.time_s, x.latest_s + tt) << i;
      if (x.min_speed_ms == x.max_speed_ms) {
        EXPECT_NEAR(r.speed_ms, x.min_speed_ms, kExactSpeed_ms) << i;
      }
    }
  }
}

}  // namespace
}  // namespace ecorail::dp

namespace ecorail::dp {
namespace {

// Checks every window of a one-part journey's solution on its re-simulation: the passing
// points' times (zero-width ones within 1 ms) and speeds, and the arrival.
void expect_every_window_holds(const TimingJourneySolution& sol,
                               const std::vector<TimingWindow>& windows,
                               const TimingJourneyOptions& options) {
  ASSERT_TRUE(sol.summary.IsSolutionUsable()) << sol.summary.FullReport();
  ASSERT_TRUE(sol.windows_met);
  const physics::SimulationResult& sim = sol.journey.sections.at(0).run.sim;
  const double tol_v = units::kmh_to_ms(options.speed_tolerance_kmh);
  for (std::size_t k = 1; k + 1 < windows.size(); ++k) {
    const TimingWindow& x = windows[k];
    const At at = at_position(sim, x.position_m);
    const double tt = x.earliest_s == x.latest_s ? kExactTime_s : options.time_tolerance_s;
    EXPECT_GE(at.t_s, x.earliest_s - tt) << k;
    EXPECT_LE(at.t_s, x.latest_s + tt) << k;
    EXPECT_GE(at.v_ms, x.min_speed_ms - tol_v) << k;
    EXPECT_LE(at.v_ms, x.max_speed_ms + tol_v) << k;
  }
  EXPECT_LE(sim.running_time_s, windows.back().latest_s + options.time_tolerance_s);
  EXPECT_GE(sim.running_time_s, windows.back().earliest_s - options.time_tolerance_s);
}
void expect_every_window_holds(const physics::Train& train, const physics::Route& track,
                               const std::vector<TimingWindow>& windows,
                               const TimingJourneyOptions& options) {
  expect_every_window_holds(solve_timing_journey(train, track, windows, options), windows, options);
}

// Speed windows at passing points between two grid stages, from random journeys around witness
// runs (a 3 km track with a 6 per mille rise over 1000-1800 m, a moving start, --ds 10 --dv 0.5;
// windows printed to the millisecond and 1 mm/s): the runs passed the last point 0.56 and 0.27
// km/h above its speed window (traction from the stage before the point; the band held the
// stage only) and were reported as missing it. Every window now holds on the re-simulation.
TEST(TimingJourneyExact, SpeedWindowsBetweenGridStagesHoldOnTheReSimulation) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const TimingJourneyOptions options = coarse_timing();
  const std::vector<std::vector<TimingWindow>> journeys = {
      {{0.0, 0.0, 0.0, 2.017, 2.017},
       {403.2, 29.076, kOpen, -kOpen, kOpen},
       {1236.7, 76.136, kOpen, -kOpen, kOpen},
       {1924.3, -kOpen, 120.327, 12.475, 13.913},
       stop_at(3000.0, 201.207, 211.207)},
      {{0.0, 0.0, 0.0, 1.430, 1.430},
       {461.7, 31.186, 33.943, -kOpen, kOpen},
       {1238.5, 72.920, 76.105, -kOpen, kOpen},
       {1702.3, -kOpen, 105.410, 15.803, 17.560},
       stop_at(3000.0, 186.407, 196.407)}};
  for (std::size_t i = 0; i < journeys.size(); ++i) {
    SCOPED_TRACE(describe(static_cast<int>(i), journeys[i]));
    expect_every_window_holds(train, track, journeys[i], options);
  }
}

// Passing windows near the flat-out time, from random journeys around witness runs (the 3 km
// track of the test above): a zero-width time at 311.9 m with a least speed, then a speed
// window, from rest (the price search ends with its run 0.9 s early and 2 s late at the next
// point: the run is moved onto the windows by continuation); a latest bound at 177.4 m 0.10 s
// above the flat-out time from a moving start (the search's run holds for 3.3 m after its first
// traction, which pins both switches: the run without its short phases is solved); a
// zero-width time at 212.2 m that the plain search passed 2.3 ms late (within half the window
// tolerance, so it did not bind). All three missed a window before. Every window holds on the
// re-simulation, zero-width ones exactly.
TEST(TimingJourneyExact, WindowsNearTheFlatOutTimeAreMetOnTheSimulator) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const TimingJourneyOptions options = coarse_timing();
  const std::vector<std::vector<TimingWindow>> journeys = {
      {stop_at(0.0, 0.0, 0.0),
       {311.9, 26.914, 26.914, 14.759, kOpen},
       {1008.1, -kOpen, 69.058, 14.181, 14.715},
       {1660.4, -kOpen, 113.981, -kOpen, kOpen},
       stop_at(3000.0, 234.685, 244.685)},
      {{0.0, 0.0, 0.0, 1.186, 1.186},
       {177.4, -kOpen, 17.981, -kOpen, kOpen},
       {976.1, 68.509, kOpen, -kOpen, kOpen},
       {1786.3, 130.019, kOpen, -kOpen, kOpen},
       stop_at(3000.0, 251.919, 261.919)},
      {{0.0, 0.0, 0.0, 1.964, 1.964},
       {212.2, 19.468, 19.468, 14.829, kOpen},
       {918.7, -kOpen, 64.876, -kOpen, kOpen},
       {1704.3, -kOpen, 114.493, -kOpen, kOpen},
       stop_at(3000.0, 210.161, 220.161)}};
  for (std::size_t i = 0; i < journeys.size(); ++i) {
    SCOPED_TRACE(describe(static_cast<int>(i), journeys[i]));
    expect_every_window_holds(train, track, journeys[i], options);
  }
}

// Two journeys of a sample drawn after the transition bands (the 3 km track above, at rest,
// --ds 10 --dv 0.5) that missed a window on stop 39's code as well: a speed window at 1871.6 m
// whose band the run kept missing by 0.21 m/s (the cruise held over the point; 8 487
// evaluations and the window missed), now narrowed by the miss; and a zero-width time at
// 336.5 m passed 7 ms early, within the loose first scale of the Newton step, which took the
// run as exact without looking closer. Every window holds on the re-simulation.
TEST(TimingJourneyExact, ABandTheRunStillMissesIsNarrowedAndAZeroWidthTimeIsHeldExactly) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const TimingJourneyOptions options = coarse_timing();
  const std::vector<std::vector<TimingWindow>> journeys = {
      {stop_at(0.0, 0.0, 0.0),
       {308.8, 27.281, kOpen, -kOpen, kOpen},
       {1113.9, 80.893, 80.893, -kOpen, kOpen},
       {1871.6, -kOpen, 135.416, 12.147, 13.852},
       stop_at(3000.0, 226.653, 226.653)},
      {stop_at(0.0, 0.0, 0.0),
       {336.5, 27.804, 27.804, -kOpen, kOpen},
       {978.1, 65.320, 69.984, -kOpen, kOpen},
       {1960.7, 138.892, 141.186, -kOpen, kOpen},
       stop_at(3000.0, 245.032, 255.032)}};
  for (std::size_t i = 0; i < journeys.size(); ++i) {
    SCOPED_TRACE(describe(static_cast<int>(i), journeys[i]));
    expect_every_window_holds(train, track, journeys[i], options);
  }
}

// On the 3 km rise track at --ds 10 --dv 0.5: the witness (its program, simulated from the
// journey's start speed) meets every window, so the optimum is no dearer than it; the solver's
// run must meet every window and not be dearer than the witness either (0.1 %).
void expect_no_dearer_than_witness(const std::vector<TimingWindow>& windows,
                                   const physics::ControlProgram& witness_program) {
  const physics::Train train = data::default_train();
  const physics::Route track = timing_test::rise_track(1000.0, 1800.0, 3000.0, 6.0, "X0", "X1");
  const TimingJourneyOptions options = coarse_timing();
  const SectionEngine engine(train, track, options.engine);
  const physics::SimulationResult witness =
      engine.simulate(witness_program, {0.0, windows.front().min_speed_ms}, 1.0);
  ASSERT_TRUE(run_arrives(witness));
  for (std::size_t k = 1; k < windows.size(); ++k) {
    const TimingWindow& x = windows[k];
    const At at = k + 1 < windows.size() ? at_position(witness, x.position_m)
                                         : At{witness.running_time_s, 0.0};
    EXPECT_GE(at.t_s, x.earliest_s - 0.01) << k;
    EXPECT_LE(at.t_s, x.latest_s + 0.01) << k;
    EXPECT_GE(at.v_ms, x.min_speed_ms) << k;
    EXPECT_LE(at.v_ms, x.max_speed_ms) << k;
  }
  const TimingJourneySolution sol = solve_timing_journey(train, track, windows, options);
  expect_every_window_holds(sol, windows, options);
  EXPECT_LE(sol.summary.traction_energy_kJ * 1e3, 1.001 * witness.energy.traction_work_J);
}

// A run that slows through a speed window between two grid stages, from a random journey around
// a witness run (the 3 km track above, moving start, --ds 10 --dv 0.5): the witness coasts up
// the rise through the window at 2052.4 m (11.19 m/s there, 11.74 m/s at the stage before it,
// above the window's top). The window was banded on the nodes of both stages either side, which
// forbade such runs, and the solver's run cost 13.7 % more than the witness. The band is now on
// the sweep's transitions at the point. The witness (its program to 0.1 m) meets every window,
// so the optimum is no dearer than it; the solver's run must not be either (0.1 %).
TEST(TimingJourneyExact, ARunSlowingThroughASpeedWindowBetweenStagesIsAllowed) {
  using physics::Control;
  const std::vector<TimingWindow> windows = {{0.0, 0.0, 0.0, 1.843, 1.843},
                                             {485.7, -kOpen, 32.539, 20.177, 21.021},
                                             {912.1, 51.169, 53.392, -kOpen, kOpen},
                                             {2052.4, -kOpen, 126.815, 11.104, 11.487},
                                             stop_at(3000.0, 199.631, 209.631)};
  expect_no_dearer_than_witness(windows, {{0.0, Control::MaxTraction},
                                          {359.5, Control::Coast},
                                          {595.8, Control::MaxTraction},
                                          {696.4, Control::Hold},
                                          {809.1, Control::Coast},
                                          {1158.3, Control::MaxTraction},
                                          {1209.0, Control::Coast},
                                          {2271.9, Control::MaxTraction},
                                          {2350.1, Control::Coast}});
}

// One hold through two timed points, from a random journey around a witness run (the 3 km track
// above, moving start, --ds 10 --dv 0.5; bench_timing_windows /1/22 journey 28): a latest bound
// with a speed window at 372.7 m and a zero-width time with a least speed at 956.5 m. The
// search's run held 67.89 km/h through both and passed the second 136 ms early; the hold that
// passes both at their bounds is 0.37 km/h slower after the first point, below the grid's speed
// step, and no switch of that run can slow it between the points alone. It was reported as
// missing the window after 8 914 evaluations; the phase is now split there (a short coast that
// Newton's method on the switches places). The witness (its program to 0.1 m) meets every
// window, so the optimum is no dearer than it; the solver's run must not be either (0.1 %).
TEST(TimingJourneyExact, OneHoldThroughTwoTimedPointsIsSplitBetweenThem) {
  using physics::Control;
  const std::vector<TimingWindow> windows = {{0.0, 0.0, 0.0, 3.735, 3.735},
                                             {372.7, -kOpen, 26.066, 18.380, 18.899},
                                             {956.5, 57.192, 57.192, 17.257, kOpen},
                                             {1873.7, -kOpen, 119.986, 10.203, 11.150},
                                             stop_at(3000.0, 223.489, 233.489)};
  expect_no_dearer_than_witness(windows, {{0.0, Control::MaxTraction},
                                          {239.3, Control::Coast},
                                          {539.7, Control::MaxTraction},
                                          {639.4, Control::Hold},
                                          {774.7, Control::Coast},
                                          {1273.5, Control::MaxTraction},
                                          {1313.4, Control::Coast},
                                          {2209.5, Control::MaxTraction},
                                          {2259.9, Control::Coast}});
}

}  // namespace
}  // namespace ecorail::dp
