// Periodic regimes of one trip: what a long timetable whose headways repeat with period one
// (constant headway a) or two (alternating a, b) is worth per headway in steady state, for any
// energy model. A regime's value is the growth of the used energy (traction less substation
// energy; the quantity the headway search maximises) per period in steady state: what the two
// middle trains of a long periodic timetable use (a model that attributes the used energy to
// the braking train), else the growth (U(P + 2 periods) - U(P periods)) / 2, P periods lasting
// at least twice the trip time so that the middle trains see a full periodic neighbourhood. The
// analysis evaluates every constant and every alternating pair of one headway class on a grid, so
// that the resonant regimes (the few headway pairs whose braking and motoring phases line up) show
// without knowing the line; the fleet search builds its starts from them (fleet/regime_start.hpp).
#pragma once

#include <functional>
#include <vector>

#include "energy/fleet_energy_model.hpp"

namespace ecorail::fleet {

struct PeriodicRegime {
  int a_s = 0, b_s = 0;            // a_s == b_s: a constant headway
  double used_per_period_J = 0.0;  // steady-state used energy per period (a + b seconds)
  double used_per_headway_J() const { return 0.5 * used_per_period_J; }
};

struct PeriodicRegimeOptions {
  int lo_s = 120, hi_s = 660;  // the headway class's range
  int grid_s = 10;             // every multiple of grid_s within [lo_s, hi_s]
  int max_spread_s = 120;      // alternating pairs with b - a at most this
  int threads = 0;             // 0: OpenMP's default
  // Asked between regimes; once it returns true the rest are left unpriced (value 0) and the
  // analysis returns at once (a caller out of time drops it).
  std::function<bool()> stop;
};

// Every regime a <= b on the grid (constants included), in the order (a, b). The model is
// rebuilt for each periodic timetable (same trip and options, the timetable's own limits).
std::vector<PeriodicRegime> analyse_periodic_regimes(const energy::FleetEnergyModel& model,
                                                     const PeriodicRegimeOptions& options);

// The used energy of a periodic timetable of `periods` periods (2 * periods + 1 trains, the
// first departing at 0), evaluated directly by the model rebuilt for it.
double periodic_timetable_used_J(const energy::FleetEnergyModel& model, int a_s, int b_s,
                                 int periods);

// The steady-state used energy of one period (a + b seconds): the two middle trains' attributed
// used energy in a timetable of base_periods + 1 periods when the model attributes it to
// trains, else half the growth from base_periods to base_periods + 2 periods.
double steady_used_per_period_J(const energy::FleetEnergyModel& model, int a_s, int b_s);

// Periods whose timetable lasts at least twice the trip time (the analysis' base length).
int base_periods(const energy::FleetEnergyModel& model, int a_s, int b_s);

}  // namespace ecorail::fleet
