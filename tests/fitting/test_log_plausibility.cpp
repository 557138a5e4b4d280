// Physically impossible log rows are refused before any fit: a speed above the
// train's maximum (a tenfold typo, 615 km/h for an 80 km/h train) or a speed change the
// envelopes cannot produce is an InputError naming file, row and the speed column; the
// published tables, ecorail's own per-second tables and synthetic logs with the gross errors
// the robust loss is for pass. A fit that ends without convergence is never the result, and
// ecorail's own table carries the curve radius that calibrate reads.
#include <gtest/gtest.h>

#include "data/input_error.hpp"
#include "fitting/calibration.hpp"
#include "fitting/log_plausibility.hpp"
#include "fitting/log_reader.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

// The published A6 -> A7 table with row `row` (file line) given speed_cm_s `cm_s`.
Log published_with_speed(int row, double cm_s) {
  Log log = read_log(test::published_table("seed_profile_A6_A7_110s.csv"));
  for (auto& r : log.rows) {
    if (r.source_row == row) r.speed_ms = cm_s / 100.0;
  }
  return log;
}

data::InputError error_of(const Log& log) {
  try {
    check_log_plausible(log, test::reference_train());
  } catch (const data::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error";
  return data::InputError("", 0, "", "");
}

TEST(LogPlausibility, PublishedTablesPass) {
  for (const char* name : {"seed_profile_A6_A7_110s.csv", "seed_profile_A6_A8_220s.csv"}) {
    EXPECT_NO_THROW(
        check_log_plausible(read_log(test::published_table(name)), test::reference_train()))
        << name;
  }
}

TEST(LogPlausibility, TenfoldSpeedTypoIsRefusedByRow) {
  const Log log = published_with_speed(40, 17083.3);  // 615 km/h instead of 61.5
  const auto e = error_of(log);
  EXPECT_EQ(e.row(), 40);
  EXPECT_EQ(e.field(), "speed_cm_s");
  EXPECT_NE(std::string(e.what()).find("maximum speed 80 km/h"), std::string::npos) << e.what();
  // ... and so is the whole calibration, before any fit.
  EXPECT_THROW(calibrate({log}, test::reference_train(), {}), data::InputError);
}

TEST(LogPlausibility, ImpossibleDecelerationIsRefusedByRow) {
  const Log log = published_with_speed(40, 159.2);  // 5.7 km/h instead of 57
  const auto e = error_of(log);
  EXPECT_EQ(e.row(), 40);
  EXPECT_EQ(e.field(), "speed_cm_s");
  EXPECT_NE(std::string(e.what()).find("from row 39"), std::string::npos) << e.what();
}

TEST(LogPlausibility, BoundsFollowTheEnvelopesAndTheTrack) {
  const physics::Train t = test::reference_train();
  const AccelBounds level = accel_bounds(t, 10.0, 0.0, 0.0);
  // 203 kN on 194.3 t: 1.045 m/s^2 above the 1 m/s^2 limit.
  EXPECT_NEAR(level.accel_m_s2, 203000.0 / t.effective_mass_kg(), 1e-9);
  EXPECT_GE(level.decel_m_s2, t.max_decel_m_s2);
  const AccelBounds down = accel_bounds(t, 10.0, -30.0, 0.0);
  const AccelBounds up = accel_bounds(t, 10.0, 30.0, 0.0);
  EXPECT_NEAR(down.accel_m_s2 - level.accel_m_s2, 30.0 * t.gravity_m_s2 / 1000.0, 1e-9);
  EXPECT_NEAR(up.decel_m_s2 - level.decel_m_s2, 30.0 * t.gravity_m_s2 / 1000.0, 1e-9);
}

TEST(LogPlausibility, SyntheticLogsWithGrossErrorsPass) {
  // The gross errors the robust loss is there for (up to 8 km/h on a row) are not refused.
  SyntheticLogOptions o;
  o.rows = 3000;
  o.corrupt_fraction = 0.03;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    o.seed = seed;
    const SyntheticLog s = make_synthetic_log(test::truth_train(), o);
    ASSERT_FALSE(s.corrupted_rows.empty());
    EXPECT_NO_THROW(check_log_plausible(s.log, test::reference_train())) << "seed " << seed;
  }
}

TEST(Calibration, NonConvergedFitIsNotTheResult) {
  const Log log = read_log(test::published_table("seed_profile_A6_A7_110s.csv"));
  CalibrationOptions o;
  o.max_iterations = 1;
  const Summary s = calibrate({log}, test::reference_train(), o);
  ASSERT_FALSE(s.primary().fit.converged());
  try {
    s.converged_primary();
    FAIL() << "no error";
  } catch (const NotConvergedError& e) {
    EXPECT_NE(std::string(e.what()).find(dp::termination_name(s.primary().fit.termination)),
              std::string::npos);
  }
  // With the default iteration limit the A6 -> A8 table converges and is the result.
  const Summary ok = calibrate({read_log(test::published_table("seed_profile_A6_A8_220s.csv"))},
                               test::reference_train(), {});
  EXPECT_TRUE(ok.converged_primary().fit.converged());
}

}  // namespace
}  // namespace ecorail::fitting
