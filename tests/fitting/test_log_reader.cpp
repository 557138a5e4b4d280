// Reading logs: the published per-second tables and plain CSVs with named columns, converted to
// SI; bad logs (missing columns, non-numbers, time that does not increase, negative speeds or
// forces) are InputErrors naming file, row and field.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "data/input_error.hpp"
#include "fitting/log_reader.hpp"
#include "fitting_test_support.hpp"

namespace ecorail::fitting {
namespace {

data::InputError error_of(const std::string& text) {
  try {
    parse_log(text, "log.csv");
  } catch (const data::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return data::InputError("", 0, "", "");
}

TEST(LogReader, ReadsThePublishedTable) {
  const Log log = read_log(test::published_table("seed_profile_A6_A7_110s.csv"));
  EXPECT_EQ(log.format, LogFormat::Published);
  ASSERT_EQ(log.rows.size(), 110u);
  EXPECT_DOUBLE_EQ(log.rows[0].time_s, 1.0);
  EXPECT_EQ(log.rows[0].source_row, 2);
  EXPECT_DOUBLE_EQ(log.rows[7].speed_ms, 7.996);  // speed_cm_s 799.6, the finer column
  EXPECT_DOUBLE_EQ(log.rows[14].traction_force_N, 190600.0);
  EXPECT_TRUE(std::isnan(log.rows[14].braking_force_N));  // the table has no braking column
  EXPECT_DOUBLE_EQ(log.rows[60].gradient_permille, -3.5);
  EXPECT_DOUBLE_EQ(log.rows[109].position_m, 1354.0);
  EXPECT_TRUE(log.has_traction);
  EXPECT_FALSE(log.has_braking);
}

TEST(LogReader, ReadsPlainCsvWithKilometrePosts) {
  const Log log = parse_log(
      "time_hms,speed_kmh,km_post_m,gradient_permille,force_kN,curve_radius_m\n"
      "1:00:00,36,1000,2,50,0\n"
      "1:00:01,36.5,990,2,-20,400\n",
      "log.csv");
  EXPECT_EQ(log.format, LogFormat::Plain);
  EXPECT_DOUBLE_EQ(log.rows[0].time_s, 3600.0);
  EXPECT_DOUBLE_EQ(log.rows[0].speed_ms, 10.0);
  EXPECT_DOUBLE_EQ(log.rows[1].position_m, 10.0);  // posts fall along the run
  EXPECT_DOUBLE_EQ(log.rows[0].traction_force_N, 50000.0);
  EXPECT_DOUBLE_EQ(log.rows[0].braking_force_N, 0.0);
  EXPECT_DOUBLE_EQ(log.rows[1].braking_force_N, 20000.0);
  EXPECT_DOUBLE_EQ(log.rows[1].curve_radius_m, 400.0);
}

TEST(LogReader, RoundTripsThePlainFormat) {
  const Log a = parse_log(
      "time_s,speed_kmh,position_m,gradient_permille,traction_force_kN,braking_force_kN\n"
      "0,0,0,1.5,203,0\n1,3.6,0.5,1.5,203,0\n2,7.2,2,1.5,0,10\n",
      "a.csv");
  std::ostringstream out;
  write_log_csv(a, out);
  const Log b = parse_log(out.str(), "b.csv");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_NEAR(a.rows[i].speed_ms, b.rows[i].speed_ms, 1e-9);
    EXPECT_NEAR(a.rows[i].position_m, b.rows[i].position_m, 1e-9);
    EXPECT_NEAR(a.rows[i].braking_force_N, b.rows[i].braking_force_N, 1e-6);
  }
}

TEST(LogReader, MissingColumnsAreNamed) {
  auto e = error_of("t,speed_kmh,traction_force_kN\n0,1,2\n1,2,3\n");
  EXPECT_EQ(e.field(), "time_s");
  EXPECT_EQ(e.row(), 1);
  e = error_of("time_s,v,traction_force_kN\n0,1,2\n1,2,3\n");
  EXPECT_EQ(e.field(), "speed_kmh");
  e = error_of("time_s,speed_kmh\n0,1\n1,2\n");
  EXPECT_EQ(e.field(), "traction_force_kN");
  EXPECT_NE(std::string(e.what()).find("braking_force_kN"), std::string::npos);
}

TEST(LogReader, NonMonotoneTimeIsAnError) {
  const auto e = error_of("time_s,speed_kmh,traction_force_kN\n0,1,2\n1,2,3\n1,2,3\n");
  EXPECT_EQ(e.row(), 4);
  EXPECT_EQ(e.field(), "time_s");
  EXPECT_NE(std::string(e.what()).find("increasing"), std::string::npos);
  EXPECT_EQ(error_of("time_hms,speed_kmh,traction_force_kN\n00:00:02,1,2\n00:00:01,2,3\n").row(),
            3);
}

TEST(LogReader, BadValuesAreErrors) {
  EXPECT_EQ(error_of("time_s,speed_kmh,traction_force_kN\n0,1,2\n1,x,3\n").row(), 3);
  EXPECT_EQ(error_of("time_s,speed_kmh,traction_force_kN\n0,-1,2\n1,2,3\n").field(), "speed_kmh");
  EXPECT_EQ(error_of("time_s,speed_kmh,traction_force_kN\n0,1,-2\n1,2,3\n").field(),
            "traction_force_kN");
  EXPECT_EQ(error_of("time_hms,speed_kmh,traction_force_kN\n0:61:00,1,2\n0:62:00,2,3\n").field(),
            "time_hms");
  EXPECT_EQ(error_of("time_s,speed_kmh,notch\n0,1,2\n1,2,0\n").field(), "notch");
  EXPECT_EQ(error_of("time_s,speed_kmh,traction_force_kN\n0,1,2\n").row(), 0);  // one row
}

}  // namespace
}  // namespace ecorail::fitting
