// Calibration of one long log (10 000 rows, 2 % corrupted): the fit is still right at this
// length. The log is also written to the build tree (fitting_synthetic_10000.csv) so the
// end-to-end time of `ecorail calibrate` can be measured on it; the speed itself is measured by
// bench/bench_calibration.cpp (docs/calibration.md), not asserted here.
#include <gtest/gtest.h>

#include <fstream>

#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

TEST(CalibrationLongLog, TenThousandRowsRecoverTheParameters) {
  SyntheticLogOptions o;
  o.rows = 10000;
  o.corrupt_fraction = 0.02;
  o.seed = 42;
  const SyntheticLog log = make_synthetic_log(test::truth_train(), o);
  {
    std::ofstream out(std::string(ECORAIL_BINARY_DIR) + "/fitting_synthetic_10000.csv");
    write_log_csv(log.log, out);
  }
  const Summary s = calibrate({log.log}, test::reference_train(), CalibrationOptions{});
  const auto& oe = s.primary();
  EXPECT_NEAR(oe.params[kDavisC].value, test::truth_train().davis.C, 3.0 * oe.params[kDavisC].se);
  EXPECT_NEAR(oe.params[kRotatingMassFactor].value, 0.08, 3.0 * oe.params[kRotatingMassFactor].se);
}

}  // namespace
}  // namespace ecorail::fitting
