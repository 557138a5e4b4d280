#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data_test_support.hpp"
#include "physics/units.hpp"

namespace ecorail::data {
namespace {

using test::copy_contest_line;
using test::edit_file;
using test::expect_input_error;
using test::TempDir;

struct Run {
  double length_m;
  double value;
};

// The route compressed to runs of constant value of one quantity.
template <class Get>
std::vector<Run> runs(const physics::Route& route, Get get) {
  std::vector<Run> out;
  for (const auto& seg : route.segments()) {
    const double v = get(seg);
    if (!out.empty() && out.back().value == v) {
      out.back().length_m += seg.end_m - seg.start_m;
    } else {
      out.push_back({seg.end_m - seg.start_m, v});
    }
  }
  return out;
}

void expect_runs(const std::vector<Run>& got, const std::vector<Run>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].length_m, want[i].length_m, 1e-9) << "run " << i;
    EXPECT_EQ(got[i].value, want[i].value) << "run " << i;
  }
}

double gradient(const physics::RouteSegment& s) {
  return s.gradient_permille;
}
double limit_kmh(const physics::RouteSegment& s) {
  return units::ms_to_kmh(s.speed_limit_ms);
}
double radius(const physics::RouteSegment& s) {
  return s.curve_radius_m;
}

class RouteBuilder : public ::testing::Test {
 protected:
  Line line_ = default_line();
  physics::Train train_ = default_train();
};

TEST_F(RouteBuilder, A6ToA7MatchesTheModelDescription) {
  const auto route = build_route(line_, "A6", "A7", train_);
  EXPECT_EQ(route.length_m(), 1354.0);
  EXPECT_EQ(route.from_name(), "A6");
  EXPECT_EQ(route.to_name(), "A7");
  // Towards decreasing km post: +1.8 is the -1.8 row, -3.5 the +3.5 row.
  expect_runs(runs(route, gradient), {{304, 0.0}, {380, 1.8}, {620, -3.5}, {50, 0.0}});
  expect_runs(runs(route, limit_kmh), {{120, 55.0}, {1234, 80.0}});
  expect_runs(runs(route, radius), {{1354, 0.0}});
  EXPECT_EQ(route.km_post_m(0.0), 13594.0);
  EXPECT_EQ(route.km_post_m(1354.0), 12240.0);
  EXPECT_DOUBLE_EQ(route.speed_limit_ms(60.0), 55.0 / 3.6);
  EXPECT_DOUBLE_EQ(route.speed_limit_ms(121.0), 80.0 / 3.6);
  EXPECT_EQ(route.at(500.0).gradient_permille, 1.8);
  EXPECT_EQ(route.at(684.0).gradient_permille, -3.5);  // a boundary belongs to the next row
}

TEST_F(RouteBuilder, ReverseDirectionFlipsGradients) {
  const auto route = build_route(line_, "A7", "A6", train_);
  EXPECT_EQ(route.length_m(), 1354.0);
  expect_runs(runs(route, gradient), {{50, 0.0}, {620, 3.5}, {380, -1.8}, {304, 0.0}});
  expect_runs(runs(route, limit_kmh), {{1234, 80.0}, {120, 55.0}});
  EXPECT_EQ(route.km_post_m(0.0), 12240.0);
  EXPECT_EQ(route.km_post_m(1354.0), 13594.0);
}

TEST_F(RouteBuilder, SegmentsAreContiguousAndMerged) {
  const auto route = build_route(line_, "A1", "A14", train_);
  const auto& segs = route.segments();
  ASSERT_FALSE(segs.empty());
  EXPECT_EQ(segs.front().start_m, 0.0);
  for (std::size_t i = 1; i < segs.size(); ++i) {
    EXPECT_EQ(segs[i].start_m, segs[i - 1].end_m);
    EXPECT_GT(segs[i].end_m, segs[i].start_m);
    const bool same = segs[i].gradient_permille == segs[i - 1].gradient_permille &&
                      segs[i].curve_radius_m == segs[i - 1].curve_radius_m &&
                      segs[i].speed_limit_ms == segs[i - 1].speed_limit_ms;
    EXPECT_FALSE(same) << "segments " << i - 1 << " and " << i << " should be one";
  }
}

TEST_F(RouteBuilder, WholeLineAndStationSpacing) {
  EXPECT_EQ(build_route(line_, "A1", "A14", train_).length_m(), 22728.0);
  EXPECT_EQ(build_route(line_, "A14", "A1", train_).length_m(), 22728.0);
  const double spacing[] = {1334, 1286, 2086, 2265, 2338, 1354, 1280,
                            1538, 993,  1982, 2366, 1275, 2631};
  for (int i = 0; i < 13; ++i) {
    const std::string a = "A" + std::to_string(i + 1);
    const std::string b = "A" + std::to_string(i + 2);
    EXPECT_EQ(build_route(line_, a, b, train_).length_m(), spacing[i]) << a << "->" << b;
  }
}

TEST_F(RouteBuilder, TrackSeenInBothDirectionsHasOppositeGradientWork) {
  // The climb summed over A1 -> A14 is the negative of that over A14 -> A1, and equals the
  // height difference read straight off the gradient table.
  auto climb = [](const physics::Route& r) {
    double h = 0.0;
    for (const auto& s : r.segments()) h += s.gradient_permille * (s.end_m - s.start_m) / 1000.0;
    return h;
  };
  double rise_to_increasing_km = 0.0;  // from km 175 up to km 22903
  for (const auto& row : line_.gradients) {
    const double lo = std::max(row.start_km_post_m, 175.0);
    const double hi = std::min(row.end_km_post_m, 22903.0);
    if (hi > lo) rise_to_increasing_km += row.value * (hi - lo) / 1000.0;
  }
  const double down = climb(build_route(line_, "A1", "A14", train_));
  const double up = climb(build_route(line_, "A14", "A1", train_));
  EXPECT_NEAR(up, rise_to_increasing_km, 1e-9);
  EXPECT_NEAR(down, -rise_to_increasing_km, 1e-9);
  EXPECT_GT(std::abs(up), 1.0);
}

TEST_F(RouteBuilder, CurvesArePlacedInTravelDirection) {
  // A1 (22903) -> A2 (21569): the 3000 m curve at km 22528..22626 lies 277..375 m out.
  const auto route = build_route(line_, "A1", "A2", train_);
  EXPECT_EQ(route.at(276.0).curve_radius_m, 0.0);
  EXPECT_EQ(route.at(277.0).curve_radius_m, 3000.0);
  EXPECT_EQ(route.at(374.9).curve_radius_m, 3000.0);
  EXPECT_EQ(route.at(375.0).curve_radius_m, 0.0);
  // The 55 km/h stretch 22783..22904 covers the first 120 m; the 40 km/h row beyond A1 is not
  // on the route.
  expect_runs(runs(route, limit_kmh), {{120, 55.0}, {1214, 80.0}});
}

// ---- errors ---------------------------------------------------------------------------------

TEST_F(RouteBuilder, UnknownStation) {
  expect_input_error([&] { build_route(line_, "A6", "X9", train_); }, "<embedded>/stations.csv", 0,
                     "station", {"one of A1, A2", "A14", "got 'X9'"});
  expect_input_error([&] { build_route(line_, "a6", "A7", train_); }, "<embedded>/stations.csv", 0,
                     "station", {"got 'a6'"});
}

TEST_F(RouteBuilder, SameStationTwice) {
  expect_input_error([&] { build_route(line_, "A6", "A6", train_); }, "<embedded>/stations.csv", 0,
                     "station", {"two different stations", "'A6'"});
}

TEST_F(RouteBuilder, LimitAboveTrainMaximumOnTheRoute) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "speed_limits.csv", "12240,13474,80", "12240,13474,90");
  const Line line = load_line(tmp.path());
  // A limit above the train's maximum speed is capped at that maximum (the program says so).
  EXPECT_DOUBLE_EQ(build_route(line, "A6", "A7", train_).speed_limit_ms(500.0), 80.0 / 3.6);
  EXPECT_NO_THROW(build_route(line, "A7", "A8", train_));
  EXPECT_NO_THROW(build_route(line, "A5", "A6", train_));
  // A faster train may use it.
  auto fast = train_;
  fast.max_speed_ms = 100.0 / 3.6;
  EXPECT_DOUBLE_EQ(build_route(line, "A6", "A7", fast).speed_limit_ms(500.0), 90.0 / 3.6);
}

TEST_F(RouteBuilder, TableNotCoveringTheRoute) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  // The gradient table now ends at km 23194 and A1 moves beyond it.
  edit_file(tmp / "stations.csv", "A1,22903", "A1,23500");
  test::write_file(
      tmp / "gradients.csv",
      test::read_file(test::contest_dir() / "gradients.csv")
          .substr(0, test::read_file(test::contest_dir() / "gradients.csv").find("23194,23214")));
  const Line line = load_line(tmp.path());
  expect_input_error([&] { build_route(line, "A1", "A2", train_); },
                     (tmp / "gradients.csv").string(), 59, "end_km_post_m",
                     {"covering km posts 21569 to 23500", "ends at 23194"});
  EXPECT_NO_THROW(build_route(line, "A2", "A3", train_));
}

TEST_F(RouteBuilder, StationsAtTheSameKmPost) {
  TempDir tmp;
  copy_contest_line(tmp.path());
  edit_file(tmp / "stations.csv", "A7,12240", "A7,13594");
  const Line line = load_line(tmp.path());
  expect_input_error([&] { build_route(line, "A6", "A7", train_); },
                     (tmp / "stations.csv").string(), 8, "km_post_m", {"different"});
}

}  // namespace
}  // namespace ecorail::data
