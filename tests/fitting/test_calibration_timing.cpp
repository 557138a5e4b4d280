// The acceptance figure: calibration (both formulations) of one log of 10 000 rows finishes in
// under 5 s. The log is also written to the build tree (fitting_synthetic_10000.csv) so the
// end-to-end time of `ecorail calibrate` can be measured on it (docs/calibration.md).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>

#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

TEST(CalibrationTiming, TenThousandRowsUnderFiveSeconds) {
  SyntheticLogOptions o;
  o.rows = 10000;
  o.corrupt_fraction = 0.02;
  o.seed = 42;
  const SyntheticLog log = make_synthetic_log(test::truth_train(), o);
  {
    std::ofstream out(std::string(ECORAIL_BINARY_DIR) + "/fitting_synthetic_10000.csv");
    write_log_csv(log.log, out);
  }
  const auto start = std::chrono::steady_clock::now();
  const Summary s = calibrate({log.log}, test::reference_train(), CalibrationOptions{});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("10 000 rows: %.3f s (equation error %.3f s, output error %.3f s)\n", seconds,
              s.results.at(0).fit.solve_time_s, s.results.at(1).fit.solve_time_s);
  EXPECT_LT(seconds, 5.0);
  // And the fit is still right at this length.
  const auto& oe = s.primary();
  EXPECT_NEAR(oe.params[kDavisC].value, test::truth_train().davis.C, 3.0 * oe.params[kDavisC].se);
  EXPECT_NEAR(oe.params[kRotatingMassFactor].value, 0.08, 3.0 * oe.params[kRotatingMassFactor].se);
}

}  // namespace
}  // namespace ecorail::fitting
