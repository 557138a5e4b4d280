#include <gtest/gtest.h>

#include <charconv>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data_test_support.hpp"

namespace ecorail::data {
namespace {

using test::contest_dir;
using test::copy_contest_line;
using test::edit_file;
using test::expect_input_error;
using test::TempDir;
using test::write_file;

std::string num(double v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

// The same content as a line TOML file (numbers written shortest, so mostly TOML integers).
std::string line_to_toml(const Line& line) {
  std::string out = "# test line\n";
  for (const auto& s : line.stations) {
    out += "[[stations]]\nname = \"" + s.name + "\"\nkm_post_m = " + num(s.km_post_m) + "\n";
  }
  auto table = [&](const char* name, const char* key, const std::vector<IntervalRow>& rows) {
    for (const auto& r : rows) {
      out += std::string("\n[[") + name + "]]\nstart_km_post_m = " + num(r.start_km_post_m) +
             "\nend_km_post_m = " + num(r.end_km_post_m) + "\n" + key + " = " + num(r.value) + "\n";
    }
  };
  table("gradients", "gradient_permille", line.gradients);
  table("speed_limits", "limit_kmh", line.limits);
  table("curves", "radius_m", line.curves);
  return out;
}

void expect_same_route(const physics::Route& a, const physics::Route& b) {
  ASSERT_EQ(a.segments().size(), b.segments().size());
  for (std::size_t i = 0; i < a.segments().size(); ++i) {
    const auto& x = a.segments()[i];
    const auto& y = b.segments()[i];
    EXPECT_EQ(x.start_m, y.start_m);
    EXPECT_EQ(x.end_m, y.end_m);
    EXPECT_EQ(x.gradient_permille, y.gradient_permille);
    EXPECT_EQ(x.curve_radius_m, y.curve_radius_m);
    EXPECT_EQ(x.speed_limit_ms, y.speed_limit_ms);
  }
}

TEST(LineLoader, DefaultLineIsTheContestLine) {
  const Line line = default_line();
  EXPECT_EQ(line.name, "contest");
  EXPECT_EQ(line.stations_file, "<embedded>/stations.csv");
  EXPECT_EQ(line.gradients_file, "<embedded>/gradients.csv");
  ASSERT_EQ(line.stations.size(), 14u);
  EXPECT_EQ(line.stations.front().name, "A1");
  EXPECT_EQ(line.stations.front().km_post_m, 22903.0);
  EXPECT_EQ(line.stations.front().source_row, 2);
  EXPECT_EQ(line.stations.back().name, "A14");
  EXPECT_EQ(line.stations.back().km_post_m, 175.0);
  EXPECT_EQ(line.gradients.size(), 63u);
  EXPECT_EQ(line.limits.size(), 40u);
  EXPECT_EQ(line.curves.size(), 76u);
  EXPECT_EQ(line.gradients.back().end_km_post_m, 23803.34);
  ASSERT_NE(line.find_station("A6"), nullptr);
  EXPECT_EQ(line.find_station("A6")->km_post_m, 13594.0);
  EXPECT_EQ(line.find_station("A15"), nullptr);
  for (std::size_t i = 1; i < line.gradients.size(); ++i) {
    EXPECT_EQ(line.gradients[i].start_km_post_m, line.gradients[i - 1].end_km_post_m);
  }
}

TEST(LineLoader, DirectoryLoadMatchesEmbeddedLine) {
  const Line dir = load_line(contest_dir());
  EXPECT_EQ(dir.name, contest_dir().string());
  EXPECT_EQ(dir.curves_file, (contest_dir() / "curves.csv").string());
  EXPECT_EQ(dir.checksum(), default_line().checksum());
  // The row of a table is its line in the file.
  EXPECT_EQ(dir.gradients[33].source_row, 35);
  EXPECT_EQ(dir.gradients[33].value, 3.5);
}

TEST(LineLoader, ChecksumSeesContentChanges) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  const auto before = load_line(tmp.path()).checksum();
  edit_file(tmp / "gradients.csv", "12290,12910,3.5", "12290,12910,3.6");
  const auto after = load_line(tmp.path()).checksum();
  EXPECT_NE(before, after);
  edit_file(tmp / "gradients.csv", "12290,12910,3.6", "12290,12910,3.5");
  edit_file(tmp / "stations.csv", "A7,", "B7,");
  EXPECT_NE(before, load_line(tmp.path()).checksum());
}

TEST(LineLoader, RowsOutOfOrderAreSortedByStart) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  // Move the first data row to the end of the file.
  edit_file(tmp / "gradients.csv", "0,355,-2\r\n", "");
  std::string text = test::read_file(tmp / "gradients.csv") + "0,355,-2\r\n";
  write_file(tmp / "gradients.csv", text);
  const Line line = load_line(tmp.path());
  EXPECT_EQ(line.checksum(), default_line().checksum());
  EXPECT_EQ(line.gradients.front().start_km_post_m, 0.0);
  EXPECT_EQ(line.gradients.front().source_row, 64);
}

TEST(LineLoader, TomlLineEqualsCsvLine) {
  TempDir tmp;
  const Line csv = default_line();
  write_file(tmp / "line.toml", line_to_toml(csv));
  const Line toml = load_line(tmp / "line.toml");
  EXPECT_EQ(toml.name, (tmp / "line.toml").string());
  EXPECT_EQ(toml.stations_file, (tmp / "line.toml").string());
  EXPECT_EQ(toml.limits_file, (tmp / "line.toml").string());
  EXPECT_EQ(toml.checksum(), csv.checksum());
  EXPECT_EQ(toml.stations.size(), 14u);
  EXPECT_EQ(toml.gradients[33].source_row, 34);  // TOML rows are entry indices
  const auto train = default_train();
  for (const auto& [from, to] : {std::pair{"A6", "A7"}, {"A1", "A14"}, {"A14", "A1"}}) {
    SCOPED_TRACE(std::string(from) + "->" + to);
    expect_same_route(build_route(csv, from, to, train), build_route(toml, from, to, train));
  }
}

// ---- errors in CSV directories --------------------------------------------------------------

TEST(LineLoaderErrors, MissingPath) {
  TempDir tmp;
  const auto p = tmp / "no_such_line";
  expect_input_error([&] { load_line(p); }, p.string(), 0, "", {"no such file or directory"});
}

TEST(LineLoaderErrors, MissingFileInDirectory) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  std::filesystem::remove(tmp / "curves.csv");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "curves.csv").string(), 0, "",
                     {"no such file"});
}

TEST(LineLoaderErrors, WrongExtension) {
  TempDir tmp;
  write_file(tmp / "line.txt", "x");
  expect_input_error([&] { load_line(tmp / "line.txt"); }, (tmp / "line.txt").string(), 0, "",
                     {".toml", "line.txt"});
}

TEST(LineLoaderErrors, MissingColumn) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "curves.csv", "radius_m", "radius");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "curves.csv").string(), 1, "radius_m",
                     {"a column named 'radius_m'", "radius"});
}

TEST(LineLoaderErrors, NonNumericField) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "gradients.csv", "12290,12910,3.5", "12290,12910,3.5x");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "gradients.csv").string(), 35,
                     "gradient_permille", {"a number", "'3.5x'"});
}

TEST(LineLoaderErrors, NonNumericStationKmPost) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "stations.csv", "A7,12240", "A7,");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "stations.csv").string(), 8,
                     "km_post_m", {"a number", "empty field"});
}

TEST(LineLoaderErrors, EndNotAfterStart) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "gradients.csv", "12290,12910,3.5", "12290,12290,3.5");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "gradients.csv").string(), 35,
                     "end_km_post_m", {"greater than the start 12290", "got 12290"});
}

TEST(LineLoaderErrors, Gap) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "gradients.csv", "13290,13700,0", "13300,13700,0");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "gradients.csv").string(), 37,
                     "start_km_post_m", {"gap of 10 m", "end 13290", "row 36"});
}

TEST(LineLoaderErrors, Overlap) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "speed_limits.csv", "12240,13474,80", "12230,13474,80");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "speed_limits.csv").string(), 23,
                     "start_km_post_m", {"overlap of 10 m"});
}

TEST(LineLoaderErrors, MismatchWithinToleranceIsContiguous) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "gradients.csv", "13290,13700,0", "13290.0000005,13700,0");
  EXPECT_NO_THROW(load_line(tmp.path()));
  edit_file(tmp / "gradients.csv", "13290.0000005,13700,0", "13290.000002,13700,0");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "gradients.csv").string(), 37,
                     "start_km_post_m", {"gap of"});
}

TEST(LineLoaderErrors, NegativeRadius) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "curves.csv", "22528,22626,3000", "22528,22626,-3000");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "curves.csv").string(), 69, "radius_m",
                     {"at least 0", "got -3000"});
}

TEST(LineLoaderErrors, NonPositiveLimit) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "speed_limits.csv", "12240,13474,80", "12240,13474,0");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "speed_limits.csv").string(), 23,
                     "limit_kmh", {"above 0 km/h", "got 0"});
}

TEST(LineLoaderErrors, DuplicateStation) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "stations.csv", "A7,12240", "A6,12240");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "stations.csv").string(), 8, "station",
                     {"'A6' again", "first at row 7"});
}

TEST(LineLoaderErrors, EmptyTable) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  write_file(tmp / "curves.csv", "start_km_post_m,end_km_post_m,radius_m\r\n");
  expect_input_error([&] { load_line(tmp.path()); }, (tmp / "curves.csv").string(), 0, "",
                     {"at least one row"});
}

// ---- errors in TOML lines -------------------------------------------------------------------

class TomlLineErrors : public ::testing::Test {
 protected:
  void SetUp() override { text_ = line_to_toml(default_line()); }
  // Replaces the n-th (1-based) occurrence of from and writes the file.
  void write(const std::string& from, const std::string& to, int n = 1) {
    std::size_t pos = std::string::npos;
    for (int i = 0; i < n; ++i) pos = text_.find(from, pos == std::string::npos ? 0 : pos + 1);
    ASSERT_NE(pos, std::string::npos) << from;
    text_.replace(pos, from.size(), to);
    write_file(file(), text_);
  }
  std::filesystem::path file() const { return tmp_ / "line.toml"; }

  TempDir tmp_;
  std::string text_;
};

TEST_F(TomlLineErrors, GapNamesTheEntry) {
  // The third [[gradients]] entry starts at 535; move it to 540.
  write("start_km_post_m = 535\n", "start_km_post_m = 540\n");
  expect_input_error([&] { load_line(file()); }, file().string(), 3, "start_km_post_m",
                     {"gap of 5 m", "previous row 2"});
}

TEST_F(TomlLineErrors, MissingKey) {
  write("km_post_m = 21569\n", "");
  expect_input_error([&] { load_line(file()); }, file().string(), 2, "km_post_m",
                     {"a number", "missing"});
}

TEST_F(TomlLineErrors, WrongType) {
  write("radius_m = 1000\n", "radius_m = \"big\"\n");
  expect_input_error([&] { load_line(file()); }, file().string(), 2, "radius_m",
                     {"a number", "the string \"big\""});
}

TEST_F(TomlLineErrors, StationNameMustBeAString) {
  write("name = \"A3\"", "name = 3");
  expect_input_error([&] { load_line(file()); }, file().string(), 3, "name",
                     {"a string", "the integer 3"});
}

TEST_F(TomlLineErrors, DuplicateStation) {
  write("name = \"A3\"", "name = \"A1\"");
  expect_input_error([&] { load_line(file()); }, file().string(), 3, "name",
                     {"'A1' again", "first at row 1"});
}

TEST_F(TomlLineErrors, UnknownKey) {
  write("limit_kmh = 55\n", "limit_kph = 55\n");
  expect_input_error([&] { load_line(file()); }, file().string(), 2, "limit_kph",
                     {"one of the keys", "limit_kmh"});
}

TEST_F(TomlLineErrors, MissingTable) {
  text_ = "[[stations]]\nname = \"A\"\nkm_post_m = 0\n";
  write_file(file(), text_);
  expect_input_error([&] { load_line(file()); }, file().string(), 0, "gradients",
                     {"[[gradients]]", "missing"});
}

TEST_F(TomlLineErrors, SyntaxError) {
  write("[[curves]]", "[[curves]", 5);
  expect_input_error([&] { load_line(file()); }, file().string(), 0, "", {"valid TOML", "line "});
}

}  // namespace
}  // namespace ecorail::data
