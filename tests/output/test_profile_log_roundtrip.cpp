// ecorail's own per-second table (output/profile_writers) read back as a calibration log
// (fitting/log_reader): what one room writes, the other reads, curve radius and braking force
// included.
#include <gtest/gtest.h>

#include <sstream>

#include "fitting/log_reader.hpp"
#include "output/profile_writers.hpp"

namespace ecorail::fitting {
namespace {

TEST(OwnTable, CurveRadiusReachesTheCalibration) {
  // ecorail's per-second table carries the curve radius, and calibrate reads it from there.
  output::Timeline rows;
  for (int k = 0; k < 4; ++k) {
    output::TimelinePoint p;
    p.t_s = k + 1.0;
    p.s_m = 10.0 * (k + 1);
    p.v_ms = 10.0;
    p.force_N = 20000.0;
    p.speed_limit_ms = 20.0;
    p.curve_radius_m = k < 2 ? 0.0 : 350.0;
    rows.push_back(p);
  }
  std::ostringstream csv;
  output::write_profile_csv(csv, rows);
  const Log log = parse_log(csv.str(), "own.csv");
  EXPECT_EQ(log.format, LogFormat::Published);
  EXPECT_TRUE(log.has_curve);
  EXPECT_DOUBLE_EQ(log.rows[1].curve_radius_m, 0.0);
  EXPECT_DOUBLE_EQ(log.rows[2].curve_radius_m, 350.0);
  EXPECT_TRUE(log.has_braking);  // and the braking force, so no braking is guessed
}

}  // namespace
}  // namespace ecorail::fitting
