// Closed-loop acceptance of the advisor, on A6 -> A7 with a 110 s timetable: the
// physics simulator (RK4, 5 cm steps) driven by a ControlLaw that asks the advisor "what now?" at
// every step. Following the nominal layer alone:
//   (a) on time it reproduces the optimal energy within 0.5 %;
//   (b) started 3 km/h slow at 300 m, (c) with a train 5 % heavier than the table assumed and
//   (d) with the speed measured with +-0.5 km/h uniform noise (seeded), it stops within 1 m,
//   never exceeds a limit, and arrives within kArrivalBound_s of the timetable.
// With the ladder (-4..+4 s) and the layer re-chosen every 10 m by the time left, the same cases
// arrive within kLadderBound_s. Both bounds are stated in docs/policy_format.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"

namespace ecorail {
namespace {

constexpr double kTimetable_s = 110.0;
constexpr double kArrivalBound_s = 1.0;  // nominal layer only
// Ladder with time keeping: a layer is chosen, not interpolated, so a residual of up to about
// half the 2 s spacing can remain (the noise cases keep ~0.4 s of the time their extra traction
// gained).
constexpr double kLadderBound_s = 0.6;
constexpr double kStopBound_m = 1.0;
constexpr double kOverspeedBound_kmh = 0.01;  // numerically zero: the plant is clamped

// The train as it really is: its own route and speed envelope (braking-curve supervision).
struct Plant {
  physics::Train train;
  physics::Route route;
  physics::SpeedEnvelope envelope;
  physics::Motion motion;
  Plant(const physics::Train& t, const data::Line& line)
      : train(t),
        route(data::build_route(line, "A6", "A7", train)),
        envelope(train, route),
        motion(train, route, envelope) {}
};

// Speed as the advisor sees it: true speed plus seeded uniform noise (or none).
struct SpeedSensor {
  double amplitude_ms = 0.0;
  std::mt19937 rng{1};
  double operator()(double v) {
    if (amplitude_ms == 0.0) return v;
    return v + std::uniform_real_distribution<double>(-amplitude_ms, amplitude_ms)(rng);
  }
};

// Time keeping with a ladder: the on-board clock (here integrated from the states the simulator
// passes) gives the time left to the timetable; every 10 m the layer whose expected time-to-go is
// closest to it is chosen.
struct TimeKeeper {
  const policy::Advisor* advisor;
  double clock_s = 0.0;
  double s_prev = 0.0, v_prev = 0.0, chosen_at = -1e9;
  int layer = 0;
  physics::Control operator()(double s, double v_measured, double v_true) {
    if (s > s_prev && v_true + v_prev > 0.0) clock_s += 2.0 * (s - s_prev) / (v_true + v_prev);
    s_prev = s;
    v_prev = v_true;
    if (s - chosen_at >= 10.0) {
      layer = advisor->layer_for_time(s, v_measured, kTimetable_s - clock_s);
      chosen_at = s;
    }
    return advisor->advise(layer, s, v_measured).control;
  }
};

class AdvisorClosedLoop : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    line_ = new data::Line(data::default_line());
    train_ = new physics::Train(data::default_train());
    const physics::Route route = data::build_route(*line_, "A6", "A7", *train_);
    const dp::SectionEngine engine(*train_, route, {});
    optimum_ = new dp::TimeSearchResult(dp::solve_for_time(engine, kTimetable_s, {}));
    policy::PolicyTable table = policy::make_policy_table(engine, line_->name, line_->checksum(),
                                                          data::train_checksum(*train_));
    for (double offset : {-4.0, -2.0, 0.0, 2.0, 4.0}) {
      // Each layer's price searched as the ladder searches it (policy::layer_search).
      const double lambda =
          dp::solve_for_time(engine, kTimetable_s + offset, policy::layer_search()).run.lambda;
      policy::PolicyLayer layer = policy::build_policy_layer(engine, lambda);
      layer.time_offset_s = offset;
      layer.target_time_s = kTimetable_s + offset;
      table.layers.push_back(std::move(layer));
    }
    advisor_ = new policy::Advisor(std::move(table), *line_, *train_);
  }
  static void TearDownTestSuite() {
    delete advisor_;
    delete optimum_;
    delete train_;
    delete line_;
  }

  // The timetable at s: time and speed of the optimal run there (interpolated in position).
  static void optimal_at(double s_m, double* t_s, double* v_ms) {
    const auto& tr = optimum_->run.sim.trace;
    auto it = std::lower_bound(tr.begin(), tr.end(), s_m,
                               [](const physics::TracePoint& p, double s) { return p.s_m < s; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double x = (s_m - a.s_m) / (b.s_m - a.s_m);
    *t_s = a.t_s + x * (b.t_s - a.t_s);
    *v_ms = a.v_ms + x * (b.v_ms - a.v_ms);
  }

  struct Outcome {
    physics::SimulationResult sim;
    double arrival_s = 0.0;  // on the timetable's clock
  };

  // Drives the plant from (s0, v0), which the timetable passes at t0; with or without the ladder.
  static Outcome drive(const physics::Motion& plant, SpeedSensor sensor, bool ladder,
                       double s0 = 0.0, double v0 = 0.0, double t0 = 0.0) {
    TimeKeeper keeper{advisor_, t0, s0, v0};
    const physics::ControlLaw law = [&](double s, double v) {
      const double measured = sensor(v);
      return ladder ? keeper(s, measured, v) : advisor_->advise(s, measured).control;
    };
    physics::SimulationOptions opt;
    opt.start_position_m = s0;
    opt.start_speed_ms = v0;
    Outcome out{physics::simulate(plant, law, {}, opt), 0.0};
    out.arrival_s = t0 + out.sim.running_time_s;
    return out;
  }

  static void check(const char* name, const Outcome& o, double bound_s) {
    const auto& sim = o.sim;
    const double overspeed_kmh = units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms));
    std::printf(
        "%-26s traction %9.1f kJ, arrival %8.3f s (%+.3f s), stop error %+.4f m, max "
        "overspeed %.4f km/h\n",
        name, units::J_to_kJ(sim.energy.traction_work_J), o.arrival_s, o.arrival_s - kTimetable_s,
        sim.stop_error_m, overspeed_kmh);
    EXPECT_LT(std::abs(sim.stop_error_m), kStopBound_m) << name;
    EXPECT_LT(overspeed_kmh, kOverspeedBound_kmh) << name;
    EXPECT_LT(std::abs(o.arrival_s - kTimetable_s), bound_s) << name;
  }

  static physics::Train heavier() {
    physics::Train heavy = *train_;
    heavy.mass_kg *= 1.05;
    return heavy;
  }

  static SpeedSensor noisy(unsigned seed) { return {units::kmh_to_ms(0.5), std::mt19937(seed)}; }

  static inline data::Line* line_ = nullptr;
  static inline physics::Train* train_ = nullptr;
  static inline dp::TimeSearchResult* optimum_ = nullptr;
  static inline policy::Advisor* advisor_ = nullptr;
};

TEST_F(AdvisorClosedLoop, OnTimeReproducesTheOptimalEnergy) {
  const Plant plant(*train_, *line_);
  const Outcome o = drive(plant.motion, {}, false);
  const double optimum_J = optimum_->run.sim.energy.traction_work_J;
  const double ratio = o.sim.energy.traction_work_J / optimum_J - 1.0;
  std::printf("optimum (solve_for_time) %.1f kJ in %.3f s; advisor closed loop %+.3f %%\n",
              units::J_to_kJ(optimum_J), optimum_->run.sim.running_time_s, 100.0 * ratio);
  EXPECT_LT(std::abs(ratio), 0.005);
  check("(a) on time", o, 0.1);
}

TEST_F(AdvisorClosedLoop, StartedSlowAt300m) {
  const Plant plant(*train_, *line_);
  double t300, v300;
  optimal_at(300.0, &t300, &v300);
  const double v0 = v300 - units::kmh_to_ms(3.0);
  std::printf("timetable at 300 m: %.3f s, %.2f km/h; start at %.2f km/h\n", t300,
              units::ms_to_kmh(v300), units::ms_to_kmh(v0));
  check("(b) 3 km/h slow at 300 m", drive(plant.motion, {}, false, 300.0, v0, t300),
        kArrivalBound_s);
  check("(b) + ladder", drive(plant.motion, {}, true, 300.0, v0, t300), kLadderBound_s);
}

TEST_F(AdvisorClosedLoop, TrainFivePercentHeavier) {
  const Plant plant(heavier(), *line_);
  check("(c) 5 % heavier", drive(plant.motion, {}, false), kArrivalBound_s);
  check("(c) + ladder", drive(plant.motion, {}, true), kLadderBound_s);
}

TEST_F(AdvisorClosedLoop, SpeedMeasuredWithNoise) {
  const Plant plant(*train_, *line_);
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const std::string name = "(d) noise, seed " + std::to_string(seed);
    check(name.c_str(), drive(plant.motion, noisy(seed), false), kArrivalBound_s);
    check((name + " + ladder").c_str(), drive(plant.motion, noisy(seed), true), kLadderBound_s);
  }
}

TEST_F(AdvisorClosedLoop, AllThreeAtOnce) {
  // Heavier, started slow and measured with noise: the bounds still hold.
  const Plant plant(heavier(), *line_);
  double t300, v300;
  optimal_at(300.0, &t300, &v300);
  const double v0 = v300 - units::kmh_to_ms(3.0);
  check("(b+c+d)", drive(plant.motion, noisy(9), false, 300.0, v0, t300), kArrivalBound_s);
  check("(b+c+d) + ladder", drive(plant.motion, noisy(9), true, 300.0, v0, t300), kLadderBound_s);
}

}  // namespace
}  // namespace ecorail
