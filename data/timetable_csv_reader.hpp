// Reading the timetable CSV that `ecorail timetable evaluate|optimise --csv` and `montecarlo
// --adjust --adjusted-csv` write (docs/formats.md, "Timetable CSV"): columns train, station,
// arrival_s, departure_s (others ignored), rows grouped by train, trains numbered 1, 2, ...
// without gaps, every train calling at the same stations in the order of its rows. A file that
// breaks any of this is an InputError naming the file, the row and the field.
#pragma once

#include <string>
#include <vector>

namespace ecorail::data {

struct TimetableStopTimes {
  std::vector<std::string> stations;             // in the order of travel
  std::vector<std::vector<double>> arrival_s;    // per train (in train order), per station
  std::vector<std::vector<double>> departure_s;  // per train, per station
};

TimetableStopTimes read_timetable_csv(const std::string& file);

}  // namespace ecorail::data
