// Calibration on synthetic logs made by the engine's integrator from known parameters, with
// 0.2 km/h speed noise and 2 % of rows corrupted: both formulations must recover A, B, C and the
// rotating-mass factor within two standard errors and flag exactly the corrupted rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

struct SyntheticCase {
  SyntheticLog log;
  Summary summary;
};

const SyntheticCase& synthetic_case() {
  static const SyntheticCase c = [] {
    SyntheticLogOptions o;
    o.rows = 2400;
    o.speed_noise_kmh = 0.2;
    o.corrupt_fraction = 0.02;
    o.seed = 7;
    SyntheticCase sc;
    sc.log = make_synthetic_log(test::truth_train(), o);
    CalibrationOptions co;
    co.method = Method::Both;
    sc.summary = calibrate({sc.log.log}, test::reference_train(), co);
    return sc;
  }();
  return c;
}

TEST(CalibrationSynthetic, RecoversParametersWithinTwoStandardErrors) {
  const auto& c = synthetic_case();
  std::cout << c.summary.FullReport();
  const physics::Train truth = test::truth_train();
  const double want[] = {truth.davis.A, truth.davis.B, truth.davis.C, truth.rotating_mass_factor};
  ASSERT_EQ(c.summary.results.size(), 2u);
  for (const auto& r : c.summary.results) {
    for (int p : {kDavisA, kDavisB, kDavisC, kRotatingMassFactor}) {
      const auto& e = r.params[static_cast<std::size_t>(p)];
      SCOPED_TRACE(std::string(method_name(r.method)) + " " + std::string(param_name(p)));
      ASSERT_TRUE(std::isfinite(e.se));
      EXPECT_GT(e.se, 0.0);
      EXPECT_LE(std::abs(e.value - want[p]), 2.0 * e.se)
          << "value " << e.value << " truth " << want[p] << " se " << e.se;
    }
    // The log feels its gradient: the gradient scale is 1 within its errors.
    const auto& gs = r.params[kGradientScale];
    EXPECT_LE(std::abs(gs.value - 1.0), 3.0 * gs.se) << gs.value << " +- " << gs.se;
  }
}

TEST(CalibrationSynthetic, FlagsTheCorruptedRows) {
  const auto& c = synthetic_case();
  const std::set<int> corrupted(c.log.corrupted_rows.begin(), c.log.corrupted_rows.end());
  // Rows the fits can see: those touching a used interval.
  std::set<int> visible;
  const auto& log = c.summary.data.logs.at(0);
  for (std::size_t i = 0; i < log.intervals.size(); ++i) {
    if (log.intervals[i] != IntervalStatus::Used) continue;
    visible.insert(log.rows[i].source_row);
    visible.insert(log.rows[i + 1].source_row);
  }
  for (const auto& r : c.summary.results) {
    SCOPED_TRACE(std::string(method_name(r.method)));
    std::set<int> flagged;
    for (const auto& d : r.fit.discounted) flagged.insert(d.source_row);
    int missed = 0, false_flags = 0, seen = 0;
    for (int row : corrupted) {
      if (!visible.count(row)) continue;
      ++seen;
      if (!flagged.count(row)) {
        ++missed;
        std::cout << "missed row " << row << "\n";
      }
    }
    for (int row : flagged) {
      if (!corrupted.count(row)) {
        ++false_flags;
        std::cout << "false flag row " << row << "\n";
      }
    }
    std::cout << method_name(r.method) << ": " << corrupted.size() << " corrupted, " << seen
              << " visible, " << flagged.size() << " flagged, " << missed << " missed, "
              << false_flags << " false\n";
    EXPECT_GT(seen, 20);
    EXPECT_EQ(missed, 0);
    EXPECT_LE(false_flags, 1);
  }
}

}  // namespace
}  // namespace ecorail::fitting
