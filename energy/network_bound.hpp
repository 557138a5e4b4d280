// A lower bound on the network model's substation energy for every timetable of a problem, so
// that the network optimiser can state a gap. At every instant (bin) b of the load flow, with
// F_b the fleet's traction input at full demand (traction at the wheel over the traction
// efficiency), A_b its auxiliaries, R_b the regeneration offered, S_b the substations' output,
// U_b the regeneration that entered the line, C_b the traction curtailed at the minimum voltage
// and L_b the line losses, the load flow's energy balance is S_b + U_b = F_b - C_b + A_b + L_b
// (power/load_flow.hpp). With L_b >= 0 and U_b <= R_b: S_b + C_b >= F_b + A_b - R_b. When every
// substation has a diode, S_b >= 0 and C_b >= 0 as well, so S_b + C_b >= D_b - min(D_b, R_b)
// with D_b = F_b + A_b: the single-supply-section power balance (power-flow model, zero
// resistance) of the demand D and the regeneration R. Summed over the day, the network uses at
// most what that power balance could use in its best timetable, and the power-flow pair bound
// (pair_bound.hpp) of the profile (D, R) caps that for every timetable of the problem (peak
// classes relaxed to one range covering both), as does, with one headway class, the window
// bound (window_bound.hpp) of the same profile. So for every timetable
//   substation + curtailed traction >= D - min(R, pair bound of (D, R), window bound of (D, R)),
// and with a reversible substation (S_b may be negative) only D - R. Losses, curtailment and
// the distance between trains are not bounded below, which is what keeps the gap open. The
// profile's bins are rounded to micro-joules; the bound takes off one micro-joule per train
// and bin for that.
#pragma once

#include <functional>
#include <string>

#include "energy/model_options.hpp"
#include "power/network_profile.hpp"
#include "power/power_supply.hpp"

namespace ecorail::energy {

struct NetworkBound {
  double substation_J = 0.0;  // lower bound on substation + curtailed traction energy
  double demand_J = 0.0;      // traction input at full demand + auxiliaries (every timetable)
  double regen_J = 0.0;       // regeneration offered (every timetable)
  double reuse_cap_J = 0.0;   // the most regeneration any timetable can put to use
  bool pair_bound = false;    // the pair bound capped the reuse below the total regeneration
  bool window_bound = false;  // the window bound capped it below that (one headway class)
  std::string cut_short;      // how `stop` cut the window bound short (empty: it did not)
};

NetworkBound network_substation_bound(const power::NetworkProfile& profile,
                                      const power::PowerSupply& supply, double traction_efficiency,
                                      const FleetLimits& limits,
                                      const std::function<bool()>& stop = {});

}  // namespace ecorail::energy
