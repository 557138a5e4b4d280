// GTFS export: valid HH:MM:SS times (past 24 h too), each trip's stops in time order with
// stop_sequence 1..n, exactly one row per stop and train, the whole feed (agency, calendar,
// feed_info, located stops) or nothing, files all or none.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "output/gtfs_writer.hpp"
#include "physics/motion.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"
#include "temp_dir_test.hpp"

namespace ecorail::output {
namespace {

std::vector<std::vector<std::string>> csv(const std::string& text) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    out.push_back(cells);
  }
  return out;
}

int seconds_of(const std::string& hms) {
  int h = 0, m = 0, s = 0;
  EXPECT_EQ(std::sscanf(hms.c_str(), "%d:%d:%d", &h, &m, &s), 3) << hms;
  EXPECT_LT(m, 60);
  EXPECT_LT(s, 60);
  EXPECT_EQ(hms.size() >= 8, true);
  return 3600 * h + 60 * m + s;
}

// A complete feed's options, every station of the rows below located.
GtfsOptions feed() {
  GtfsOptions o;
  o.agency_name = "Test Metro";
  o.agency_url = "https://metro.example";
  o.agency_timezone = "Europe/Paris";
  o.start_date = "20270104";
  o.end_date = "20270108";
  o.weekdays = {true, true, true, true, true, false, false};
  double lat = 48.85;
  for (const char* s : {"A", "B", "C", "A6", "A7", "A8"}) o.stop_locations[s] = {lat += 0.01, 2.35};
  return o;
}

TEST(GtfsExport, TimesAreHoursMinutesSeconds) {
  EXPECT_EQ(gtfs_time(0.0), "00:00:00");
  EXPECT_EQ(gtfs_time(3661.4), "01:01:01");
  EXPECT_EQ(gtfs_time(59.5), "00:01:00");
  EXPECT_EQ(gtfs_time(25 * 3600.0 + 7), "25:00:07");  // past midnight, as GTFS wants
  EXPECT_THROW(gtfs_time(-1.0), std::invalid_argument);
}

TEST(GtfsExport, OneRowPerStopAndTrainInTimeOrder) {
  // Two trains over three stations, rows given out of order.
  const std::vector<GtfsRow> rows{
      {"T2", "B", 7 * 3600.0 + 400.2, 7 * 3600.0 + 430.2},
      {"T1", "C", 7 * 3600.0 + 250.0, 7 * 3600.0 + 250.0},
      {"T1", "A", 7 * 3600.0, 7 * 3600.0},
      {"T2", "A", 7 * 3600.0 + 300.0, 7 * 3600.0 + 300.0},
      {"T1", "B", 7 * 3600.0 + 100.4, 7 * 3600.0 + 130.4},
      {"T2", "C", 7 * 3600.0 + 550.0, 7 * 3600.0 + 550.0},
  };
  const GtfsTables t = gtfs_tables(rows, feed());
  const auto st = csv(t.stop_times_txt);
  ASSERT_EQ(st.size(), 7u);
  EXPECT_EQ(st[0], (std::vector<std::string>{"trip_id", "arrival_time", "departure_time", "stop_id",
                                             "stop_sequence"}));
  std::map<std::string, std::vector<std::vector<std::string>>> by_trip;
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t i = 1; i < st.size(); ++i) {
    by_trip[st[i][0]].push_back(st[i]);
    EXPECT_TRUE(seen.insert({st[i][0], st[i][3]}).second) << "twice: " << st[i][0] << st[i][3];
  }
  EXPECT_EQ(seen.size(), rows.size());
  for (const auto& [trip, visits] : by_trip) {
    ASSERT_EQ(visits.size(), 3u);
    int last = -1;
    for (std::size_t k = 0; k < visits.size(); ++k) {
      EXPECT_EQ(visits[k][4], std::to_string(k + 1));
      const int arr = seconds_of(visits[k][1]);
      const int dep = seconds_of(visits[k][2]);
      EXPECT_LE(arr, dep);
      EXPECT_LE(last, arr);
      last = dep;
    }
    EXPECT_EQ(visits[0][3], "A");
    EXPECT_EQ(visits[2][3], "C");
  }
  EXPECT_EQ(by_trip["T1"][1][1], "07:01:40");  // 100.4 s rounds to 100 s
  EXPECT_EQ(csv(t.trips_txt).size(), 3u);
  EXPECT_EQ(csv(t.stops_txt).size(), 4u);
}

TEST(GtfsExport, BadRowsAreRefused) {
  EXPECT_THROW(gtfs_tables({{"T", "A", 100.0, 90.0}}, feed()), std::invalid_argument);
  EXPECT_THROW(gtfs_tables({{"T", "A", 0.0, 50.0}, {"T", "B", 40.0, 60.0}}, feed()),
               std::invalid_argument);
  EXPECT_THROW(gtfs_tables({{"", "A", 0.0, 0.0}}, feed()), std::invalid_argument);
}

TEST(GtfsExport, AFeedWithoutAgencyDatesOrCoordinatesIsRefused) {
  const std::vector<GtfsRow> rows{{"T", "A", 0.0, 0.0}, {"T", "B", 60.0, 60.0}};
  EXPECT_NO_THROW(gtfs_tables(rows, feed()));
  const std::vector<std::pair<const char*, void (*)(GtfsOptions&)>> broken{
      {"agency_name", [](GtfsOptions& o) { o.agency_name.clear(); }},
      {"agency_url", [](GtfsOptions& o) { o.agency_url = "metro.example"; }},
      {"agency_timezone", [](GtfsOptions& o) { o.agency_timezone = "Paris time"; }},
      {"start_date", [](GtfsOptions& o) { o.start_date = "20270231"; }},
      {"end_date", [](GtfsOptions& o) { o.end_date = "2027-01-08"; }},
      {"end_date", [](GtfsOptions& o) { o.end_date = "20261231"; }},
      {"monday", [](GtfsOptions& o) { o.weekdays.fill(false); }},
      {"feed_lang", [](GtfsOptions& o) { o.feed_lang = "e n"; }},
  };
  for (const auto& [field, spoil] : broken) {
    GtfsOptions o = feed();
    spoil(o);
    try {
      gtfs_tables(rows, o);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
  GtfsOptions o = feed();
  o.stop_locations.erase("B");
  try {
    gtfs_tables(rows, o);
    ADD_FAILURE() << "a stop without coordinates accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stop_lat"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("none for B"), std::string::npos) << e.what();
  }
}

TEST(GtfsExport, DatesAreCalendarDays) {
  EXPECT_TRUE(is_gtfs_date("20240229"));   // a leap year
  EXPECT_FALSE(is_gtfs_date("20230229"));  // not one
  EXPECT_FALSE(is_gtfs_date("21000229"));  // centuries are not, unless divisible by 400
  EXPECT_TRUE(is_gtfs_date("20000229"));
  EXPECT_FALSE(is_gtfs_date("20271301"));
  EXPECT_FALSE(is_gtfs_date("2027011"));
  EXPECT_FALSE(is_gtfs_date("2027O101"));
}

TEST(GtfsExport, TheFeedsOwnTables) {
  const GtfsTables t = gtfs_tables({{"T", "A", 0.0, 0.0}, {"T", "B", 60.0, 60.0}}, feed());
  const auto agency = csv(t.agency_txt);
  ASSERT_EQ(agency.size(), 2u);
  EXPECT_EQ(agency[1][1], "Test Metro");
  EXPECT_EQ(agency[1][2], "https://metro.example");
  EXPECT_EQ(agency[1][3], "Europe/Paris");
  const auto calendar = csv(t.calendar_txt);
  ASSERT_EQ(calendar.size(), 2u);
  EXPECT_EQ(calendar[1], (std::vector<std::string>{"service", "1", "1", "1", "1", "1", "0", "0",
                                                   "20270104", "20270108"}));
  const auto trips = csv(t.trips_txt);
  EXPECT_EQ(trips[1][1], calendar[1][0]);  // every trip runs on the calendar's service
  const auto stops = csv(t.stops_txt);
  ASSERT_EQ(stops.size(), 3u);
  EXPECT_EQ(stops[0][2], "stop_lat");
  EXPECT_EQ(stops[1][2], "48.860000");
  EXPECT_EQ(stops[2][3], "2.350000");
  const auto info = csv(t.feed_info_txt);
  ASSERT_EQ(info.size(), 2u);
  EXPECT_EQ(info[1][0], "Test Metro");
  EXPECT_EQ(info[1][2], "en");
}

TEST(GtfsExport, RowsOfAJourneyTrip) {
  // A6 -> A7 -> A8 on the reference line, each section run flat out for 600 m then coasting
  // into the braking curve, 45 s at A7, departing 07:00:00.
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const auto routes = data::build_routes(line, {"A6", "A7", "A8"}, train);
  std::vector<physics::SpeedEnvelope> envelopes;
  std::vector<physics::SimulationResult> sims;
  for (const auto& r : routes) envelopes.emplace_back(train, r, 1.0);
  for (std::size_t i = 0; i < routes.size(); ++i) {
    const physics::Motion m(train, routes[i], envelopes[i]);
    const physics::ControlProgram program{{0.0, physics::Control::MaxTraction},
                                          {600.0, physics::Control::Coast}};
    sims.push_back(physics::simulate(m, program, physics::SimulationOptions{}));
  }
  const physics::Trip trip({{&routes[0], &sims[0], 45.0}, {&routes[1], &sims[1], 0.0}}, 7 * 3600.0,
                           train.regen_efficiency);
  const auto rows = gtfs_rows_of_trip(trip, "T1");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].station, "A6");
  EXPECT_EQ(rows[2].station, "A8");
  EXPECT_DOUBLE_EQ(rows[0].departure_s, 7 * 3600.0);
  EXPECT_NEAR(rows[1].arrival_s, 7 * 3600.0 + sims[0].running_time_s, 1e-6);
  EXPECT_NEAR(rows[1].departure_s - rows[1].arrival_s, 45.0, 1e-6);
  EXPECT_NEAR(rows[2].arrival_s, rows[1].departure_s + sims[1].running_time_s, 1e-6);
  const auto st = csv(gtfs_tables(rows, feed()).stop_times_txt);
  ASSERT_EQ(st.size(), 4u);
  EXPECT_EQ(st[1][2], "07:00:00");
}

class GtfsFiles : public ecorail::testing::TempDirTest {};

TEST_F(GtfsFiles, AreWrittenTogether) {
  {
    data::OutputBatch batch;
    add_gtfs_files(batch, dir_, {{"T1", "A", 0.0, 0.0}, {"T1", "B", 60.0, 60.0}}, feed());
    // Not committed: nothing is written.
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "stop_times.txt"));
  data::OutputBatch batch;
  add_gtfs_files(batch, dir_, {{"T1", "A", 0.0, 0.0}, {"T1", "B", 60.0, 60.0}}, feed());
  batch.commit();
  for (const char* f : {"agency.txt", "stops.txt", "routes.txt", "trips.txt", "stop_times.txt",
                        "calendar.txt", "feed_info.txt"}) {
    EXPECT_TRUE(std::filesystem::exists(dir_ / f)) << f;
  }
}

}  // namespace
}  // namespace ecorail::output
