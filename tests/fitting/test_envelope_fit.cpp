// Envelope fitting: sampling the reference traction and braking envelopes with noise and fitting
// must recover the breakpoints (51.5 and 77 km/h) within 0.5 km/h and the forces within 1 %;
// the piecewise form must beat the constant-power form on them, and a constant-power curve
// must be recognised as such. Bad point files are clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "data/input_error.hpp"
#include "fitting/envelope_fit.hpp"
#include "fitting_test_support.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {
namespace {

std::vector<EnvelopePoint> sample(const physics::ForceEnvelope& e, double noise_fraction,
                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<EnvelopePoint> pts;
  int row = 2;
  for (double v = 0.0; v <= 80.0 + 1e-9; v += 0.5) {
    const double f = e.force_kN_at_kmh(v);
    pts.push_back({v, f * (1.0 + noise_fraction * n(rng)), row++});
  }
  return pts;
}

void expect_recovers(const physics::ForceEnvelope& truth, int degree, double breakpoint,
                     std::uint64_t seed) {
  EnvelopeFitOptions o;
  o.degree = degree;
  const EnvelopeFitResult r = fit_envelope(sample(truth, 0.003, seed), o);
  std::cout << r.report(EnvelopeKind::Traction);
  EXPECT_EQ(r.better, EnvelopeForm::Piecewise);
  EXPECT_NEAR(r.piecewise.breakpoint_kmh, breakpoint, 0.5);
  EXPECT_LT(r.piecewise.breakpoint_kmh_se, 0.5);
  const physics::ForceEnvelope fitted = to_force_envelope(r.piecewise, 80.0);
  for (double v = 0.0; v <= 80.0; v += 0.25) {
    const double want = truth.force_kN_at_kmh(v);
    EXPECT_NEAR(fitted.force_kN_at_kmh(v), want, 0.01 * want) << v << " km/h";
  }
}

TEST(EnvelopeFit, RecoversReferenceTraction) {
  expect_recovers(test::reference_train().traction, 3, 51.5, 11);
}

TEST(EnvelopeFit, RecoversReferenceBraking) {
  expect_recovers(test::reference_train().braking, 2, 77.0, 12);
}

TEST(EnvelopeFit, RecognisesConstantPower) {
  // 300 kN up to P / Fmax = 2000 kW / 300 kN = 6.67 m/s = 24 km/h, then 2000 kW / v.
  const physics::ForceEnvelope truth =
      physics::ForceEnvelope::piecewise({{0.0, 80.0, {300.0}}}, 2000.0);
  const EnvelopeFitResult r = fit_envelope(sample(truth, 0.003, 13), EnvelopeFitOptions{});
  EXPECT_EQ(r.better, EnvelopeForm::ConstantPower);
  EXPECT_NEAR(r.power.power_kW, 2000.0, 3.0 * r.power.power_kW_se + 1e-9);
  EXPECT_NEAR(r.power.force_max_kN, 300.0, 3.0 * r.power.force_max_kN_se + 1e-9);
  EXPECT_NEAR(r.power.breakpoint_kmh, 24.0, 0.3);
}

TEST(EnvelopeFit, StandardErrorsCoverTheTruth) {
  // The expanded coefficients of the exact polynomial above the breakpoint lie within a few
  // standard errors of the fitted ones (braking: quadratic, exactly representable).
  const physics::Train ref = test::reference_train();
  EnvelopeFitOptions o;
  o.degree = 2;
  const EnvelopeFitResult r = fit_envelope(sample(ref.braking, 0.003, 14), o);
  const auto& want = ref.braking.pieces().back().coeffs_kN;
  ASSERT_EQ(r.piecewise.coeffs_kN.size(), want.size());
  for (std::size_t j = 0; j < want.size(); ++j) {
    EXPECT_NEAR(r.piecewise.coeffs_kN[j], want[j], 4.0 * r.piecewise.coeffs_kN_se[j]) << j;
  }
}

TEST(EnvelopeFit, BadPointsAreClearErrors) {
  EXPECT_THROW(parse_envelope_points("speed_kmh,force\n1,2\n", "p.csv"), data::InputError);
  try {
    parse_envelope_points("speed_kmh,force_kN\n1,2\n2,-3\n", "p.csv");
    FAIL();
  } catch (const data::InputError& e) {
    EXPECT_EQ(e.row(), 3);
    EXPECT_EQ(e.field(), "force_kN");
  }
  const auto few = parse_envelope_points("speed_kmh,force_kN\n1,2\n2,3\n3,3\n", "p.csv");
  EXPECT_THROW(fit_envelope(few, EnvelopeFitOptions{}), data::InputError);
}

}  // namespace
}  // namespace ecorail::fitting
