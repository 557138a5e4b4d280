// The per-day table of a Monte Carlo run (`ecorail montecarlo --csv`, docs/outputs.md): one row
// per simulated day, in day order, with its arrivals, punctuality, lateness, recoveries, delays
// and energies.
#pragma once

#include <ostream>
#include <vector>

#include "recovery/monte_carlo_stats.hpp"

namespace ecorail::output {

void write_day_records_csv(std::ostream& out, const std::vector<recovery::DayRecord>& days);

}  // namespace ecorail::output
