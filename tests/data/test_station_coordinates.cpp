// Optional station coordinates (lat, lon) of the stations table: read from CSV columns and TOML
// keys, both or neither, within range; they change no checksum (no run depends on them).
#include <gtest/gtest.h>

#include "data/csv_reader.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data_test_support.hpp"

namespace ecorail::data {
namespace {

using test::expect_input_error;

Line with_stations(const std::string& stations_csv) {
  const CsvTable gradients =
      CsvTable::parse("start_km_post_m,end_km_post_m,gradient_permille\n0,2000,0\n", "g.csv");
  const CsvTable limits =
      CsvTable::parse("start_km_post_m,end_km_post_m,limit_kmh\n0,2000,80\n", "l.csv");
  const CsvTable curves =
      CsvTable::parse("start_km_post_m,end_km_post_m,radius_m\n0,2000,0\n", "c.csv");
  return line_from_csv_tables(CsvTable::parse(stations_csv, "stations.csv"), gradients, limits,
                              curves);
}

TEST(StationCoordinates, ReadFromTheStationsTable) {
  const Line line = with_stations("station,km_post_m,lat,lon\nA,0,48.8,2.3\nB,1500,48.81,2.31\n");
  ASSERT_EQ(line.stations.size(), 2u);
  EXPECT_TRUE(line.stations[0].has_coordinates());
  EXPECT_DOUBLE_EQ(line.stations[1].lat_deg, 48.81);
  EXPECT_DOUBLE_EQ(line.stations[1].lon_deg, 2.31);
  // No coordinate columns, or a row with both fields empty: no coordinates, no error.
  const Line bare = with_stations("station,km_post_m\nA,0\nB,1500\n");
  EXPECT_FALSE(bare.stations[0].has_coordinates());
  const Line partly = with_stations("station,km_post_m,lat,lon\nA,0,,\nB,1500,48.81,2.31\n");
  EXPECT_FALSE(partly.stations[0].has_coordinates());
  EXPECT_TRUE(partly.stations[1].has_coordinates());
  // They change no run: the checksum is the one without them.
  EXPECT_EQ(line.checksum(), bare.checksum());
}

TEST(StationCoordinates, BothOrNeitherWithinRange) {
  expect_input_error([] { with_stations("station,km_post_m,lat\nA,0,48.8\nB,1500,48.8\n"); },
                     "stations.csv", 1, "lon");
  expect_input_error([] { with_stations("station,km_post_m,lat,lon\nA,0,48.8,\nB,1500,1,1\n"); },
                     "stations.csv", 2, "lon");
  expect_input_error([] { with_stations("station,km_post_m,lat,lon\nA,0,91,2\nB,1500,1,1\n"); },
                     "stations.csv", 2, "lat");
  expect_input_error([] { with_stations("station,km_post_m,lat,lon\nA,0,45,181\nB,1500,1,1\n"); },
                     "stations.csv", 2, "lon");
  expect_input_error([] { with_stations("station,km_post_m,lat,lon\nA,0,x,2\nB,1500,1,1\n"); },
                     "stations.csv", 2, "lat");
}

TEST(StationCoordinates, TomlKeys) {
  const std::string tables =
      "[[gradients]]\nstart_km_post_m = 0\nend_km_post_m = 2000\ngradient_permille = 0\n"
      "[[speed_limits]]\nstart_km_post_m = 0\nend_km_post_m = 2000\nlimit_kmh = 80\n"
      "[[curves]]\nstart_km_post_m = 0\nend_km_post_m = 2000\nradius_m = 0\n";
  const Line line = line_from_toml_text(
      "[[stations]]\nname = \"A\"\nkm_post_m = 0\nlat = -33.9\nlon = 151.2\n"
      "[[stations]]\nname = \"B\"\nkm_post_m = 1500\n" +
          tables,
      "line.toml");
  EXPECT_DOUBLE_EQ(line.stations[0].lat_deg, -33.9);
  EXPECT_DOUBLE_EQ(line.stations[0].lon_deg, 151.2);
  EXPECT_FALSE(line.stations[1].has_coordinates());
  expect_input_error(
      [&] {
        line_from_toml_text(
            "[[stations]]\nname = \"A\"\nkm_post_m = 0\nlat = 1.0\n"
            "[[stations]]\nname = \"B\"\nkm_post_m = 1500\n" +
                tables,
            "line.toml");
      },
      "line.toml", 1, "lon");
}

}  // namespace
}  // namespace ecorail::data
