#include <gtest/gtest.h>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data_test_support.hpp"

namespace ecorail::data {
namespace {

using test::expect_input_error;

TEST(InputError, MessageNamesFileRowFieldAndExpectation) {
  const InputError e("a.csv", 7, "limit_kmh", "a number; got 'x'");
  EXPECT_STREQ(e.what(), "a.csv: row 7, field 'limit_kmh': expected a number; got 'x'");
  EXPECT_EQ(e.file(), "a.csv");
  EXPECT_EQ(e.row(), 7);
  EXPECT_EQ(e.field(), "limit_kmh");
}

TEST(InputError, OmitsRowZeroAndEmptyField) {
  EXPECT_STREQ(InputError("t.toml", 0, "mass_t", "a mass").what(),
               "t.toml: field 'mass_t': expected a mass");
  EXPECT_STREQ(InputError("a.csv", 3, "", "3 fields").what(), "a.csv: row 3: expected 3 fields");
  EXPECT_STREQ(InputError("dir", 0, "", "a directory").what(), "dir: expected a directory");
}

TEST(CsvTable, TrimsSkipsBlankLinesAndCountsFileLines) {
  const auto t = CsvTable::parse("\xEF\xBB\xBF a , b \r\n\r\n 1 ,  x y\r\n   \n2,3", "f.csv");
  ASSERT_EQ(t.header().size(), 2u);
  EXPECT_EQ(t.header()[0], "a");
  EXPECT_EQ(t.header()[1], "b");
  ASSERT_EQ(t.rows().size(), 2u);
  EXPECT_EQ(t.rows()[0].row, 3);
  EXPECT_EQ(t.rows()[0].fields[1], "x y");
  EXPECT_EQ(t.rows()[1].row, 5);
  EXPECT_EQ(t.column("b"), 1u);
  EXPECT_DOUBLE_EQ(t.number(t.rows()[1], t.column("b")), 3.0);
}

TEST(CsvTable, MissingColumnNamesFileAndColumn) {
  const auto t = CsvTable::parse("start_km_post_m,end_km_post_m,radius\n0,1,0\n", "curves.csv");
  expect_input_error([&] { t.column("radius_m"); }, "curves.csv", 1, "radius_m",
                     {"radius_m", "got columns start_km_post_m, end_km_post_m, radius"});
}

TEST(CsvTable, WrongFieldCountNamesRow) {
  expect_input_error([] { CsvTable::parse("a,b\n1,2\n\n3\n", "x.csv"); }, "x.csv", 4, "",
                     {"2 comma-separated fields", "got 1"});
}

TEST(CsvTable, EmptyFileIsAnError) {
  expect_input_error([] { CsvTable::parse(" \n\r\n", "e.csv"); }, "e.csv", 0, "", {"header"});
}

TEST(CsvTable, NonNumericFieldNamesRowAndColumn) {
  const auto t = CsvTable::parse("a,b\n1,2\n1,2.5x\n", "n.csv");
  EXPECT_DOUBLE_EQ(t.number(t.rows()[0], 1), 2.0);
  expect_input_error([&] { t.number(t.rows()[1], 1); }, "n.csv", 3, "b",
                     {"a number", "got '2.5x'"});
}

TEST(ParseNumber, AcceptsDecimalNotation) {
  EXPECT_DOUBLE_EQ(parse_number("12.078", "f", 1, "x"), 12.078);
  EXPECT_DOUBLE_EQ(parse_number("-34.47", "f", 1, "x"), -34.47);
  EXPECT_DOUBLE_EQ(parse_number("+1.5", "f", 1, "x"), 1.5);
  EXPECT_DOUBLE_EQ(parse_number("1e3", "f", 1, "x"), 1000.0);
  EXPECT_DOUBLE_EQ(parse_number(" 7 ", "f", 1, "x"), 7.0);
  EXPECT_DOUBLE_EQ(parse_number(".5", "f", 1, "x"), 0.5);
}

TEST(ParseNumber, RejectsEverythingElse) {
  for (const char* bad : {"", "abc", "1.2x", "nan", "NaN", "inf", "-inf", "infinity", "1e400",
                          "--1", "+", "+-1", "1,5", "0x10", "1 2", "."}) {
    SCOPED_TRACE(bad);
    expect_input_error([&] { parse_number(bad, "f.csv", 9, "km_post_m"); }, "f.csv", 9, "km_post_m",
                       {"a number"});
  }
}

// Clock times of logs (MM:SS for two fields) and of --gtfs-start (HH:MM): one parser.
TEST(ClockTime, ReadsFieldsAndRefusesWhatIsNoClock) {
  const auto ms = TwoFieldClock::MinutesSeconds, hm = TwoFieldClock::HoursMinutes;
  auto clock = [](const std::string& t, TwoFieldClock two) {
    return parse_clock_s(t, two, "f", 3, "time", "a time");
  };
  EXPECT_EQ(clock("01:02:03", ms), 3723.0);
  EXPECT_EQ(clock("01:02:03", hm), 3723.0);
  EXPECT_EQ(clock("02:03", ms), 123.0);
  EXPECT_EQ(clock("02:03", hm), 7380.0);
  EXPECT_EQ(clock("25:00:01.5", hm), 90001.5);  // past midnight, a fraction of the last field
  for (const std::string bad :
       {".", "1", "1:60", "1:2:60", "1.5:00", "-1:00", "1:2:3:4", ":", "a:b", "1::2"}) {
    try {
      clock(bad, hm);
      ADD_FAILURE() << "read: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("a time; got '" + bad + "'"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace ecorail::data
