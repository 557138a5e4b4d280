#include "fleet/periodic_regimes.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace ecorail::fleet {

int base_periods(const energy::FleetEnergyModel& model, int a_s, int b_s) {
  return static_cast<int>(std::ceil(2.0 * model.trip().arrival_s() / (a_s + b_s))) + 1;
}

namespace {

energy::FleetEvaluation periodic_evaluation(const energy::FleetEnergyModel& model, int a_s, int b_s,
                                            int periods) {
  if (a_s <= 0 || b_s <= 0 || periods < 1)
    throw std::invalid_argument("a periodic timetable needs headways > 0 and a period");
  energy::FleetLimits limits;
  limits.trains = 2 * periods + 1;
  limits.span_s = periods * (a_s + b_s);
  limits.headway_min_s = std::min(a_s, b_s);
  limits.headway_max_s = std::max(a_s, b_s);
  std::vector<int> departures(limits.trains, 0);
  for (int k = 1; k < limits.trains; ++k) departures[k] = departures[k - 1] + (k % 2 ? a_s : b_s);
  const std::unique_ptr<energy::FleetEnergyModel> m =
      model.rebuilt(model.trip(), limits, model.options());
  return m->evaluate(departures);
}

}  // namespace

double periodic_timetable_used_J(const energy::FleetEnergyModel& model, int a_s, int b_s,
                                 int periods) {
  return periodic_evaluation(model, a_s, b_s, periods).total.used_regen_J;
}

double steady_used_per_period_J(const energy::FleetEnergyModel& model, int a_s, int b_s) {
  const int p = base_periods(model, a_s, b_s);
  // The two middle trains of a timetable with a full periodic neighbourhood on both sides
  // (models that attribute the used energy to trains); else two more periods' growth.
  const energy::FleetEvaluation e = periodic_evaluation(model, a_s, b_s, p + 1);
  if (static_cast<int>(e.per_train.size()) == 2 * (p + 1) + 1)
    return e.per_train[p].used_regen_J + e.per_train[p + 1].used_regen_J;
  return 0.5 * (periodic_timetable_used_J(model, a_s, b_s, p + 2) -
                periodic_timetable_used_J(model, a_s, b_s, p));
}

std::vector<PeriodicRegime> analyse_periodic_regimes(const energy::FleetEnergyModel& model,
                                                     const PeriodicRegimeOptions& options) {
  if (options.grid_s < 1 || options.lo_s < 1 || options.hi_s < options.lo_s)
    throw std::invalid_argument("periodic regimes: expected 1 <= lo <= hi and a grid >= 1 s");
  std::vector<int> h;
  const int first = (options.lo_s + options.grid_s - 1) / options.grid_s * options.grid_s;
  for (int v = first; v <= options.hi_s; v += options.grid_s) h.push_back(v);
  if (h.empty()) h.push_back(options.lo_s);
  std::vector<PeriodicRegime> out;
  for (std::size_t i = 0; i < h.size(); ++i)
    for (std::size_t j = i; j < h.size() && h[j] - h[i] <= options.max_spread_s; ++j)
      out.push_back({h[i], h[j], 0.0});
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const int n = static_cast<int>(out.size());
  // Each regime is priced on its own rebuilt models: the order of evaluation does not matter.
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
  for (int r = 0; r < n; ++r) {
    if (options.stop && options.stop()) continue;
    out[r].used_per_period_J = steady_used_per_period_J(model, out[r].a_s, out[r].b_s);
  }
  return out;
}

}  // namespace ecorail::fleet
