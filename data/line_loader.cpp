#include "data/line_loader.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "data/csv_reader.hpp"
#include "data/embedded.hpp"
#include "data/input_error.hpp"
#include "data/plausibility.hpp"
#include "data/toml_util.hpp"
#include "data/ttobench_io.hpp"

namespace ecorail::data {

namespace {

// Consecutive rows whose end and start differ by no more than this are contiguous.
constexpr double kContiguityTolerance_m = 1e-6;

constexpr const char* kStart = "start_km_post_m";
constexpr const char* kEnd = "end_km_post_m";

struct TableSpec {
  const char* csv_name;   // file in a line directory
  const char* toml_name;  // array of tables in a line TOML file
  const char* value_key;  // column / key of the value
};

constexpr TableSpec kGradients{"gradients.csv", "gradients", "gradient_permille"};
constexpr TableSpec kLimits{"speed_limits.csv", "speed_limits", "limit_kmh"};
constexpr TableSpec kCurves{"curves.csv", "curves", "radius_m"};

std::string in_quotes(const std::string& s) {
  return "'" + s + "'";
}

// ---- CSV ----------------------------------------------------------------------------------

// Latitude and longitude in degrees, both or neither, within their ranges (WGS 84).
void set_coordinates(Station& s, double lat, double lon, const std::string& file, int row) {
  if (!(lat >= -90.0 && lat <= 90.0)) {
    throw InputError(file, row, "lat",
                     "a latitude from -90 to 90 degrees; got " + format_number(lat));
  }
  if (!(lon >= -180.0 && lon <= 180.0)) {
    throw InputError(file, row, "lon",
                     "a longitude from -180 to 180 degrees; got " + format_number(lon));
  }
  s.lat_deg = lat;
  s.lon_deg = lon;
}

std::vector<Station> stations_from_csv(const CsvTable& t) {
  const auto name_col = t.column("station");
  const auto km_col = t.column("km_post_m");
  // Optional coordinates: both columns or neither; in a row both fields or neither.
  const bool located = t.has_column("lat") || t.has_column("lon");
  const std::size_t lat_col = located ? t.column("lat") : 0;
  const std::size_t lon_col = located ? t.column("lon") : 0;
  std::vector<Station> out;
  for (const auto& row : t.rows()) {
    Station s{t.text(row, name_col), t.number(row, km_col), row.row};
    if (located && (!t.text(row, lat_col).empty() || !t.text(row, lon_col).empty())) {
      if (t.text(row, lat_col).empty() || t.text(row, lon_col).empty()) {
        throw InputError(t.file(), row.row, t.text(row, lat_col).empty() ? "lat" : "lon",
                         "both lat and lon, or neither; got only one");
      }
      set_coordinates(s, t.number(row, lat_col), t.number(row, lon_col), t.file(), row.row);
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<IntervalRow> rows_from_csv(const CsvTable& t, const TableSpec& spec) {
  const auto start_col = t.column(kStart);
  const auto end_col = t.column(kEnd);
  const auto value_col = t.column(spec.value_key);
  std::vector<IntervalRow> out;
  for (const auto& row : t.rows()) {
    out.push_back(IntervalRow{t.number(row, start_col), t.number(row, end_col),
                              t.number(row, value_col), row.row});
  }
  return out;
}

// ---- validation ---------------------------------------------------------------------------

// Plausibility ranges (data/plausibility.hpp): values that parse but describe no railway.
void check_plausible(const IntervalRow& r, const std::string& file, const TableSpec& spec) {
  auto refuse = [&](const char* field, const std::string& expected, double got) {
    throw InputError(file, r.source_row, field,
                     expected + " (plausibility range); got " + format_number(got));
  };
  for (const auto& [field, km] : {std::pair{kStart, r.start_km_post_m}, {kEnd, r.end_km_post_m}}) {
    if (!(std::abs(km) <= plausible::kMaxKmPost_m)) {
      refuse(field, "a km post within +-" + format_number(plausible::kMaxKmPost_m) + " m", km);
    }
  }
  if (&spec == &kGradients && !(std::abs(r.value) <= plausible::kMaxGradient_permille)) {
    refuse(spec.value_key,
           "a gradient within +-" + format_number(plausible::kMaxGradient_permille) + " per mille",
           r.value);
  }
  if (&spec == &kCurves && r.value != 0.0 && !(r.value >= plausible::kMinCurveRadius_m)) {
    refuse(spec.value_key,
           "0 (straight) or a radius of at least " + format_number(plausible::kMinCurveRadius_m) +
               " m",
           r.value);
  }
  if (&spec == &kLimits && !(r.value <= plausible::kMaxSpeedLimit_kmh)) {
    refuse(spec.value_key,
           "a speed limit of at most " + format_number(plausible::kMaxSpeedLimit_kmh) + " km/h",
           r.value);
  }
}

// Row checks in file order, then sorts by start and checks that consecutive rows meet.
void validate_table(std::vector<IntervalRow>& rows, const std::string& file,
                    const TableSpec& spec) {
  const std::string value_key = spec.value_key;
  if (rows.empty()) {
    throw InputError(file, 0, "", "at least one row after the header; got none");
  }
  for (const auto& r : rows) {
    if (!(r.end_km_post_m > r.start_km_post_m)) {
      throw InputError(file, r.source_row, kEnd,
                       "an end greater than the start " + format_number(r.start_km_post_m) +
                           "; got " + format_number(r.end_km_post_m));
    }
    if (&spec == &kLimits && !(r.value > 0.0)) {
      throw InputError(file, r.source_row, value_key,
                       "a speed limit above 0 km/h; got " + format_number(r.value));
    }
    if (&spec == &kCurves && r.value < 0.0) {
      throw InputError(file, r.source_row, value_key,
                       "a radius of at least 0 m (0 = straight); got " + format_number(r.value));
    }
    check_plausible(r, file, spec);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const IntervalRow& a, const IntervalRow& b) {
    return a.start_km_post_m < b.start_km_post_m;
  });
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& prev = rows[i - 1];
    const auto& cur = rows[i];
    const double diff = cur.start_km_post_m - prev.end_km_post_m;
    if (std::abs(diff) <= kContiguityTolerance_m) continue;
    const std::string expected = "a start equal to the end " + format_number(prev.end_km_post_m) +
                                 " of the previous row " + std::to_string(prev.source_row) +
                                 "; got " + format_number(cur.start_km_post_m) + ", ";
    if (diff > 0.0) {
      throw InputError(file, cur.source_row, kStart,
                       expected + "a gap of " + format_number(diff) + " m");
    }
    throw InputError(file, cur.source_row, kStart,
                     expected + "an overlap of " + format_number(-diff) + " m");
  }
}

void validate(Line& line, const std::string& station_field) {
  if (line.stations.empty()) {
    throw InputError(line.stations_file, 0, "", "at least one station; got none");
  }
  for (std::size_t i = 0; i < line.stations.size(); ++i) {
    const auto& s = line.stations[i];
    if (s.name.empty()) {
      throw InputError(line.stations_file, s.source_row, station_field,
                       "a station name; got an empty field");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (line.stations[j].name == s.name) {
        throw InputError(line.stations_file, s.source_row, station_field,
                         "a station name not used before; got " + in_quotes(s.name) +
                             " again (first at row " + std::to_string(line.stations[j].source_row) +
                             ")");
      }
    }
  }
  validate_table(line.gradients, line.gradients_file, kGradients);
  validate_table(line.limits, line.limits_file, kLimits);
  validate_table(line.curves, line.curves_file, kCurves);
}

Line line_from_csv(const CsvTable& stations, const CsvTable& gradients, const CsvTable& limits,
                   const CsvTable& curves) {
  Line line;
  line.stations_file = stations.file();
  line.gradients_file = gradients.file();
  line.limits_file = limits.file();
  line.curves_file = curves.file();
  line.stations = stations_from_csv(stations);
  line.gradients = rows_from_csv(gradients, kGradients);
  line.limits = rows_from_csv(limits, kLimits);
  line.curves = rows_from_csv(curves, kCurves);
  validate(line, "station");
  return line;
}

// ---- TOML ---------------------------------------------------------------------------------

const toml::array& toml_entries(const toml::table& root, const char* key, const std::string& file) {
  const toml::node* node = root.get(key);
  const toml::array* arr = node != nullptr ? node->as_array() : nullptr;
  if (arr == nullptr || arr->empty()) {
    throw InputError(
        file, 0, key,
        std::string("an array of tables [[") + key + "]] with at least one entry; got " +
            (arr != nullptr ? std::string("an empty array") : toml_util::describe(node)));
  }
  for (std::size_t i = 0; i < arr->size(); ++i) {
    if (!arr->get(i)->is_table()) {
      throw InputError(
          file, static_cast<int>(i + 1), key,
          std::string("a table per entry of ") + key + "; got " + toml_util::describe(arr->get(i)));
    }
  }
  return *arr;
}

std::vector<IntervalRow> rows_from_toml(const toml::table& root, const TableSpec& spec,
                                        const std::string& file) {
  const auto& arr = toml_entries(root, spec.toml_name, file);
  std::vector<IntervalRow> out;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const int row = static_cast<int>(i + 1);
    const auto& t = *arr.get(i)->as_table();
    toml_util::check_keys(t, {kStart, kEnd, spec.value_key}, file, row, "");
    out.push_back(IntervalRow{toml_util::number(t.get(kStart), file, row, kStart),
                              toml_util::number(t.get(kEnd), file, row, kEnd),
                              toml_util::number(t.get(spec.value_key), file, row, spec.value_key),
                              row});
  }
  return out;
}

Line line_from_toml(std::string_view text, const std::string& file) {
  const toml::table root = toml_util::parse(text, file);
  toml_util::check_keys(root, {"stations", "gradients", "speed_limits", "curves"}, file, 0, "");
  Line line;
  line.stations_file = line.gradients_file = line.limits_file = line.curves_file = file;
  const auto& stations = toml_entries(root, "stations", file);
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const int row = static_cast<int>(i + 1);
    const auto& t = *stations.get(i)->as_table();
    toml_util::check_keys(t, {"name", "km_post_m", "lat", "lon"}, file, row, "");
    const toml::node* name = t.get("name");
    if (name == nullptr || !name->is_string()) {
      throw InputError(file, row, "name", "a string; got " + toml_util::describe(name));
    }
    Station s{std::string(name->as_string()->get()),
              toml_util::number(t.get("km_post_m"), file, row, "km_post_m"), row};
    if (t.get("lat") != nullptr || t.get("lon") != nullptr) {
      if (t.get("lat") == nullptr || t.get("lon") == nullptr) {
        throw InputError(file, row, t.get("lat") == nullptr ? "lat" : "lon",
                         "both lat and lon, or neither; got only one");
      }
      set_coordinates(s, toml_util::number(t.get("lat"), file, row, "lat"),
                      toml_util::number(t.get("lon"), file, row, "lon"), file, row);
    }
    line.stations.push_back(std::move(s));
  }
  line.gradients = rows_from_toml(root, kGradients, file);
  line.limits = rows_from_toml(root, kLimits, file);
  line.curves = rows_from_toml(root, kCurves, file);
  validate(line, "name");
  return line;
}

CsvTable embedded_table(const char* name) {
  const std::string_view text = embedded::find(name);
  const std::string label = std::string("<embedded>/") + name;
  if (text.empty()) throw InputError(label, 0, "", "a table compiled into the program; got none");
  return CsvTable::parse(text, label);
}

}  // namespace

Line line_from_csv_tables(const CsvTable& stations, const CsvTable& gradients,
                          const CsvTable& limits, const CsvTable& curves) {
  return line_from_csv(stations, gradients, limits, curves);
}

Line line_from_toml_text(std::string_view text, const std::string& file) {
  return line_from_toml(text, file);
}

Line default_line() {
  Line line = line_from_csv(embedded_table("stations.csv"), embedded_table(kGradients.csv_name),
                            embedded_table(kLimits.csv_name), embedded_table(kCurves.csv_name));
  line.name = "contest";
  return line;
}

Line load_line(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw InputError(path.string(), 0, "",
                     "a directory of line CSV files or a .toml line file; got no such file or "
                     "directory");
  }
  Line line;
  if (std::filesystem::is_directory(status)) {
    line = line_from_csv(
        CsvTable::read(path / "stations.csv"), CsvTable::read(path / kGradients.csv_name),
        CsvTable::read(path / kLimits.csv_name), CsvTable::read(path / kCurves.csv_name));
  } else if (path.extension() == ".toml") {
    line = line_from_toml(read_text_file(path), path.string());
  } else if (const std::string text = read_text_file(path); looks_like_json(text)) {
    line = line_from_ttobench(text, path.string());  // TTOBench track, known by its content
  } else {
    throw InputError(path.string(), 0, "",
                     "a directory of line CSV files, a .toml line file or a TTOBench track (JSON); "
                     "got a file named " +
                         in_quotes(path.filename().string()));
  }
  line.name = path.string();
  return line;
}

}  // namespace ecorail::data
