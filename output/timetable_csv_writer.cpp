#include "output/timetable_csv_writer.hpp"

#include <cmath>
#include <cstdio>

namespace ecorail::output {

std::string clock_text(double t_s) {
  const long s = std::lround(t_s);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

void write_timetable_csv(std::ostream& out, const std::vector<TimetableCsvRow>& rows) {
  out << "train,station,position_m,arrival_s,departure_s,arrival,departure,dwell_s\n";
  char buf[256];
  for (const TimetableCsvRow& r : rows) {
    std::snprintf(buf, sizeof buf, "%zu,%s,%.1f,%.3f,%.3f,%s,%s,%.3f\n", r.train, r.station.c_str(),
                  r.position_m, r.arrival_s, r.departure_s, clock_text(r.arrival_s).c_str(),
                  clock_text(r.departure_s).c_str(), r.dwell_s);
    out << buf;
  }
}

void write_timetable_csv(std::ostream& out, const recovery::Plan& plan,
                         const std::vector<double>& positions_m) {
  std::vector<TimetableCsvRow> rows;
  for (std::size_t k = 0; k < plan.trains.size(); ++k)
    for (std::size_t j = 0; j < plan.stations.size(); ++j)
      rows.push_back({k + 1, plan.stations[j], positions_m.at(j), plan.trains[k].arrival_s[j],
                      plan.trains[k].departure_s[j], plan.dwell_s(k, j)});
  write_timetable_csv(out, rows);
}

}  // namespace ecorail::output
