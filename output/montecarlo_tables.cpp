#include "output/montecarlo_tables.hpp"

#include <cstdio>

namespace ecorail::output {

void write_day_records_csv(std::ostream& out, const std::vector<recovery::DayRecord>& days) {
  out << "day,arrivals,punctual,punctuality,mean_lateness_s,p95_lateness_s,max_lateness_s,"
         "recoveries,mean_recovery_time_s,unrecovered_episodes,primary_delays,tail_delays,"
         "knock_on_delays,takeovers,arrivals_taken_over,traction_kJ,regen_kJ,used_regen_kJ,"
         "substation_kJ\n";
  char buf[600];
  for (const recovery::DayRecord& r : days) {
    std::snprintf(
        buf, sizeof buf,
        "%llu,%lld,%lld,%.6f,%.4f,%.3f,%.3f,%lld,%.3f,%lld,%lld,%lld,%lld,%lld,%lld,%.3f,"
        "%.3f,%.3f,%.3f\n",
        static_cast<unsigned long long>(r.day), static_cast<long long>(r.arrivals),
        static_cast<long long>(r.punctual), r.punctuality(), r.mean_lateness_s(), r.p95_lateness_s,
        r.max_lateness_s, static_cast<long long>(r.recoveries),
        r.recoveries > 0 ? r.recovery_time_sum_s / static_cast<double>(r.recoveries) : 0.0,
        static_cast<long long>(r.unrecovered_episodes), static_cast<long long>(r.primary_delays),
        static_cast<long long>(r.tail_delays), static_cast<long long>(r.knock_on_delays),
        static_cast<long long>(r.takeovers), static_cast<long long>(r.arrivals_taken_over),
        r.traction_kJ, r.regen_kJ, r.used_regen_kJ, r.substation_kJ);
    out << buf;
  }
}

}  // namespace ecorail::output
