// Route terms of TTOBench tracks and trains, against hand integrals: a train length holds a
// limit until the tail has passed and averages the gradient; clothoids; Roeckl; tunnel drag.
#include <gtest/gtest.h>

#include <cmath>

#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/ttobench_io.hpp"
#include "data/ttobench_route_terms.hpp"
#include "physics/motion.hpp"
#include "physics/speed_envelope.hpp"

namespace ecorail::data {
namespace {

Line line_of(const std::string& extra) {
  return line_from_ttobench(R"J({
  "metadata": {"id": "t", "library version": "TTOBench v1.4"},
  "stops": {"unit": "m", "values": [0, 2000]},
  "speed limits": {"units": {"position": "m", "velocity": "km/h"},
                   "values": [[0, 50], [1000, 80]]},
  "gradients": {"units": {"position": "m", "slope": "permil"},
                "values": [[0, 0], [1000, 10]]})J" +
                                extra + "}",
                            "t.json");
}

physics::Train train_of(double length_m) {
  physics::Train t;
  t.name = "t";
  t.mass_kg = 100000.0;
  t.gravity_m_s2 = 9.81;
  t.max_speed_ms = 30.0;
  t.length_m = length_m;
  t.traction = physics::ForceEnvelope::table({{0.0, 200.0}}, 2000.0);
  t.braking = physics::ForceEnvelope::table({{0.0, 200.0}}, 2000.0);
  t.tunnel_drag = {{24.0, 0.0012}, {40.0, 0.0006}};
  return t;
}

// Integral over [a, b] of a segment field.
template <class F>
double integral(const physics::Route& r, double a, double b, F field) {
  double sum = 0.0;
  for (const auto& s : r.segments()) {
    const double lo = std::max(a, s.start_m);
    const double hi = std::min(b, s.end_m);
    if (hi > lo) sum += field(s) * (hi - lo);
  }
  return sum;
}

TEST(TtobenchRouteTerms, LimitHoldsUntilTheTailHasPassed) {
  const physics::Route r = build_route(line_of(""), "S0", "S1", train_of(100.0));
  EXPECT_DOUBLE_EQ(r.speed_limit_ms(1099.0), 50.0 / 3.6);
  EXPECT_DOUBLE_EQ(r.speed_limit_ms(1101.0), 80.0 / 3.6);
  // A point train takes the rise at once.
  const physics::Route p = build_route(line_of(""), "S0", "S1", train_of(0.0));
  EXPECT_DOUBLE_EQ(p.speed_limit_ms(1001.0), 80.0 / 3.6);
}

TEST(TtobenchRouteTerms, GradientIsAveragedOverTheTrain) {
  const physics::Route r = build_route(line_of(""), "S0", "S1", train_of(100.0));
  const auto g = [](const physics::RouteSegment& s) { return s.gradient_permille; };
  // Entering the 10 per mille climb the felt gradient ramps from 0 to 10 over 100 m: its
  // integral there is 500 per mille m, and 10 * 900 after; 0 before.
  EXPECT_NEAR(integral(r, 0.0, 1000.0, g), 0.0, 1e-9);
  EXPECT_NEAR(integral(r, 1000.0, 1100.0, g), 500.0, 1e-9);
  EXPECT_NEAR(integral(r, 1100.0, 2000.0, g), 9000.0, 1e-9);
  // Pieces under the ramp are at most kMaxPiece_m long.
  for (const auto& s : r.segments()) {
    if (s.start_m >= 1000.0 && s.end_m <= 1100.0) {
      EXPECT_LE(s.end_m - s.start_m, kMaxPiece_m);
    }
  }
  // Run the other way: the climb is a descent felt from 1000 m (km post 1000) on.
  const physics::Route back = build_route(line_of(""), "S1", "S0", train_of(100.0));
  EXPECT_NEAR(integral(back, 0.0, 1000.0, g), -10000.0 + 0.0, 1e-9);
  EXPECT_NEAR(integral(back, 1000.0, 1100.0, g), -500.0, 1e-9);
}

TEST(TtobenchRouteTerms, ClothoidCurveResistanceIsItsExactMean) {
  // Straight, then a clothoid to R = 500 m over 100 m (from 500 m), 500 m arc, straight.
  const Line line = line_of(R"J(,
  "curvatures": {"units": {"position": "m", "radius at start": "m", "radius at end": "m"},
                 "values": [[0, "infinity", "infinity"], [500, "infinity", 500],
                            [600, 500, 500], [1100, "infinity", "infinity"]]})J");
  const physics::Route r = build_route(line, "S0", "S1", train_of(0.0));
  const auto c = [](const physics::RouteSegment& s) {
    return s.track_N_per_kN() - s.gradient_permille;
  };
  // 600/R: the clothoid's mean curvature is half of 1/500 -> 0.6 N/kN over 100 m = 60.
  EXPECT_NEAR(integral(r, 500.0, 600.0, c), 60.0, 1e-9);
  EXPECT_NEAR(integral(r, 600.0, 1100.0, c), 1.2 * 500.0, 1e-9);
  EXPECT_NEAR(integral(r, 1100.0, 2000.0, c), 0.0, 1e-12);
  // Roeckl: 500 / (R - 30) on the arc, and the clothoid's integral of 500 k / (1 - 30 k).
  Line roeckl = line;
  roeckl.curve_formula = CurveFormula::Roeckl;
  const physics::Route rr = build_route(roeckl, "S0", "S1", train_of(0.0));
  EXPECT_NEAR(integral(rr, 600.0, 1100.0, c), 500.0 / 470.0 * 500.0, 1e-9);
  // int_0^100 500 k(x) / (1 - 30 k(x)) dx with k = x / 50000: closed form.
  const double a = 1.0 / 50000.0;
  const auto F = [&](double x) {
    const double u = 1.0 - 30.0 * a * x;
    return 500.0 / a * (u - std::log(u)) / 900.0;
  };
  EXPECT_NEAR(integral(rr, 500.0, 600.0, c), F(100.0) - F(0.0), 1e-6);
  EXPECT_NEAR(curve_resistance_N_per_kN(1.0 / 200.0, CurveFormula::Roeckl), 650.0 / 145.0, 1e-12);
}

TEST(TtobenchRouteTerms, TunnelDragFromTheTrainsTable) {
  const Line line = line_of(R"J(,
  "tunnels": {"units": {"position": "m", "length": "m", "cross section": "m^2"},
              "values": [[200, 300, 40], [1200, 100, 32]]})J");
  const physics::Train t = train_of(0.0);
  const physics::Route r = build_route(line, "S0", "S1", t);
  const auto c = [](const physics::RouteSegment& s) { return s.tunnel_drag_N_per_kN_kmh2; };
  // 0.0006 kN/(km/h)^2 = 0.6 N/(km/h)^2 in the 40 m^2 tunnel, per kN of this train's weight.
  const double spec40 = 0.6 * 1000.0 / (100000.0 * 9.81);
  EXPECT_NEAR(integral(r, 200.0, 500.0, c), spec40 * 300.0, 1e-12);
  // 32 m^2 lies half way between 24 and 40: 0.0009.
  EXPECT_NEAR(integral(r, 1200.0, 1300.0, c), 1.5 * spec40 * 100.0, 1e-12);
  EXPECT_NEAR(integral(r, 0.0, 200.0, c) + integral(r, 500.0, 1200.0, c), 0.0, 1e-15);
  // The motion kernel adds C v^2: at 72 km/h in the 40 m^2 tunnel, 0.6 N * 72^2.
  const physics::SpeedEnvelope env(t, r, 1.0);
  const physics::Motion m(t, r, env);
  const physics::RouteSegment& in = r.at(300.0);
  EXPECT_NEAR(m.resistance_N(20.0, in) - t.resistance_N(20.0, in.track_N_per_kN()),
              0.6 * 72.0 * 72.0, 1e-9);
  // A train without tunnel data is refused on a line with tunnels.
  physics::Train bare = t;
  bare.tunnel_drag.clear();
  EXPECT_THROW(build_route(line, "S0", "S1", bare), InputError);
  // A cross-section outside the table is refused.
  const Line wide = line_of(R"J(,
  "tunnels": {"units": {"position": "m", "length": "m", "cross section": "m^2"},
              "values": [[200, 300, 60]]})J");
  EXPECT_THROW(build_route(wide, "S0", "S1", t), InputError);
}

TEST(TtobenchRouteTerms, LimitsAboveTheTrainsMaximumMeanTheMaximum) {
  physics::Train slow = train_of(0.0);
  slow.max_speed_ms = 60.0 / 3.6;
  const physics::Route r = build_route(line_of(""), "S0", "S1", slow);
  EXPECT_DOUBLE_EQ(r.speed_limit_ms(1500.0), 60.0 / 3.6);
  EXPECT_DOUBLE_EQ(r.speed_limit_ms(500.0), 50.0 / 3.6);
}

}  // namespace
}  // namespace ecorail::data
