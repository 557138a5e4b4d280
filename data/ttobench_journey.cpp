#include "data/ttobench_journey.hpp"

#include <cmath>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/ttobench_json.hpp"

namespace ecorail::data {

namespace {
using nlohmann::json;
using ttobench::index;
using ttobench::JsonReader;

const char* const kColumns[] = {"position", "lower time constraint", "upper time constraint",
                                "lower speed constraint", "upper speed constraint"};
}  // namespace

TtobenchJourney journey_from_ttobench(const std::string& text, const std::string& file) {
  const JsonReader r(file);
  const json root = r.parse_root(text, ttobench::Kind::Journey,
                                 "a TTOBench journey (an object with \"timing points\")");
  r.check_keys(root, {"metadata", "timing points"}, "");
  TtobenchJourney j;
  j.other_metadata = r.metadata(root, ttobench::kJourneyMetadataKeys);
  const json& meta = r.object(root, "metadata", "");
  j.id = r.string(meta, "id", "metadata");
  j.track_id = r.string(meta, "associated track", "metadata");

  const json& tp = r.object(root, "timing points", "");
  r.check_keys(tp, {"units", "values"}, "timing points");
  const json& units = r.object(tp, "units", "timing points");
  std::vector<std::string> names(std::begin(kColumns), std::end(kColumns));
  r.check_keys(units, names, "timing points.units");
  const ttobench::UnitTable* tables[] = {&ttobench::kLength, &ttobench::kTime, &ttobench::kTime,
                                         &ttobench::kSpeed, &ttobench::kSpeed};
  double factor[5];
  for (int k = 0; k < 5; ++k) {
    const std::string at = "timing points.units." + names[k];
    if (!units.contains(names[k])) r.fail(at, "a unit; got nothing (the key is missing)");
    factor[k] = r.unit_factor(units.at(names[k]), at, *tables[k]);
  }
  if (!tp.contains("values")) r.fail("timing points.values", "an array of timing points");
  const json& values = r.array(tp.at("values"), "timing points.values");
  if (values.size() < 2) {
    r.fail("timing points.values", "at least two timing points (departure and arrival); got " +
                                       std::to_string(values.size()));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string rp = index("timing points.values", i);
    const json& row = r.array(values[i], rp);
    if (row.size() != 5) {
      r.fail(rp, "5 values [position, lower time, upper time, lower speed, upper speed]; got " +
                     std::to_string(row.size()));
    }
    TimingPoint p;
    double* fields[] = {&p.position_m, &p.earliest_s, &p.latest_s, &p.min_speed_ms,
                        &p.max_speed_ms};
    for (int k = 0; k < 5; ++k) {
      if (k > 0 && row[k].is_null()) continue;  // an open bound
      *fields[k] = r.number(row[k], index(rp, k)) * factor[k];
    }
    if (p.position_m < 0.0) r.fail(index(rp, 0), "a position of at least 0 m");
    if (!j.points.empty() && p.position_m < j.points.back().position_m) {
      r.fail(index(rp, 0), "positions in increasing order (the previous point is at " +
                               format_number(j.points.back().position_m) + " m)");
    }
    if (p.earliest_s > p.latest_s) r.fail(index(rp, 2), "an upper time >= the lower time");
    if (p.min_speed_ms > p.max_speed_ms) r.fail(index(rp, 4), "an upper speed >= the lower");
    if (std::isfinite(p.min_speed_ms) && p.min_speed_ms < 0.0)
      r.fail(index(rp, 3), "a speed of at least 0");
    j.points.push_back(p);
  }
  return j;
}

}  // namespace ecorail::data
