// TTOBench track JSON -> data::Line (the mapping is documented in docs/formats.md).
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/ttobench_io.hpp"
#include "data/ttobench_json.hpp"

namespace ecorail::data {

namespace {

using nlohmann::json;
using ttobench::index;
using ttobench::join;
using ttobench::JsonReader;

std::vector<std::pair<std::string, std::string>> read_metadata(const JsonReader& r,
                                                               const json& root) {
  auto other = r.metadata(root, ttobench::kTrackMetadataKeys);
  r.string(r.object(root, "metadata", ""), "id", "metadata");
  return other;
}

// A table {"units": {col: unit}, "values": [[...], ...]}: the rows converted to SI column by
// column (factors from units), each row exactly columns.size() long. Column 0 must be strictly
// increasing from 0 when `from_zero`. A column whose units are empty takes numbers as they are;
// allow_infinity columns also accept "infinity".
struct Column {
  std::string name;
  const ttobench::UnitTable* units;
  bool allow_infinity = false;
};

std::vector<std::vector<double>> read_table(const JsonReader& r, const json& root,
                                            const std::string& key,
                                            const std::vector<Column>& columns, bool from_zero) {
  const json& t = r.object(root, key, "");
  r.check_keys(t, {"units", "values"}, key);
  const json& units = r.object(t, "units", key);
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  r.check_keys(units, names, join(key, "units"));
  std::vector<double> factors;
  for (const auto& c : columns) {
    const std::string at = join(join(key, "units"), c.name);
    if (!units.contains(c.name)) r.fail(at, "a unit; got nothing (the key is missing)");
    factors.push_back(r.unit_factor(units.at(c.name), at, *c.units));
  }
  if (!t.contains("values")) r.fail(join(key, "values"), "an array of rows; got nothing");
  const std::string vpath = join(key, "values");
  const json& values = r.array(t.at("values"), vpath);
  if (values.empty()) r.fail(vpath, "at least one row; got an empty array");
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string rp = index(vpath, i);
    const json& row = r.array(values[i], rp);
    if (row.size() != columns.size()) {
      r.fail(rp, "a row of " + std::to_string(columns.size()) + " numbers; got " +
                     std::to_string(row.size()));
    }
    std::vector<double> out;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const double v = columns[k].allow_infinity ? r.number_or_infinity(row[k], index(rp, k))
                                                 : r.number(row[k], index(rp, k));
      out.push_back(v * factors[k]);
    }
    if (i == 0 && from_zero && out[0] != 0.0) {
      r.fail(index(rp, 0), "the first row at position 0; got " + format_number(out[0]));
    }
    if (i > 0 && !(out[0] > rows.back()[0])) {
      r.fail(index(rp, 0), "a position above the previous row's " + format_number(rows.back()[0]) +
                               " (strictly increasing); got " + format_number(out[0]));
    }
    rows.push_back(std::move(out));
  }
  return rows;
}

// Rows [x_i, x_{i+1}) with the last ending at the track's length, from a table of starts.
std::vector<IntervalRow> intervals(const JsonReader& r, const std::string& key,
                                   const std::vector<std::vector<double>>& rows, double length_m) {
  std::vector<IntervalRow> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double end = i + 1 < rows.size() ? rows[i + 1][0] : length_m;
    if (!(end > rows[i][0])) {
      r.fail(index(index(join(key, "values"), i), 0), "a position below the track's length " +
                                                          format_number(length_m) + " m; got " +
                                                          format_number(rows[i][0]));
    }
    out.push_back(IntervalRow{rows[i][0], end, rows[i][1], static_cast<int>(i + 1)});
  }
  return out;
}

double curvature_of(const JsonReader& r, double radius_m, const std::string& path) {
  if (std::isinf(radius_m)) return 0.0;
  if (radius_m == 0.0) r.fail(path, "a non-zero radius in m (\"infinity\" = straight); got 0");
  return 1.0 / radius_m;
}

}  // namespace

bool looks_like_json(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  return first != std::string::npos && (text[first] == '{' || text[first] == '[');
}

Line line_from_ttobench(const std::string& text, const std::string& file) {
  const JsonReader r(file);
  const json root =
      r.parse_root(text, ttobench::Kind::Track, "a TTOBench track (an object with \"stops\")");
  r.check_keys(root,
               {"metadata", "altitude", "stops", "stop names", "speed limits", "gradients",
                "curvatures", "tunnels", "ETCS braking data"},
               "");
  read_metadata(r, root);
  if (root.contains("altitude")) r.quantity(root, "altitude", ttobench::kLength);

  Line line;
  line.stations_file = line.gradients_file = line.limits_file = line.curves_file =
      line.tunnels_file = file;
  line.cap_limits_at_train_speed = true;

  // Stops: {"unit", "values": [0, ..., length]}.
  const json& stops = r.object(root, "stops", "");
  r.check_keys(stops, {"unit", "values"}, "stops");
  if (!stops.contains("unit")) r.fail("stops.unit", "a unit; got nothing (the key is missing)");
  const double stop_factor = r.unit_factor(stops.at("unit"), "stops.unit", ttobench::kLength);
  if (!stops.contains("values")) r.fail("stops.values", "an array of positions; got nothing");
  const json& stop_values = r.array(stops.at("values"), "stops.values");
  if (stop_values.size() < 2) {
    r.fail("stops.values", "at least two stops (departure at 0 and the end of the track); got " +
                               std::to_string(stop_values.size()));
  }
  std::vector<std::string> names;
  if (root.contains("stop names")) {
    const json& n = r.array(root.at("stop names"), "stop names");
    if (n.size() != stop_values.size()) {
      r.fail("stop names", "one name per stop (" + std::to_string(stop_values.size()) + "); got " +
                               std::to_string(n.size()));
    }
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (!n[i].is_string() || n[i].get<std::string>().empty()) {
        r.fail(index("stop names", i), "a non-empty string");
      }
      names.push_back(n[i].get<std::string>());
      for (std::size_t k = 0; k < i; ++k) {
        if (names[k] == names[i]) r.fail(index("stop names", i), "a name not used before");
      }
    }
  }
  for (std::size_t i = 0; i < stop_values.size(); ++i) {
    const std::string at = index("stops.values", i);
    const double x = r.number(stop_values[i], at) * stop_factor;
    if (i == 0 && x != 0.0) r.fail(at, "the first stop at position 0; got " + format_number(x));
    if (i > 0 && !(x > line.stations.back().km_post_m)) {
      r.fail(at, "a position above the previous stop's " +
                     format_number(line.stations.back().km_post_m) + " (strictly increasing)");
    }
    line.stations.push_back(
        Station{names.empty() ? "S" + std::to_string(i) : names[i], x, static_cast<int>(i + 1)});
  }
  const double length_m = line.stations.back().km_post_m;

  const Column position{"position", &ttobench::kLength};
  line.limits = intervals(
      r, "speed limits",
      read_table(r, root, "speed limits", {position, {"velocity", &ttobench::kSpeedKmh}}, true),
      length_m);
  for (const auto& row : line.limits) {
    if (!(row.value > 0.0)) {
      r.fail(index(index("speed limits.values", row.source_row - 1), 1),
             "a speed limit above 0; got " + format_number(row.value));
    }
  }
  if (root.contains("gradients")) {
    line.gradients = intervals(
        r, "gradients",
        read_table(r, root, "gradients", {position, {"slope", &ttobench::kSlope}}, true), length_m);
  } else {
    line.gradients.push_back(IntervalRow{0.0, length_m, 0.0, 0});  // level track
  }
  line.curves.push_back(IntervalRow{0.0, length_m, 0.0, 0});  // straight unless curvatures
  if (root.contains("curvatures")) {
    const auto rows = read_table(r, root, "curvatures",
                                 {position,
                                  {"radius at start", &ttobench::kLength, true},
                                  {"radius at end", &ttobench::kLength, true}},
                                 true);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const std::string rp = index("curvatures.values", i);
      const double end = i + 1 < rows.size() ? rows[i + 1][0] : length_m;
      if (!(end > rows[i][0])) {
        r.fail(index(rp, 0), "a position below the track's length " + format_number(length_m) +
                                 " m; got " + format_number(rows[i][0]));
      }
      line.curvatures.push_back(
          CurvatureRow{rows[i][0], end, curvature_of(r, rows[i][1], index(rp, 1)),
                       curvature_of(r, rows[i][2], index(rp, 2)), static_cast<int>(i + 1)});
    }
  }
  // Without a clothoid the curvatures are plain curves (radius |1/k|, 0 = straight): the
  // plain route builder takes them, with 600/R as for any line.
  bool clothoid = false;
  for (const auto& c : line.curvatures) {
    clothoid = clothoid || c.curvature_start_per_m != c.curvature_end_per_m;
  }
  if (!line.curvatures.empty() && !clothoid) {
    line.curves.clear();
    for (const auto& c : line.curvatures) {
      const double k = std::abs(c.curvature_start_per_m);
      line.curves.push_back(
          IntervalRow{c.start_km_post_m, c.end_km_post_m, k > 0.0 ? 1.0 / k : 0.0, c.source_row});
    }
    line.curvatures.clear();
  }
  if (root.contains("tunnels")) {
    const auto rows = read_table(
        r, root, "tunnels",
        {position, {"length", &ttobench::kLength}, {"cross section", &ttobench::kArea}}, false);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const std::string rp = index("tunnels.values", i);
      if (rows[i][0] < 0.0) r.fail(index(rp, 0), "a position of at least 0 m");
      if (!(rows[i][1] >= 0.0)) r.fail(index(rp, 1), "a length of at least 0 m");
      if (rows[i][0] + rows[i][1] > length_m + 1e-9) {
        r.fail(index(rp, 1), "a tunnel ending by the track's end at " + format_number(length_m) +
                                 " m; got one ending at " + format_number(rows[i][0] + rows[i][1]));
      }
      if (i > 0 && rows[i][0] < rows[i - 1][0] + rows[i - 1][1]) {
        r.fail(index(rp, 0), "a tunnel starting after the previous one ends at " +
                                 format_number(rows[i - 1][0] + rows[i - 1][1]));
      }
      if (!(rows[i][2] > 0.0)) r.fail(index(rp, 2), "a cross-section above 0 m^2");
      if (rows[i][1] > 0.0) {
        line.tunnels.push_back(
            TunnelRow{rows[i][0], rows[i][0] + rows[i][1], rows[i][2], static_cast<int>(i + 1)});
      }
    }
  }
  return line;
}

std::vector<std::string> ttobench_metadata_warnings(const std::string& text) {
  const ttobench::Kind kind = ttobench::detect(text);
  if (kind != ttobench::Kind::Track && kind != ttobench::Kind::Train &&
      kind != ttobench::Kind::Journey) {
    return {};
  }
  const json root = json::parse(text, nullptr, false);
  if (!root.is_object() || !root.contains("metadata") || !root.at("metadata").is_object()) {
    return {};
  }
  const std::vector<std::string>& known =
      kind == ttobench::Kind::Track   ? ttobench::kTrackMetadataKeys
      : kind == ttobench::Kind::Train ? ttobench::kTrainMetadataKeys
                                      : ttobench::kJourneyMetadataKeys;
  return ttobench::metadata_warnings(JsonReader("").metadata(root, known));
}

std::vector<std::string> ttobench_unmodelled_fields(const std::string& text) {
  std::vector<std::string> out;
  const ttobench::Kind kind = ttobench::detect(text);
  if (kind != ttobench::Kind::Track && kind != ttobench::Kind::Train) return out;
  const json root = json::parse(text, nullptr, false);
  if (root.is_object() && root.contains("ETCS braking data")) {
    out.push_back(
        "'ETCS braking data' (signalling supervision curves; ecorail's trajectory model brakes "
        "within the train's own force and deceleration limits and does not use them)");
  }
  return out;
}

}  // namespace ecorail::data
