#include "data/timetable_csv_reader.hpp"

#include <cmath>
#include <map>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"

namespace ecorail::data {

TimetableStopTimes read_timetable_csv(const std::string& file) {
  const CsvTable table = CsvTable::read(file);
  const std::size_t c_train = table.column("train"), c_station = table.column("station");
  const std::size_t c_arr = table.column("arrival_s"), c_dep = table.column("departure_s");
  std::map<long, std::vector<const CsvRow*>> by_train;
  for (const CsvRow& row : table.rows()) {
    const double k = table.number(row, c_train);
    if (k != std::floor(k) || k < 1 || k > 1e6)
      throw InputError(file, row.row, "train", "a train number >= 1");
    by_train[static_cast<long>(k)].push_back(&row);
  }
  if (by_train.empty()) throw InputError(file, 0, "train", "at least one train's rows");
  TimetableStopTimes out;
  long expected = 1;
  for (const auto& [k, rows] : by_train) {
    if (k != expected)
      throw InputError(file, rows.front()->row, "train",
                       "trains numbered 1, 2, ... without gaps; train " + std::to_string(expected) +
                           " is missing");
    ++expected;
    std::vector<std::string> names;
    std::vector<double> arrival_s, departure_s;
    for (const CsvRow* row : rows) {
      names.push_back(table.text(*row, c_station));
      arrival_s.push_back(table.number(*row, c_arr));
      departure_s.push_back(table.number(*row, c_dep));
    }
    if (out.stations.empty()) out.stations = names;
    if (names != out.stations)
      throw InputError(file, rows.front()->row, "station",
                       "the same stations for every train (train " + std::to_string(k) +
                           " differs from train 1)");
    out.arrival_s.push_back(std::move(arrival_s));
    out.departure_s.push_back(std::move(departure_s));
  }
  return out;
}

}  // namespace ecorail::data
