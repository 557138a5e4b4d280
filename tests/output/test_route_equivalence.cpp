// data::line_runs_difference: a line and its TTOBench export drive alike; a change to one
// gradient, limit or curve anywhere on the line is found and named.
#include <gtest/gtest.h>

#include "data/line_loader.hpp"
#include "data/route_equivalence.hpp"
#include "data/train_io.hpp"
#include "data/ttobench_io.hpp"
#include "output/ttobench_writer.hpp"

namespace ecorail::data {
namespace {

TEST(RouteEquivalence, ExportedReferenceLineDrivesAlike) {
  const Line line = default_line();
  const physics::Train train = default_train();
  const Line back = line_from_ttobench(output::line_to_ttobench(line, "ref"), "ref.json");
  EXPECT_NE(back.checksum(), line.checksum());             // the tables differ ...
  EXPECT_EQ(line_runs_difference(line, back, train), "");  // ... the runs do not
  EXPECT_EQ(line_runs_difference(back, line, train), "");
}

TEST(RouteEquivalence, FindsEachKindOfChange) {
  const Line line = default_line();
  const physics::Train train = default_train();
  Line gradient = line, limit = line, curve = line;
  gradient.gradients[5].value += 0.5;
  limit.limits[7].value -= 5.0;
  for (std::size_t i = curve.curves.size() / 2; i < curve.curves.size(); ++i) {
    if (curve.curves[i].value > 0.0) {  // a curve between the stations, not beyond the ends
      curve.curves[i].value *= 1.1;
      break;
    }
  }
  EXPECT_NE(line_runs_difference(line, gradient, train).find("gradient"), std::string::npos);
  EXPECT_NE(line_runs_difference(line, limit, train).find("speed limit"), std::string::npos);
  EXPECT_NE(line_runs_difference(line, curve, train).find("curve resistance"), std::string::npos);
  Line renamed = line;
  renamed.stations[3].name = "X";
  EXPECT_NE(line_runs_difference(line, renamed, train), "");
}

}  // namespace
}  // namespace ecorail::data
