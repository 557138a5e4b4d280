// The moving speed cap: a follower behind a train that stops on the line, with the separation
// cap v <= sqrt(2 L b). The follower must never exceed the cap, must stop behind the train
// ahead, and, when the train ahead moves on, wait and then complete its run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics/motion.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"
#include "physics_fixtures.hpp"

namespace ecorail::physics {
namespace {

constexpr double kBrake_m_s2 = 0.6;  // separation braking, below the train's own

// A train ahead that runs at 12 m/s from 700 m, stops at `stop_m` and, if `leave_s` is finite,
// leaves again at that clock time at 12 m/s.
struct Leader {
  double stop_m = 1500.0;
  double leave_s = INFINITY;
  double position(double t) const {
    const double arrive = (stop_m - 700.0) / 12.0;
    if (t < arrive) return 700.0 + 12.0 * t;
    if (t < leave_s) return stop_m;
    return stop_m + 12.0 * (t - leave_s);
  }
  SpeedCap cap() const {
    return [*this](double t, double s) {
      return std::sqrt(2.0 * kBrake_m_s2 * std::max(0.0, position(t) - s));
    };
  }
};

class SpeedCapTest : public ::testing::Test {
 protected:
  SpeedCapTest()
      : train_(data::default_train()),
        route_(test::straight_track(0.0, 3000.0, 80.0)),
        envelope_(train_, route_),
        motion_(train_, route_, envelope_) {}
  Train train_;
  Route route_;
  SpeedEnvelope envelope_;
  Motion motion_;
};

TEST_F(SpeedCapTest, FollowerStopsBehindAStoppedTrainAndNeverExceedsTheCap) {
  const Leader leader;
  SimulationOptions opt;
  opt.speed_cap = leader.cap();
  opt.max_wait_s = 30.0;
  const SimulationResult sim = simulate(motion_, ControlProgram{{0.0, Control::MaxTraction}}, opt);
  EXPECT_TRUE(sim.stopped_early);
  EXPECT_LE(sim.end_position_m, leader.stop_m);
  EXPECT_GT(sim.end_position_m, leader.stop_m - 1.0);  // it closes up, as the cap allows
  EXPECT_GT(sim.cap_binding_m, 100.0);
  EXPECT_LE(sim.max_cap_overspeed_ms, 1e-9);
  // Independently of the simulator's own bookkeeping: every trace point under the cap.
  for (const TracePoint& p : sim.trace) {
    EXPECT_LE(p.v_ms, leader.cap()(p.t_s, p.s_m) + 1e-9) << "at " << p.s_m << " m";
    EXPECT_LE(p.s_m, leader.position(p.t_s) + 1e-9);
  }
}

TEST_F(SpeedCapTest, FollowerWaitsWhileHeldAndArrivesWhenTheCapLifts) {
  Leader leader;
  leader.leave_s = 200.0;
  SimulationOptions opt;
  opt.speed_cap = leader.cap();
  const SimulationResult sim = simulate(motion_, ControlProgram{{0.0, Control::MaxTraction}}, opt);
  EXPECT_FALSE(sim.stopped_early);
  EXPECT_LT(std::abs(sim.stop_error_m), 0.05);
  EXPECT_GT(sim.cap_wait_s, 10.0);
  EXPECT_LE(sim.max_cap_overspeed_ms, 1e-9);
  // It could not have passed the place where the train ahead stood before that train left.
  double departed = INFINITY;
  for (const TracePoint& p : sim.trace) {
    if (p.s_m > leader.stop_m + 0.5) {
      departed = std::min(departed, p.t_s);
    }
  }
  EXPECT_GT(departed, leader.leave_s);
  // The same run without a cap is faster: the cap cost time, never broke a limit.
  const SimulationResult free_run =
      simulate(motion_, ControlProgram{{0.0, Control::MaxTraction}}, SimulationOptions{});
  EXPECT_LT(free_run.running_time_s, sim.running_time_s);
  EXPECT_LE(sim.max_overspeed_ms, 1e-6);
}

TEST_F(SpeedCapTest, AnInfiniteCapChangesNothing) {
  SimulationOptions opt;
  opt.speed_cap = [](double, double) { return INFINITY; };
  const ControlProgram program{{0.0, Control::MaxTraction}, {800.0, Control::Coast}};
  const SimulationResult capped = simulate(motion_, program, opt);
  const SimulationResult plain = simulate(motion_, program, SimulationOptions{});
  EXPECT_DOUBLE_EQ(capped.running_time_s, plain.running_time_s);
  EXPECT_DOUBLE_EQ(capped.energy.traction_work_J, plain.energy.traction_work_J);
  EXPECT_EQ(capped.cap_binding_m, 0.0);
}

}  // namespace
}  // namespace ecorail::physics
