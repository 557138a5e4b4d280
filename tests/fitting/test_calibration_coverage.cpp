// A study rather than a check (disabled by default; run with --gtest_also_run_disabled_tests
// --gtest_filter='*Coverage*'): over many seeds of the synthetic log, how often each
// formulation's estimate of A, B, C and the mass factor lies within two standard errors of the
// truth, and how many corrupted rows are missed or clean rows flagged. Figures in
// docs/calibration.md come from here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "fitting/calibration.hpp"
#include "fitting/synthetic_log.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

TEST(CalibrationCoverage, DISABLED_TwoStandardErrorCoverageOverSeeds) {
  const physics::Train truth = test::truth_train();
  const double want[] = {truth.davis.A, truth.davis.B, truth.davis.C, truth.rotating_mass_factor};
  const int seeds = 40;
  int within[2][4] = {}, missed[2] = {}, false_flags[2] = {}, corrupted_total = 0;
  double z2[2][4] = {};
  for (int seed = 1; seed <= seeds; ++seed) {
    SyntheticLogOptions o;
    o.rows = 2400;
    o.corrupt_fraction = 0.02;
    o.seed = static_cast<std::uint64_t>(seed);
    const SyntheticLog log = make_synthetic_log(truth, o);
    const Summary s = calibrate({log.log}, test::reference_train(), CalibrationOptions{});
    const std::set<int> corrupted(log.corrupted_rows.begin(), log.corrupted_rows.end());
    corrupted_total += static_cast<int>(corrupted.size());
    for (std::size_t f = 0; f < s.results.size(); ++f) {
      const auto& r = s.results[f];
      for (int p = 0; p < 4; ++p) {
        const auto& e = r.params[static_cast<std::size_t>(p)];
        const double z = (e.value - want[p]) / e.se;
        z2[f][p] += z * z;
        if (std::abs(z) <= 2.0) ++within[f][p];
      }
      std::set<int> flagged;
      for (const auto& d : r.fit.discounted) flagged.insert(d.source_row);
      for (int row : corrupted) missed[f] += flagged.count(row) ? 0 : 1;
      for (int row : flagged) false_flags[f] += corrupted.count(row) ? 0 : 1;
    }
  }
  const char* names[] = {"equation error", "output error"};
  for (int f = 0; f < 2; ++f) {
    std::printf(
        "%s over %d seeds: within 2 SE: A %d, B %d, C %d, rho %d; rms z: A %.2f, B %.2f, "
        "C %.2f, rho %.2f; corrupted rows %d, missed %d, false flags %d\n",
        names[f], seeds, within[f][0], within[f][1], within[f][2], within[f][3],
        std::sqrt(z2[f][0] / seeds), std::sqrt(z2[f][1] / seeds), std::sqrt(z2[f][2] / seeds),
        std::sqrt(z2[f][3] / seeds), corrupted_total, missed[f], false_flags[f]);
  }
}

}  // namespace
}  // namespace ecorail::fitting
