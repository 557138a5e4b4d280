#include "recovery/delay_recovery.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include "dp/time_target.hpp"
#include "fleet/fleet_pattern.hpp"
#include "service/service_simulator.hpp"

namespace ecorail::recovery {

namespace {

// A section's re-simulated run for one running time: the energy-optimal run (library.solve) or,
// at the minimum time, the flat-out run.
struct Run {
  physics::SimulationResult sim;
  physics::ControlProgram program;  // empty for the flat-out run
  bool flat_out = false;
};

class RunCache {
 public:
  RunCache(const dp::SectionLibrary& library, double flat_out_threshold_s)
      : library_(library), threshold_s_(flat_out_threshold_s) {}

  const Run& get(std::size_t k, double time_s) {
    const auto key = std::make_pair(k, std::llround(time_s * 1e6));
    auto it = runs_.find(key);
    if (it != runs_.end()) return *it->second;
    auto run = std::make_unique<Run>();
    if (time_s <= library_.min_time_s(k) + threshold_s_) {
      run->sim = library_.min_time_run(k);
      run->flat_out = true;
    } else {
      const dp::SectionTimeSolve sol = library_.solve(k, time_s);
      const physics::SimulationResult& sim = sol.search.run.sim;
      if (!sol.search.converged || !dp::run_arrives(sim) ||
          std::fabs(sim.running_time_s - time_s) > dp::kTimeTolerance_s) {
        char buf[300];
        std::snprintf(
            buf, sizeof buf,
            "section %zu (%s): no run meets the running time %.3f s (got %.3f s); "
            "nothing is reported",
            k + 1, (library_.route(k).from_name() + " -> " + library_.route(k).to_name()).c_str(),
            time_s, sim.running_time_s);
        throw std::runtime_error(buf);
      }
      run->sim = sim;
      run->program = sol.search.run.program;
    }
    return *runs_.emplace(key, std::move(run)).first->second;
  }

 private:
  const dp::SectionLibrary& library_;
  double threshold_s_;
  std::map<std::pair<std::size_t, long long>, std::unique_ptr<Run>> runs_;
};

double kJ(const physics::SimulationResult& sim) {
  return sim.energy.traction_work_J / 1e3;
}

// Lateness of a trip's arrivals against a train's plan, and where it is back on time: the
// station after its last late arrival (none when it is late at the last station).
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

}  // namespace

bool DelayRecoveryOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (!(min_dwell_s >= 0.0 && min_dwell_s < 1e5))
    return fail("DelayRecoveryOptions::min_dwell_s must lie in [0, 1e5) s");
  if (!(on_time_tolerance_s > 0.0 && on_time_tolerance_s <= 1.0))
    return fail("DelayRecoveryOptions::on_time_tolerance_s must lie in (0, 1] s");
  if (!(flat_out_threshold_s >= 0.0 && flat_out_threshold_s <= 0.5))
    return fail("DelayRecoveryOptions::flat_out_threshold_s must lie in [0, 0.5] s");
  if (max_followers < 0 || max_followers > 1000)
    return fail("DelayRecoveryOptions::max_followers must lie in [0, 1000]");
  if (!allocation.IsValid(error)) return false;
  return service.IsValid(error);
}

std::string DelayRecoverySummary::BriefReport() const {
  char buf[700];
  if (recovered)
    std::snprintf(buf, sizeof buf,
                  "ecorail delay train %d leaves %s %.2f s late: back on time at %s after %d "
                  "section%s; traction %.1f kJ (plan %.1f kJ, rule %.1f kJ: the rule costs %.1f "
                  "kJ more); %d follower%s checked, %d held up; %.2f s wall, %s",
                  train + 1, station.c_str(), delay_s, back_on_time_at.c_str(), sections,
                  sections == 1 ? "" : "s", recovery_energy_kJ, plan_energy_kJ, rule_energy_kJ,
                  rule_energy_kJ - recovery_energy_kJ, followers_checked,
                  followers_checked == 1 ? "" : "s", followers_affected, wall_s,
                  std::string(dp::status_word(termination, warnings.size())).c_str());
  else
    std::snprintf(buf, sizeof buf,
                  "ecorail delay train %d leaves %s %.2f s late: NOT back on time by the last "
                  "station; final lateness %.2f s after %d section%s flat out (traction %.1f kJ, "
                  "plan %.1f kJ); %d follower%s checked, %d held up; %.2f s wall, %s",
                  train + 1, station.c_str(), delay_s, final_lateness_s, sections,
                  sections == 1 ? "" : "s", recovery_energy_kJ, plan_energy_kJ, followers_checked,
                  followers_checked == 1 ? "" : "s", followers_affected, wall_s,
                  std::string(dp::status_word(termination, warnings.size())).c_str());
  return std::string(buf) + "\n";
}

std::string DelayRecoverySummary::FullReport() const {
  std::string out = BriefReport();
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "  train               %d\n  late departure      %s, %.3f s\n"
                "  back on time at     %s\n  final lateness      %.3f s\n"
                "  recovery sections   %d\n  traction: exact     %.1f kJ\n"
                "  traction: plan      %.1f kJ\n  traction: rule      %.1f kJ\n"
                "  followers           %d checked, %d held up, least margin %.2f km/h\n"
                "  termination         %s\n",
                train + 1, station.c_str(), delay_s,
                recovered ? back_on_time_at.c_str() : "(not by the last station)", final_lateness_s,
                sections, recovery_energy_kJ, plan_energy_kJ, rule_energy_kJ, followers_checked,
                followers_affected, min_follower_margin_kmh,
                std::string(dp::termination_name(termination)).c_str());
  out += buf;
  for (const std::string& w : warnings) out += "  warning: " + w + "\n";
  return out;
}

DelayRecoveryResult recover_delay(const dp::SectionLibrary& library, const Plan& plan,
                                  std::size_t train, std::size_t station, double delay_s,
                                  const DelayRecoveryOptions& options, dp::FrontierStore* store) {
  const auto wall0 = std::chrono::steady_clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (const std::string p = plan.problem(); !p.empty()) throw DelayInputError("plan", p);
  const std::size_t n = plan.sections();
  if (library.size() != n)
    throw DelayInputError("plan", "the plan has " + std::to_string(n) +
                                      " sections, the line's library " +
                                      std::to_string(library.size()));
  if (train >= plan.trains.size())
    throw DelayInputError("train", "a train from 1 to " + std::to_string(plan.trains.size()) +
                                       "; got " + std::to_string(train + 1));
  if (station >= n)
    throw DelayInputError("station", "a station the train departs from (" + plan.stations.front() +
                                         " to " + plan.stations[n - 1] + "); got " +
                                         plan.stations.at(std::min(station, n)));
  if (!(delay_s >= 0.0) || !std::isfinite(delay_s) || delay_s > 86400.0)
    throw DelayInputError("delay", "a delay in seconds, 0 <= D <= 86400");
  const TrainStops& st = plan.trains[train];
  // Minimum times, planned running times and dwells; the plan must be drivable.
  std::vector<double> m(n), r(n), dmin(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    m[k] = library.min_time_s(k);
    r[k] = plan.running_time_s(train, k);
    if (r[k] < m[k] - dp::kTimeTolerance_s) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "train %zu's planned running time %s -> %s of %.3f s is below the flat-out "
                    "run of %.3f s",
                    train + 1, plan.stations[k].c_str(), plan.stations[k + 1].c_str(), r[k], m[k]);
      throw DelayInputError("plan", buf);
    }
  }
  for (std::size_t j = 1; j < n; ++j)
    dmin[j] = std::min(plan.dwell_s(train, j), options.min_dwell_s);

  DelayRecoveryResult out;
  DelayRecoverySummary& sm = out.summary;
  sm.train = static_cast<int>(train);
  sm.station = plan.stations[station];
  sm.delay_s = delay_s;
  const double late_departure = st.departure_s[station] + delay_s;

  // 1. The earliest station back on time: flat out with minimum dwells, never leaving early.
  std::size_t e = n + 1;  // none
  {
    double dep = late_departure;
    if (delay_s <= 0.0) e = station;
    for (std::size_t k = station; k < n && e > n; ++k) {
      const double arr = dep + m[k];
      if (arr <= st.arrival_s[k + 1]) e = k + 1;
      if (k + 1 < n) dep = std::max(st.departure_s[k + 1], arr + dmin[k + 1]);
    }
  }
  const bool recoverable = e <= n;
  const std::size_t last = recoverable ? e : n;  // sections [station, last)
  const std::size_t count = last - station;

  // 2. New running times: exact allocation over the frontiers (or flat out).
  std::vector<double> t_new(n, 0.0), marginal(n, 0.0);
  if (recoverable && count > 0) {
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
        sm.warnings.push_back("the train waits at " + plan.stations[e - 1] +
                              " for its timetabled departure (no early departure)");
      }
    }
  } else {
    for (std::size_t k = station; k < last; ++k) {
      t_new[k] = m[k];
      marginal[k] = std::numeric_limits<double>::infinity();
    }
  }

  // 3. The rule: flat out until the delay is gone, the last section in the time that closes it.
  std::vector<double> t_rule(n, 0.0);
  {
    double dep = late_departure;
    for (std::size_t k = station; k < last; ++k) {
      const double late = dep - st.departure_s[k];
      t_rule[k] = late <= r[k] - m[k] ? r[k] - std::max(0.0, late) : m[k];
      const double arr = dep + t_rule[k];
      if (k + 1 < n) dep = std::max(st.departure_s[k + 1], arr + dmin[k + 1]);
    }
  }

  // 4. Solve and re-simulate every run; lay them out on the clock.
  RunCache cache(library, options.flat_out_threshold_s);
  std::vector<physics::TripSection> rec_sections, rule_sections, plan_sections;
  double dep = late_departure, rule_dep = late_departure;
  double arrival = late_departure;
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
  if (count > 0) {
    out.recovery_trip = physics::Trip(rec_sections, late_departure, regen);
    out.rule_trip = physics::Trip(rule_sections, late_departure, regen);
    out.planned_trip = physics::Trip(plan_sections, st.departure_s[station], regen);
  }
  sm.sections = static_cast<int>(count);
  sm.recovered = recoverable;
  const double final_late = count > 0 ? arrival - st.arrival_s[last] : 0.0;
  if (recoverable) {
    sm.back_on_time_at = plan.stations[e];
    sm.final_lateness_s = std::max(0.0, final_late);
    if (final_late > options.on_time_tolerance_s) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "the re-simulated recovery arrives at %s %.3f s after the plan (tolerance "
                    "%.3f s); nothing is reported",
                    sm.back_on_time_at.c_str(), final_late, options.on_time_tolerance_s);
      throw std::runtime_error(buf);
    }
  } else {
    sm.final_lateness_s = final_late;
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "a delay of %.2f s at %s cannot be recovered by %s: every section runs flat out "
                  "and every dwell is at its minimum, and the train arrives %.2f s late",
                  delay_s, sm.station.c_str(), plan.stations.back().c_str(), final_late);
    sm.warnings.push_back(buf);
  }

  // 5. The late train as an affected train, and the followers under the separation cap.
  AffectedTrain self;
  self.train = static_cast<int>(train);
  self.back_on_time_at = sm.back_on_time_at;
  self.final_lateness_s = sm.final_lateness_s;
  self.max_lateness_s = delay_s;
  self.lateness_s.assign(n + 1, 0.0);
  for (const RecoverySection& s : out.sections)
    self.lateness_s[s.index + 1] = s.new_arrival_s - s.planned_arrival_s;
  out.trains.push_back(self);
  sm.min_follower_margin_kmh = std::numeric_limits<double>::quiet_NaN();
  if (options.check_followers && train + 1 < plan.trains.size() && count > 0 &&
      options.max_followers > 0) {
    const service::SeparationOptions& sep = options.service.separation;
    const double b = sep.braking_m_s2 > 0.0
                         ? sep.braking_m_s2
                         : service::default_separation_braking_m_s2(library.train());
    // A train's whole run: planned runs outside [first, end), the given ones inside.
    auto planned_runs = [&](std::size_t k) {
      std::vector<const physics::SimulationResult*> runs;
      for (std::size_t j = 0; j < n; ++j)
        runs.push_back(&cache.get(j, plan.running_time_s(k, j)).sim);
      return runs;
    };
    auto planned_dwells = [&](std::size_t k) {
      std::vector<double> d;
      for (std::size_t j = 1; j < n; ++j) d.push_back(plan.dwell_s(k, j));
      return d;
    };
    std::vector<const physics::SimulationResult*> runs = planned_runs(train);
    std::vector<double> dwells = planned_dwells(train);
    double trip_dep = st.departure_s[0];
    if (station == 0)
      trip_dep = late_departure;
    else
      dwells[station - 1] += delay_s;
    for (const RecoverySection& s : out.sections) {
      runs[s.index] = &cache.get(s.index, t_new[s.index]).sim;
      if (s.index + 1 < n) dwells[s.index] = s.new_dwell_s;
    }
    const physics::Trip leader_planned =
        fleet::trip_from_runs(library, planned_runs(train), planned_dwells(train))
            .shifted(st.departure_s[0]);
    physics::Trip leader = fleet::trip_from_runs(library, runs, dwells).shifted(trip_dep);
    physics::Trip leader_plan = leader_planned;
    for (std::size_t f = train + 1;
         f < plan.trains.size() && static_cast<int>(f - train) <= options.max_followers; ++f) {
      const physics::Trip follower_plan =
          fleet::trip_from_runs(library, planned_runs(f), planned_dwells(f))
              .shifted(plan.trains[f].departure_s[0]);
      const service::SeparationScan scan = service::scan_separation(leader, follower_plan, b, sep);
      const service::SeparationScan base =
          service::scan_separation(leader_plan, follower_plan, b, sep);
      FollowerCheck fc;
      fc.train = static_cast<int>(f);
      fc.behind = static_cast<int>(f - 1);
      fc.planned_run_margin_kmh = scan.min_speed_margin_kmh;
      fc.plan_margin_kmh = base.min_speed_margin_kmh;
      fc.affected = scan.exceeded;
      fc.min_speed_margin_kmh = scan.min_speed_margin_kmh;
      fc.min_distance_margin_m = scan.min_distance_margin_m;
      fc.min_gap_m = scan.min_gap_m;
      ++sm.followers_checked;
      if (!fc.affected) {
        out.followers.push_back(fc);
        if (!(sm.min_follower_margin_kmh <= fc.min_speed_margin_kmh))
          sm.min_follower_margin_kmh = fc.min_speed_margin_kmh;
        break;  // a train on its plan holds nobody up that the plan does not
      }
      ++sm.followers_affected;
      std::vector<physics::ControlProgram> programs;
      for (std::size_t j = 0; j < n; ++j) {
        const Run& run = cache.get(j, plan.running_time_s(f, j));
        if (run.flat_out)
          throw std::runtime_error("train " + std::to_string(f + 1) +
                                   " is planned flat out on a section; its control cannot be "
                                   "re-driven behind the late train");
        programs.push_back(run.program);
      }
      const service::ServicePlan fplan =
          service::plan_from_programs(library, std::move(programs), planned_dwells(f));
      std::vector<service::CapEvent> events;
      const physics::Trip actual =
          service::run_follower(library, fplan, leader, plan.trains[f].departure_s[0],
                                options.service, b, static_cast<int>(f), &events);
      const service::SeparationScan after = service::scan_separation(leader, actual, b, sep);
      fc.min_speed_margin_kmh = after.min_speed_margin_kmh;
      fc.min_distance_margin_m = after.min_distance_margin_m;
      fc.min_gap_m = after.min_gap_m;
      if (after.exceeded)
        sm.warnings.push_back("train " + std::to_string(f + 1) +
                              " exceeds the separation cap behind the late train");
      out.followers.push_back(fc);
      if (!(sm.min_follower_margin_kmh <= fc.min_speed_margin_kmh))
        sm.min_follower_margin_kmh = fc.min_speed_margin_kmh;
      AffectedTrain at = lateness_of(static_cast<int>(f), actual, plan.trains[f], plan.stations,
                                     std::max(options.on_time_tolerance_s, dp::kTimeTolerance_s));
      if (at.back_on_time_at.empty())
        sm.warnings.push_back("train " + std::to_string(f + 1) +
                              ", held up behind the late train, is not back on time by the last "
                              "station");
      out.trains.push_back(at);
      leader_plan = follower_plan;
      leader = actual;
    }
  }
  // A follower never on the line with the train ahead has no margin to speak of: infinite.
  for (FollowerCheck& f : out.followers)
    for (double* v : {&f.planned_run_margin_kmh, &f.plan_margin_kmh, &f.min_speed_margin_kmh,
                      &f.min_distance_margin_m, &f.min_gap_m})
      if (*v >= 1e299) *v = std::numeric_limits<double>::infinity();
  if (sm.min_follower_margin_kmh >= 1e299)
    sm.min_follower_margin_kmh = std::numeric_limits<double>::infinity();
  sm.termination = dp::Termination::CONVERGENCE;
  sm.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace ecorail::recovery
