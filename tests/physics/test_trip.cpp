// Trip: a timed run over several sections. The power bins are checked against the trip's
// energy ledger (conservation, several steps, odd grid origins) and, bin by bin around every
// regime change, against an independent numerical integral of force x speed from state_at.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "physics/motion.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/trip.hpp"

namespace ecorail::physics {
namespace {

struct SectionRun {
  Route route;
  SimulationResult sim;
};

// A6 -> A7 -> A8 with full traction, coasting and the envelope's braking, plus a speed-hold
// stretch on the second section, so the trip has every regime and a dwell.
class TripTest : public ::testing::Test {
 protected:
  void SetUp() override {
    train_ = data::default_train();
    const data::Line line = data::default_line();
    const char* stops[] = {"A6", "A7", "A8"};
    const ControlProgram programs[] = {
        {{0.0, Control::MaxTraction}, {250.0, Control::Coast}, {900.0, Control::MaxTraction}},
        {{0.0, Control::MaxTraction}, {300.0, Control::Hold}, {700.0, Control::MaxTraction}}};
    for (int i = 0; i < 2; ++i) {
      runs_.push_back({data::build_route(line, stops[i], stops[i + 1], train_), {}});
    }
    for (int i = 0; i < 2; ++i) {
      const SpeedEnvelope envelope(train_, runs_[i].route);
      const Motion motion(train_, runs_[i].route, envelope);
      runs_[i].sim = simulate(motion, programs[i], SimulationOptions{});
      ASSERT_LT(std::abs(runs_[i].sim.stop_error_m), 0.01);
    }
    trip_ = Trip({{&runs_[0].route, &runs_[0].sim, 40.0}, {&runs_[1].route, &runs_[1].sim, 0.0}},
                 kDeparture, train_.regen_efficiency);
  }

  static constexpr double kDeparture = 1234.56;
  Train train_;
  std::vector<SectionRun> runs_;
  Trip trip_;
};

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

TEST_F(TripTest, StopsAndTimesAreLaidOnTheClock) {
  const auto stops = trip_.stops();
  ASSERT_EQ(stops.size(), 3u);
  const double t1 = runs_[0].sim.running_time_s;
  EXPECT_DOUBLE_EQ(stops[0].departure_s, kDeparture);
  EXPECT_NEAR(stops[1].arrival_s, kDeparture + t1, 1e-9);
  EXPECT_NEAR(stops[1].departure_s, kDeparture + t1 + 40.0, 1e-9);
  EXPECT_NEAR(stops[2].arrival_s, kDeparture + t1 + 40.0 + runs_[1].sim.running_time_s, 1e-9);
  EXPECT_NEAR(stops[1].position_m, runs_[0].route.length_m(), 1e-9);
  EXPECT_NEAR(trip_.time_at(stops[1].position_m), stops[1].arrival_s, 1e-6);
  const TripState dwelling = trip_.state_at(stops[1].arrival_s + 20.0);
  EXPECT_TRUE(dwelling.dwelling);
  EXPECT_EQ(dwelling.speed_ms, 0.0);
  EXPECT_NEAR(dwelling.position_m, stops[1].position_m, 1e-9);
  EXPECT_TRUE(trip_.state_at(kDeparture - 5.0).before_departure);
  EXPECT_TRUE(trip_.state_at(trip_.arrival_s() + 5.0).after_arrival);
}

TEST_F(TripTest, TimeAtInvertsStateAt) {
  for (double t = kDeparture + 0.5; t < trip_.arrival_s(); t += 7.3) {
    const TripState st = trip_.state_at(t);
    if (st.dwelling || st.speed_ms < 0.5) continue;
    EXPECT_NEAR(trip_.time_at(st.position_m), t, 1e-6) << "t = " << t;
  }
}

TEST_F(TripTest, StateAtMatchesTheSamplesAndStaysBetweenThem) {
  const auto& samples = trip_.samples();
  for (std::size_t k = 1; k < samples.size(); k += 997) {
    const TripState st = trip_.state_at(kDeparture + samples[k].t_s);
    EXPECT_NEAR(st.position_m, samples[k].s_m, 1e-9);
    if (!samples[k].dwelling) {
      EXPECT_NEAR(st.speed_ms, samples[k].v_ms, 1e-9);
    }
  }
}

TEST_F(TripTest, PowerBinsAddUpToTheLedgerForEveryStep) {
  const EnergyLedger& ledger = trip_.ledger();
  ASSERT_GT(ledger.brake_work_J, 0.0);
  for (double step : {1.0, 0.1, 0.01, 0.37, 3.0}) {
    const PowerBins bins = trip_.power_bins(step);
    EXPECT_LE(bins.start_s, kDeparture);
    EXPECT_GE(bins.start_s + step * bins.traction_W.size(), trip_.arrival_s());
    EXPECT_NEAR(sum(bins.traction_W) * step, ledger.traction_work_J, 1e-9 * ledger.traction_work_J)
        << "step " << step;
    EXPECT_NEAR(sum(bins.braking_W) * step, ledger.brake_work_J, 1e-9 * ledger.brake_work_J)
        << "step " << step;
    EXPECT_NEAR(sum(bins.regen_W) * step, ledger.regen_J, 1e-9 * ledger.regen_J) << "step " << step;
    // An odd origin, not aligned with the departure: the same totals.
    const PowerBins odd =
        trip_.power_bins(kDeparture - 0.123, step,
                         static_cast<std::size_t>((trip_.arrival_s() - kDeparture) / step) + 2);
    EXPECT_NEAR(sum(odd.traction_W) * step, ledger.traction_work_J, 1e-9 * ledger.traction_work_J);
  }
}

// Energy between two clock times by integrating force x speed from state_at (midpoint rule):
// independent of the bin splitting, which works on distances.
double integrated_energy(const Trip& trip, double a, double b, bool traction) {
  const int n = 40000;  // fine enough that a force jump inside a sub-interval costs < 1e-5
  const double h = (b - a) / n;
  double e = 0.0;
  for (int i = 0; i < n; ++i) {
    const TripState st = trip.state_at(a + (i + 0.5) * h);
    const double p = st.force_N * st.speed_ms;
    if (traction ? p > 0.0 : p < 0.0) e += std::abs(p) * h;
  }
  return e;
}

TEST_F(TripTest, BinsStraddlingEveryRegimeChangeHoldTheExactEnergy) {
  const auto& samples = trip_.samples();
  int changes = 0;
  for (std::size_t k = 2; k < samples.size(); ++k) {
    if (samples[k].regime == samples[k - 1].regime || samples[k].dwelling ||
        samples[k - 1].dwelling)
      continue;
    ++changes;
    const double change = kDeparture + samples[k - 1].t_s;
    for (double step : {1.0, 0.1}) {
      // One bin with the change 30 % into it.
      const double start = change - 0.3 * step;
      const PowerBins bins = trip_.power_bins(start, step, 1);
      const double traction = integrated_energy(trip_, start, start + step, true);
      const double braking = integrated_energy(trip_, start, start + step, false);
      const double scale = 1e-4 * (traction + braking) + 1.0;  // 1 J floor
      EXPECT_NEAR(bins.traction_W[0] * step, traction, scale) << "change at " << change;
      EXPECT_NEAR(bins.braking_W[0] * step, braking, scale) << "change at " << change;
    }
  }
  EXPECT_GE(changes, 4);
}

TEST_F(TripTest, ShiftedTripSharesTheTrajectoryAndMovesTheBins) {
  const Trip later = trip_.shifted(kDeparture + 600.0);
  EXPECT_EQ(&later.samples(), &trip_.samples());  // no copy, no re-simulation
  EXPECT_DOUBLE_EQ(later.arrival_s(), trip_.arrival_s() + 600.0);
  const PowerBins a = trip_.power_bins(1000.0, 1.0, 400);
  const PowerBins b = later.power_bins(1600.0, 1.0, 400);
  for (std::size_t i = 0; i < a.traction_W.size(); ++i) {
    EXPECT_NEAR(a.traction_W[i], b.traction_W[i], 1e-6 * (1.0 + a.traction_W[i]));
    EXPECT_NEAR(a.braking_W[i], b.braking_W[i], 1e-6 * (1.0 + a.braking_W[i]));
  }
  const TripState x = trip_.state_at(kDeparture + 77.7);
  const TripState y = later.state_at(kDeparture + 677.7);
  EXPECT_NEAR(x.position_m, y.position_m, 1e-9);
}

}  // namespace
}  // namespace ecorail::physics
