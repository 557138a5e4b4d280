#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <utility>

#include "dp/time_target.hpp"
#include "recovery/delay_steps.hpp"

namespace ecorail::recovery::detail {

namespace {

double kJ(const physics::SimulationResult& sim) {
  return sim.energy.traction_work_J / 1e3;
}

}  // namespace

const Run* RunCache::find(std::size_t k, double time_s) const {
  // A run already solved within a millisecond of the time is that time's run: plans are read
  // to the millisecond, so trains of one pattern differ by that much, and the solver meets a
  // time only to within dp::kTimeTolerance_s anyway.
  const long long us = std::llround(time_s * 1e6);
  const auto near = runs_.lower_bound({k, us - 1000});
  if (near != runs_.end() && near->first.first == k && near->first.second <= us + 1000)
    return near->second.get();
  return nullptr;
}

std::unique_ptr<Run> RunCache::make(std::size_t k, double time_s) const {
  auto run = std::make_unique<Run>();
  if (time_s <= library_.min_time_s(k) + threshold_s_) {
    run->sim = library_.min_time_run(k);
    run->flat_out = true;
    return run;
  }
  dp::TimeSearchResult search = library_.time_search(k, time_s, &lattice_[k]);
  physics::SimulationResult& sim = search.run.sim;
  if (!search.converged || !dp::run_arrives(sim) ||
      std::fabs(sim.running_time_s - time_s) > dp::kTimeTolerance_s) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "section %zu (%s): no run meets the running time %.3f s (got %.3f s); "
                  "nothing is reported",
                  k + 1,
                  (library_.route(k).from_name() + " -> " + library_.route(k).to_name()).c_str(),
                  time_s, sim.running_time_s);
    throw std::runtime_error(buf);
  }
  run->sim = std::move(sim);
  run->program = std::move(search.run.program);
  return run;
}

const Run& RunCache::get(std::size_t k, double time_s) {
  if (const Run* r = find(k, time_s)) return *r;
  return *runs_.emplace(std::make_pair(k, std::llround(time_s * 1e6)), make(k, time_s))
              .first->second;
}

void RunCache::prefetch(const std::vector<std::vector<double>>& times_s) {
  // Sections side by side (a section's engine is used by one thread at a time); what is made
  // does not depend on the thread count.
  const std::size_t n = times_s.size();
  std::vector<std::vector<std::pair<double, std::unique_ptr<Run>>>> made(n);
  for (std::size_t k = 0; k < n; ++k)
    for (double t : times_s[k])
      if (find(k, t) == nullptr) made[k].push_back({t, nullptr});
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 1)
  for (long kk = 0; kk < static_cast<long>(n); ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    try {
      for (auto& [t, run] : made[k]) run = make(k, t);
    } catch (...) {
#pragma omp critical(run_cache_failure)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  for (std::size_t k = 0; k < n; ++k)
    for (auto& [t, run] : made[k])
      if (find(k, t) == nullptr)
        runs_.emplace(std::make_pair(k, std::llround(t * 1e6)), std::move(run));
}

std::vector<std::vector<double>> follower_run_times(const TrainTimes& times, double step_s,
                                                    double slower_s, std::size_t first) {
  const std::size_t n = times.min_s.size();
  std::vector<std::vector<double>> grid(n);
  for (std::size_t k = first; k < n; ++k) {
    const double top = times.planned_s[k] + slower_s;
    for (int j = 0;; ++j) {
      const double t = times.min_s[k] + j * step_s;
      if (t >= top - 1e-6) break;
      grid[k].push_back(std::round(t * 1000.0) / 1000.0);
    }
    grid[k].push_back(std::round(top * 1000.0) / 1000.0);
  }
  return grid;
}

AffectedTrain lateness_of(int train, const physics::Trip& trip, const TrainStops& plan,
                          const std::vector<std::string>& stations, double tol) {
  AffectedTrain a;
  a.train = train;
  const auto stops = trip.stops();
  int last_late = -1;
  for (std::size_t j = 0; j < stops.size(); ++j) {
    const double late = j == 0 ? stops[0].departure_s - plan.departure_s[0]
                               : stops[j].arrival_s - plan.arrival_s[j];
    a.lateness_s.push_back(late);
    a.max_lateness_s = std::max(a.max_lateness_s, late);
    if (late > tol) last_late = static_cast<int>(j);
  }
  if (last_late < 0) {
    a.never_late = true;
    a.back_on_time_at = stations.front();
    a.final_lateness_s = std::max(0.0, a.lateness_s.front());
  } else if (last_late + 1 < static_cast<int>(stops.size())) {
    a.back_on_time_at = stations[last_late + 1];
    a.final_lateness_s = std::max(0.0, a.lateness_s[last_late + 1]);
  } else {
    a.final_lateness_s = a.lateness_s.back();
  }
  return a;
}

TrainTimes train_times(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                       const DelayRecoveryOptions& options) {
  const std::size_t n = plan.sections();
  TrainTimes tt;
  tt.min_s.assign(n, 0.0);
  tt.planned_s.assign(n, 0.0);
  tt.min_dwell_s.assign(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    tt.min_s[k] = library.min_time_s(k);
    tt.planned_s[k] = plan.running_time_s(train, k);
    if (tt.planned_s[k] < tt.min_s[k] - dp::kTimeTolerance_s) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "train %zu's planned running time %s -> %s of %.3f s is below the flat-out "
                    "run of %.3f s",
                    train + 1, plan.stations[k].c_str(), plan.stations[k + 1].c_str(),
                    tt.planned_s[k], tt.min_s[k]);
      throw DelayInputError("plan", buf, options.plan_file);
    }
  }
  for (std::size_t j = 1; j < n; ++j)
    tt.min_dwell_s[j] = std::min(plan.dwell_s(train, j), options.min_dwell_s);
  return tt;
}

std::size_t earliest_station_back(const TrainStops& st, const TrainTimes& tt, std::size_t station,
                                  double late_departure, double delay_s) {
  const std::size_t n = tt.min_s.size();
  if (delay_s <= 0.0) return station;
  double dep = late_departure;
  for (std::size_t k = station; k < n; ++k) {
    const double arr = dep + tt.min_s[k];
    if (arr <= st.arrival_s[k + 1]) return k + 1;
    if (k + 1 < n) dep = std::max(st.departure_s[k + 1], arr + tt.min_dwell_s[k + 1]);
  }
  return n + 1;
}

RecoveryTimes split_recovery_time(const dp::SectionLibrary& library, const Plan& plan,
                                  std::size_t train, const TrainTimes& tt, std::size_t station,
                                  std::size_t e, double late_departure,
                                  const DelayRecoveryOptions& options, dp::FrontierStore* store) {
  const std::size_t n = plan.sections();
  const TrainStops& st = plan.trains[train];
  const std::vector<double>& m = tt.min_s;
  const std::vector<double>& r = tt.planned_s;
  const std::vector<double>& dmin = tt.min_dwell_s;
  const bool recoverable = e <= n;
  const std::size_t last = recoverable ? e : n;
  const std::size_t count = last - station;
  RecoveryTimes out;
  out.time_s.assign(n, 0.0);
  out.marginal_J_per_s.assign(n, 0.0);
  std::vector<double>& t_new = out.time_s;
  std::vector<double>& marginal = out.marginal_J_per_s;
  if (!recoverable || count == 0) {
    for (std::size_t k = station; k < last; ++k) {
      t_new[k] = m[k];
      marginal[k] = std::numeric_limits<double>::infinity();
    }
    return out;
  }
  double dwell_sum = 0.0;
  for (std::size_t j = station + 1; j < e; ++j) dwell_sum += dmin[j];
  const double total = st.arrival_s[e] - late_departure - dwell_sum;
  auto allocate = [&](std::size_t a, std::size_t b, double time_s) {
    std::vector<AllocationItem> items;
    for (std::size_t k = a; k < b; ++k) {
      const dp::FrontierCurve& c = library.frontier(k, store);
      items.push_back({&c, std::max(m[k], c.t_min_s()), c.t_max_s()});
      items.back().lower_s = std::min(items.back().lower_s, items.back().upper_s);
    }
    AllocationResult ar = allocate_time(items, time_s, options.allocation);
    if (!ar.summary.IsSolutionUsable())
      throw std::runtime_error("the time allocation failed: " + ar.summary.message);
    // A section held at the end of its frontier that could use more time: the frontier is
    // too short for this recovery, and the split would not be the optimum.
    double lower_sum = 0.0;
    for (const AllocationItem& it : items) lower_sum += it.lower_s;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const double could = time_s - (lower_sum - items[i].lower_s);
      if (ar.times_s[i] >= items[i].upper_s - 1e-9 && items[i].upper_s < could - 1e-6) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "a frontier span that covers the recovery: %s -> %s's frontier ends at "
                      "%.2f s (%.2f s above its flat-out run), the recovery could give it up "
                      "to %.2f s; raise the span to at least %.0f s",
                      plan.stations[a + i].c_str(), plan.stations[a + i + 1].c_str(),
                      items[i].upper_s, items[i].upper_s - m[a + i], could,
                      std::ceil(could - m[a + i]) + 1.0);
        throw DelayInputError("frontier-span", buf);
      }
    }
    for (std::size_t k = a; k < b; ++k) {
      t_new[k] = ar.times_s[k - a];
      marginal[k] = ar.marginals_J_per_s[k - a];
    }
    return ar.summary;
  };
  library.build_frontiers(station, e, store);
  out.allocation = allocate(station, e, total);
  // The no-early-departure constraint at the last intermediate stop (the only one that can
  // bind, since the train is still late at every stop before it when run flat out).
  if (count >= 2) {
    double prefix_dwells = 0.0;
    for (std::size_t j = station + 1; j + 1 < e; ++j) prefix_dwells += dmin[j];
    const double p =
        st.departure_s[e - 1] - dmin[e - 1] - late_departure - prefix_dwells;  // least prefix
    double prefix = 0.0;
    for (std::size_t k = station; k + 1 < e; ++k) prefix += t_new[k];
    if (prefix < p - 1e-9) {
      out.allocation = allocate(station, e - 1, p);
      const dp::FrontierCurve& c = library.frontier(e - 1, store);
      if (r[e - 1] > c.t_max_s() + 1e-9)
        throw DelayInputError(
            "frontier-span",
            "a frontier span that covers the planned running time of " + plan.stations[e - 1] +
                " -> " + plan.stations[e] + "; raise the span to at least " +
                std::to_string(static_cast<int>(std::ceil(r[e - 1] - m[e - 1]) + 1)) + " s");
      t_new[e - 1] = std::clamp(r[e - 1], std::max(m[e - 1], c.t_min_s()), c.t_max_s());
      marginal[e - 1] = c.marginal_at(t_new[e - 1]);
      out.warnings.push_back("the train waits at " + plan.stations[e - 1] +
                             " for its timetabled departure (no early departure)");
    }
  }
  return out;
}

std::vector<double> rule_times(const TrainStops& st, const TrainTimes& tt, std::size_t station,
                               std::size_t last, double late_departure) {
  const std::size_t n = tt.min_s.size();
  std::vector<double> t_rule(n, 0.0);
  double dep = late_departure;
  for (std::size_t k = station; k < last; ++k) {
    const double late = dep - st.departure_s[k];
    const double r = tt.planned_s[k], m = tt.min_s[k];
    t_rule[k] = late <= r - m ? r - std::max(0.0, late) : m;
    const double arr = dep + t_rule[k];
    if (k + 1 < n) dep = std::max(st.departure_s[k + 1], arr + tt.min_dwell_s[k + 1]);
  }
  return t_rule;
}

double lay_out_runs(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                    const TrainTimes& tt, std::size_t station, std::size_t last,
                    double late_departure, const RecoveryTimes& recovery,
                    const std::vector<double>& t_rule, RunCache& cache, DelayRecoveryResult& out) {
  const std::size_t n = plan.sections();
  const TrainStops& st = plan.trains[train];
  const std::vector<double>& m = tt.min_s;
  const std::vector<double>& r = tt.planned_s;
  const std::vector<double>& dmin = tt.min_dwell_s;
  const std::vector<double>& t_new = recovery.time_s;
  const std::vector<double>& marginal = recovery.marginal_J_per_s;
  DelayRecoverySummary& sm = out.summary;
  std::vector<physics::TripSection> rec_sections, rule_sections, plan_sections;
  double dep = late_departure, rule_dep = late_departure;
  double arrival = late_departure;
  {
    // The three runs of each section solved first, sections side by side.
    std::vector<std::vector<double>> times(n);
    for (std::size_t k = station; k < last; ++k) times[k] = {r[k], t_new[k], t_rule[k]};
    cache.prefetch(times);
  }
  for (std::size_t k = station; k < last; ++k) {
    RecoverySection s;
    s.index = k;
    s.from = plan.stations[k];
    s.to = plan.stations[k + 1];
    s.min_time_s = m[k];
    const Run& planned = cache.get(k, r[k]);
    const Run& now = cache.get(k, t_new[k]);
    const Run& rule = cache.get(k, t_rule[k]);
    s.planned_time_s = planned.sim.running_time_s;
    s.new_time_s = now.sim.running_time_s;
    s.rule_time_s = rule.sim.running_time_s;
    s.plan_energy_kJ = kJ(planned.sim);
    s.new_energy_kJ = kJ(now.sim);
    s.rule_energy_kJ = kJ(rule.sim);
    s.flat_out = now.flat_out;
    s.marginal_kJ_per_s =
        now.flat_out ? std::numeric_limits<double>::infinity() : marginal[k] / 1e3;
    s.planned_arrival_s = st.arrival_s[k + 1];
    s.new_departure_s = dep;
    arrival = dep + s.new_time_s;
    s.new_arrival_s = arrival;
    s.planned_dwell_s = k + 1 < n ? plan.dwell_s(train, k + 1) : 0.0;
    const double next_dep =
        k + 1 < n ? std::max(st.departure_s[k + 1], arrival + dmin[k + 1]) : arrival;
    s.new_dwell_s = next_dep - arrival;
    const double rule_arr = rule_dep + s.rule_time_s;
    const double rule_next =
        k + 1 < n ? std::max(st.departure_s[k + 1], rule_arr + dmin[k + 1]) : rule_arr;
    const bool last_one = k + 1 == last;
    rec_sections.push_back({&library.route(k), &now.sim, last_one ? 0.0 : s.new_dwell_s});
    rule_sections.push_back({&library.route(k), &rule.sim, last_one ? 0.0 : rule_next - rule_arr});
    plan_sections.push_back({&library.route(k), &planned.sim, last_one ? 0.0 : s.planned_dwell_s});
    dep = next_dep;
    rule_dep = rule_next;
    sm.recovery_energy_kJ += s.new_energy_kJ;
    sm.plan_energy_kJ += s.plan_energy_kJ;
    sm.rule_energy_kJ += s.rule_energy_kJ;
    out.sections.push_back(s);
  }
  const double regen = library.train().regen_efficiency;
  if (last > station) {
    out.recovery_trip = physics::Trip(rec_sections, late_departure, regen);
    out.rule_trip = physics::Trip(rule_sections, late_departure, regen);
    out.planned_trip = physics::Trip(plan_sections, st.departure_s[station], regen);
  }
  return arrival;
}

}  // namespace ecorail::recovery::detail
