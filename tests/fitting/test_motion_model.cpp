// The fits' equation of motion against the engine's integrator: with the true parameters and a
// noise-free synthetic log, integrating each used interval from the logged speed lands on the
// next logged speed, and the equation-error residuals vanish to the accuracy of the trapezoid
// rule. If the two models disagreed, calibration would read the disagreement as resistance.
// The largest single-interval errors (about 0.026 m/s, half the 0.2 km/h noise of the
// acceptance logs) come from a gradient change or the 51.5 km/h traction kink falling inside
// the second, which a one-second log cannot place.
#include <gtest/gtest.h>

#include <cmath>

#include "fitting/equation_error.hpp"
#include "fitting/log_prep.hpp"
#include "fitting/motion_model.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

TEST(MotionModel, MatchesTheEngineIntegratorOnNoiseFreeLogs) {
  const physics::Train truth = test::truth_train();
  SyntheticLogOptions o;
  o.rows = 1500;
  o.speed_noise_kmh = 0.0;
  o.seed = 3;
  const SyntheticLog log = make_synthetic_log(truth, o);
  const PreparedData data = prepare_logs({log.log}, truth, PrepOptions{});
  ModelConstants k;
  k.gravity_m_s2 = truth.gravity_m_s2;
  k.max_accel_m_s2 = truth.max_accel_m_s2;
  k.max_decel_m_s2 = truth.max_decel_m_s2;
  const ParamVector p = params_from_train(truth);
  double max_oe = 0.0, ss_oe = 0.0, max_ee = 0.0, ss_ee = 0.0;
  int n = 0;
  for (const auto& l : data.logs) {
    for (std::size_t i = 0; i < l.intervals.size(); ++i) {
      if (l.intervals[i] != IntervalStatus::Used) continue;
      const double v1 =
          integrate_interval(p.data(), k, l.rows[i].speed_ms, l.rows[i], l.rows[i + 1]);
      const double e = v1 - l.rows[i + 1].speed_ms;
      const double r = equation_error_residual(l.rows[i], l.rows[i + 1], k, p, nullptr);
      max_oe = std::max(max_oe, std::abs(e));
      max_ee = std::max(max_ee, std::abs(r));
      ss_oe += e * e;
      ss_ee += r * r;
      ++n;
    }
  }
  ASSERT_GT(n, 1000);
  std::printf(
      "one-interval speed error: rms %.2e max %.2e m/s; equation error rms %.2e max %.2e "
      "m/s^2 over %d intervals\n",
      std::sqrt(ss_oe / n), max_oe, std::sqrt(ss_ee / n), max_ee, n);
  EXPECT_LT(std::sqrt(ss_oe / n), 2e-3);
  EXPECT_LT(max_oe, 4e-2);
  EXPECT_LT(std::sqrt(ss_ee / n), 2e-3);
}

}  // namespace
}  // namespace ecorail::fitting
