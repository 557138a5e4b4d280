#include "energy/network_bound.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "energy/pair_bound.hpp"
#include "energy/window_bound.hpp"

namespace ecorail::energy {

NetworkBound network_substation_bound(const power::NetworkProfile& profile,
                                      const power::PowerSupply& supply, double traction_efficiency,
                                      const FleetLimits& problem,
                                      const std::function<bool()>& stop) {
  if (!(traction_efficiency > 0.0 && traction_efficiency <= 1.0))
    throw std::invalid_argument("traction efficiency must be in (0, 1]");
  NetworkBound out;
  const double step = profile.step_s();
  const double trains = problem.trains;
  // The same loads as NetworkProfile::loads_at gives the load flow, one train's worth.
  std::vector<PowerBin> bins;
  double demand = 0.0, regen = 0.0;
  for (std::int32_t k = 0; k < profile.span_bins(); ++k) {
    const double d_J = (profile.traction_W(k) / traction_efficiency +
                        supply.auxiliary_power_W * profile.presence(k)) *
                       step;
    const double r_J = profile.regen_W(k) * step;
    demand += d_J;
    regen += r_J;
    PowerBin b;
    b.offset = k;
    b.traction = std::llround(d_J * kMicroJoulesPerJoule);
    b.regen = std::llround(r_J * kMicroJoulesPerJoule);
    if (b.traction != 0 || b.regen != 0) bins.push_back(b);
  }
  out.demand_J = demand * trains;
  out.regen_J = regen * trains;
  out.reuse_cap_J = out.regen_J;
  const bool reversible = std::any_of(supply.substations.begin(), supply.substations.end(),
                                      [](const power::Substation& s) { return s.reversible; });
  if (!reversible) {
    const PowerProfile dr =
        PowerProfile::from_bins(profile.ticks_per_second(), profile.span_bins(), std::move(bins));
    // Rounding: each train's bin is within half a micro-joule of its D and R.
    const double slack_J = trains * profile.span_bins() * 1.0 / kMicroJoulesPerJoule;
    const double cap = used_regen_bound(dr, problem).bound_used_J + slack_J;
    if (cap < out.reuse_cap_J) out.reuse_cap_J = cap, out.pair_bound = true;
    // One headway class: the window bound of the same (D, R), far tighter (it values the
    // trains on the line together, not in pairs).
    WindowBoundOptions o;
    o.stop = stop;
    const WindowBound window = window_used_regen_bound(dr, problem, o);
    if (window.stopped) out.cut_short = window_cut_short(window);
    if (window.applicable && window.bound_used_J + slack_J < out.reuse_cap_J) {
      out.reuse_cap_J = window.bound_used_J + slack_J;
      out.window_bound = true;
    }
  }
  out.substation_J = out.demand_J - out.reuse_cap_J;
  return out;
}

}  // namespace ecorail::energy
