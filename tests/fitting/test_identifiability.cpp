// Logs that cannot identify the parameters are clear errors naming the parameters, never a
// silent bad fit: too few rows, no rows of known force (mass factor against resistance scale),
// no gradient for a fitted gradient scale, mass against traction scale and mass factor.
#include <gtest/gtest.h>

#include <string>

#include "data/input_error.hpp"
#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

Log synthetic(int rows = 1200) {
  SyntheticLogOptions o;
  o.rows = rows;
  o.seed = 5;
  return make_synthetic_log(test::truth_train(), o).log;
}

std::string calibration_error(const std::vector<Log>& logs, const CalibrationOptions& o) {
  try {
    calibrate(logs, test::reference_train(), o);
  } catch (const data::InputError& e) {
    return e.what();
  }
  return "";
}

bool names(const std::string& msg, const std::string& word) {
  return msg.find(word) != std::string::npos;
}

TEST(Identifiability, TooFewRowsNamesTheParameters) {
  const Log log = parse_log(
      "time_s,speed_kmh,gradient_permille,traction_force_kN,braking_force_kN\n"
      "0,30,0,0,0\n1,29.6,0,0,0\n2,29.2,1,0,0\n",
      "short.csv");
  const std::string msg = calibration_error({log}, CalibrationOptions{});
  std::cout << msg << "\n";
  ASSERT_FALSE(msg.empty());
  EXPECT_TRUE(names(msg, "short.csv"));
  EXPECT_TRUE(names(msg, "davis_A"));
  EXPECT_TRUE(names(msg, "rotating_mass_factor"));
  EXPECT_TRUE(names(msg, "not identifiable"));
}

TEST(Identifiability, CoastingOnlyCannotSeparateInertiaFromResistance) {
  // Keep only the rows where the train coasts (and the dwells): no row has a known force.
  Log log = synthetic();
  std::vector<LogRow> coasting;
  for (const auto& r : log.rows) {
    if (r.traction_force_N == 0.0 && r.braking_force_N == 0.0) coasting.push_back(r);
  }
  log.rows = coasting;
  CalibrationOptions o;
  o.gradient_scale = GradientScaleMode::Fit;
  const std::string msg = calibration_error({log}, o);
  std::cout << msg << "\n";
  ASSERT_FALSE(msg.empty());
  EXPECT_TRUE(names(msg, "rotating_mass_factor"));
  EXPECT_TRUE(names(msg, "davis_A"));
  EXPECT_TRUE(names(msg, "known traction or braking force"));
  // Holding the mass factor makes the same log usable.
  o.fixed[kRotatingMassFactor] = true;
  EXPECT_NO_THROW(calibrate({log}, test::reference_train(), o));
}

TEST(Identifiability, LevelTrackCannotFitAGradientScale) {
  Log log = synthetic();
  for (auto& r : log.rows) r.gradient_permille = 0.0;
  CalibrationOptions o;
  o.method = Method::EquationError;
  o.gradient_scale = GradientScaleMode::Fit;
  const std::string msg = calibration_error({log}, o);
  std::cout << msg << "\n";
  EXPECT_TRUE(names(msg, "gradient_scale"));
  EXPECT_TRUE(names(msg, "no gradient"));
  EXPECT_FALSE(names(msg, "davis_A"));
  // In the default mode the scale is simply held, with a note.
  o.gradient_scale = GradientScaleMode::Auto;
  const Summary s = calibrate({log}, test::reference_train(), o);
  EXPECT_TRUE(s.results.at(0).params[kGradientScale].fixed);
  ASSERT_FALSE(s.notes.empty());
  EXPECT_TRUE(names(s.notes.front(), "gradient_scale held"));
}

TEST(Identifiability, MassWithTractionScaleAndMassFactor) {
  // Without braking rows, mass and traction scale act only through their ratio.
  Log log = synthetic();
  std::vector<LogRow> rows;
  for (const auto& r : log.rows) {
    if (r.braking_force_N == 0.0) rows.push_back(r);
  }
  log.rows = rows;
  CalibrationOptions o;
  o.method = Method::EquationError;
  o.fit_mass = true;
  o.fit_traction_scale = true;
  o.fixed[kRotatingMassFactor] = true;
  const std::string msg = calibration_error({log}, o);
  std::cout << msg << "\n";
  EXPECT_TRUE(names(msg, "mass_t"));
  EXPECT_TRUE(names(msg, "traction_scale"));
  EXPECT_TRUE(names(msg, "ratio"));
}

TEST(Identifiability, EveryParameterFixedIsAnError) {
  CalibrationOptions o;
  o.fixed.fill(true);
  EXPECT_TRUE(names(calibration_error({synthetic(300)}, o), "at least one parameter"));
}

}  // namespace
}  // namespace ecorail::fitting
