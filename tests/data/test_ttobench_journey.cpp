// TTOBench journeys: timing points with open and closed time and speed windows, mapped to SI,
// and malformed journeys refused with their JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "data/input_error.hpp"
#include "data/ttobench_io.hpp"
#include "data/ttobench_journey.hpp"

namespace ecorail::data {
namespace {

std::string journey(const std::string& values) {
  return R"J({"metadata": {"id": "T_Journey_01", "library version": "TTOBench v1.5",
  "associated track": "T"},
  "timing points": {"units": {"position": "m", "lower time constraint": "s",
    "upper time constraint": "s", "lower speed constraint": "km/h",
    "upper speed constraint": "km/h"}, "values": )J" +
         values + "}}";
}

std::string field_of(const std::string& text) {
  try {
    journey_from_ttobench(text, "j.json");
  } catch (const InputError& e) {
    return e.field();
  }
  return "(no error)";
}

TEST(TtobenchJourney, WindowsMapToSiWithOpenBounds) {
  const TtobenchJourney j = journey_from_ttobench(
      journey("[[0, 0, 0, 0, 0], [500, 30, 40, 36, null], [1000, null, 90, 0, 0]]"), "j.json");
  EXPECT_EQ(j.id, "T_Journey_01");
  EXPECT_EQ(j.track_id, "T");
  ASSERT_EQ(j.points.size(), 3u);
  EXPECT_TRUE(j.points[0].is_stop());
  EXPECT_DOUBLE_EQ(j.points[1].min_speed_ms, 10.0);
  EXPECT_TRUE(std::isinf(j.points[1].max_speed_ms));
  EXPECT_FALSE(j.points[1].is_stop());
  EXPECT_DOUBLE_EQ(j.points[1].earliest_s, 30.0);
  EXPECT_TRUE(std::isinf(j.points[2].earliest_s) && j.points[2].earliest_s < 0.0);
  EXPECT_DOUBLE_EQ(j.points[2].latest_s, 90.0);
}

TEST(TtobenchJourney, MalformedJourneysNameTheirPath) {
  EXPECT_EQ(field_of(journey("[[0, 0, 0, 0, 0]]")), "timing points.values");
  EXPECT_EQ(field_of(journey("[[0, 0, 0, 0, 0], [100, 50, 40, 0, 0]]")),
            "timing points.values[1][2]");
  EXPECT_EQ(field_of(journey("[[0, 0, 0, 0, 0], [100, 50, 60, 0]]")), "timing points.values[1]");
  EXPECT_EQ(field_of(journey("[[0, 0, 0, 0, 0], [100, 50, 60, \"fast\", 0]]")),
            "timing points.values[1][3]");
  EXPECT_EQ(field_of(journey("[[100, 0, 0, 0, 0], [50, 50, 60, 0, 0]]")),
            "timing points.values[1][0]");
  EXPECT_EQ(field_of(journey("[[0, 0, 0, 0, 0], [100, 50, 60, 30, 20]]")),
            "timing points.values[1][4]");
}

// Metadata is free text: a key TTOBench does not define there (a file from another tool) is
// kept and reported, never refused; the same key where a solve reads (the timing points) is.
TEST(TtobenchJourney, UnknownMetadataIsKeptAndReportedButUnknownDataRefused) {
  std::string text = journey("[[0, 0, 0, 0, 0], [1000, null, 90, 0, 0]]");
  text.replace(text.find("\"associated track\""), 0, "\"note\": \"from tool X\", \"rev\": 3, ");
  const TtobenchJourney j = journey_from_ttobench(text, "j.json");
  EXPECT_EQ(j.id, "T_Journey_01");
  ASSERT_EQ(j.other_metadata.size(), 2u);
  EXPECT_EQ(j.other_metadata[0].first, "note");
  EXPECT_EQ(j.other_metadata[0].second, "\"from tool X\"");
  EXPECT_EQ(j.other_metadata[1].first, "rev");
  EXPECT_EQ(j.other_metadata[1].second, "3");
  const std::vector<std::string> warnings = ttobench_metadata_warnings(text);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("'metadata.note'"), std::string::npos) << warnings[0];
  EXPECT_TRUE(
      ttobench_metadata_warnings(journey("[[0, 0, 0, 0, 0], [1000, null, 90, 0, 0]]")).empty());
  // Where a solve reads, an unknown key is still refused with its path.
  std::string data = journey("[[0, 0, 0, 0, 0], [1000, null, 90, 0, 0]]");
  data.replace(data.find("\"values\""), 0, "\"note\": 1, ");
  EXPECT_EQ(field_of(data), "timing points.note");
  // metadata.id must still be a string.
  std::string bad_id = journey("[[0, 0, 0, 0, 0], [1000, null, 90, 0, 0]]");
  bad_id.replace(bad_id.find("\"T_Journey_01\""), 14, "7");
  EXPECT_EQ(field_of(bad_id), "metadata.id");
}

TEST(TtobenchJourney, TheStGallenWilJourney) {
  const auto path = std::filesystem::path(ECORAIL_SHARED_DIR) / "data" / "ttobench" / "journeys" /
                    "CH_StGallen_Wil_Journey_01.json";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no TTOBench copy";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const TtobenchJourney j = journey_from_ttobench(text.str(), path.string());
  EXPECT_EQ(j.track_id, "CH_StGallen_Wil");
  ASSERT_EQ(j.points.size(), 6u);
  // The stop at 15 000 m: arrival window then departure window at the same position.
  EXPECT_EQ(j.points[2].position_m, j.points[3].position_m);
  EXPECT_TRUE(j.points[2].is_stop() && j.points[3].is_stop());
  EXPECT_DOUBLE_EQ(j.points[3].earliest_s, 800.0);
  EXPECT_DOUBLE_EQ(j.points[5].position_m, 29556.1);
}

}  // namespace
}  // namespace ecorail::data
