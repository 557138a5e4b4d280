// The optional parts of calibration: a traction-force scale (the logged force overstates the
// applied one), notch columns instead of forces, the equation-error-only and Huber variants,
// and the train file a result turns into.
#include <gtest/gtest.h>

#include <cmath>

#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

SyntheticLog synthetic_from(const physics::Train& truth, std::uint64_t seed) {
  SyntheticLogOptions o;
  o.rows = 2000;
  o.corrupt_fraction = 0.01;
  o.seed = seed;
  return make_synthetic_log(truth, o);
}

TEST(CalibrationOptions, RecoversATractionScale) {
  // The train pulls with 95 % of what its log records.
  physics::Train truth = test::truth_train();
  auto pieces = truth.traction.pieces();
  for (auto& p : pieces) {
    for (auto& c : p.coeffs_kN) c *= 0.95;
  }
  truth.traction = physics::ForceEnvelope::piecewise(pieces);
  SyntheticLog log = synthetic_from(truth, 21);
  for (auto& r : log.log.rows) r.traction_force_N /= 0.95;
  CalibrationOptions o;
  o.fit_traction_scale = true;
  const Summary s = calibrate({log.log}, test::reference_train(), o);
  for (const auto& r : s.results) {
    const auto& k = r.params[kTractionScale];
    SCOPED_TRACE(std::string(method_name(r.method)));
    EXPECT_FALSE(k.fixed);
    EXPECT_NEAR(k.value, 0.95, 2.5 * k.se) << k.value << " +- " << k.se;
    EXPECT_NEAR(r.params[kRotatingMassFactor].value, 0.08, 2.5 * r.params[kRotatingMassFactor].se);
  }
  // The calibrated train carries the scaled envelope and the fitted resistance.
  const physics::Train t = calibrated_train(test::reference_train(), s.primary());
  EXPECT_NEAR(t.traction.force_kN_at_kmh(30.0), 203.0 * s.primary().params[kTractionScale].value,
              1e-9);
  EXPECT_DOUBLE_EQ(t.davis.A, s.primary().params[kDavisA].value);
  EXPECT_DOUBLE_EQ(t.rotating_mass_factor, s.primary().params[kRotatingMassFactor].value);
  EXPECT_DOUBLE_EQ(t.mass_kg, test::reference_train().mass_kg);  // mass not fitted
}

TEST(CalibrationOptions, NotchColumnsReadThroughTheBaseEnvelopes) {
  // Replace the forces by notches: full traction = 1, full braking = -1, coasting 0.
  const physics::Train truth = test::truth_train();
  SyntheticLog log = synthetic_from(truth, 22);
  Log notched = log.log;
  notched.has_traction = notched.has_braking = false;
  notched.has_notch = true;
  for (auto& r : notched.rows) {
    r.notch = r.traction_force_N > 0.0 ? 1.0 : r.braking_force_N > 0.0 ? -1.0 : 0.0;
    r.traction_force_N = r.braking_force_N = kUnknown;
  }
  CalibrationOptions o;
  o.method = Method::OutputError;
  const Summary s = calibrate({notched}, test::reference_train(), o);
  const auto& r = s.primary();
  EXPECT_NEAR(r.params[kRotatingMassFactor].value, 0.08, 0.01);
  for (double v = 30.0; v <= 70.0; v += 10.0) {
    const double want = truth.gravity_m_s2 * truth.davis_N_per_kN(v / 3.6) / 1000.0 / 1.08;
    EXPECT_NEAR(r.coasting_decel_m_s2(v, truth.gravity_m_s2), want, 0.005) << v;
  }
}

TEST(CalibrationOptions, EquationErrorAloneAndHuberLoss) {
  const SyntheticLog log = synthetic_from(test::truth_train(), 23);
  CalibrationOptions o;
  o.method = Method::EquationError;
  o.loss = LossKind::Huber;
  o.loss_scale = 1.345;
  const Summary s = calibrate({log.log}, test::reference_train(), o);
  ASSERT_EQ(s.results.size(), 1u);
  EXPECT_EQ(s.primary().method, Method::EquationError);
  const auto& rho = s.primary().params[kRotatingMassFactor];
  EXPECT_NEAR(rho.value, 0.08, 2.0 * rho.se);
  EXPECT_FALSE(s.BriefReport().empty());
}

}  // namespace
}  // namespace ecorail::fitting
