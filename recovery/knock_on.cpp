// Step 5 of recover_delay: the trains behind the late train. Each is driven behind the actual
// run of the train ahead by the follower model of service/follower.hpp (it waits at a stop
// rather than leave into an occupied stretch, re-drives only the sections where its planned run
// would come closer than the braking distance, and is checked against that invariant), and the
// next train is driven behind its actual run in turn, until one is not held up. A held-up
// follower is driven back on time (options.recover_followers) by the dynamic programme of
// service/follower.hpp over the energy-optimal runs of each section for running times from
// flat out up to follower_slower_s above the planned time, every follower_time_step_s: back on
// time at the earliest station, then least energy (or, lateness first, least total lateness,
// then least energy), never closer than its braking distance.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>

#include "dp/time_target.hpp"
#include "recovery/delay_steps.hpp"
#include "service/follower.hpp"

namespace ecorail::recovery::detail {

namespace {

physics::Trip trip_of(const dp::SectionLibrary& library,
                      const std::vector<const physics::SimulationResult*>& runs,
                      const std::vector<double>& dwells_s, double departure_s) {
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < runs.size(); ++i)
    sections.push_back({&library.route(i), runs[i], i < dwells_s.size() ? dwells_s[i] : 0.0});
  return physics::Trip(sections, departure_s, library.train().regen_efficiency);
}

std::string two_decimals(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

}  // namespace

void follow_the_late_train(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                           std::size_t station, double delay_s, const RecoveryTimes& recovery,
                           const DelayRecoveryOptions& options, RunCache& cache,
                           DelayRecoveryResult& out) {
  DelayRecoverySummary& sm = out.summary;
  sm.min_follower_margin_kmh = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = plan.sections();
  if (!options.check_followers || options.max_followers <= 0 || train + 1 >= plan.trains.size() ||
      out.sections.empty())
    return;
  const service::SeparationOptions& sep = options.service.separation;
  const double b = sep.braking_m_s2 > 0.0
                       ? sep.braking_m_s2
                       : service::default_separation_braking_m_s2(library.train());
  // A train's planned runs, solved sections side by side.
  auto prefetch_planned = [&](std::size_t k) {
    std::vector<std::vector<double>> times(n);
    for (std::size_t j = 0; j < n; ++j) times[j] = {plan.running_time_s(k, j)};
    cache.prefetch(times);
  };
  auto planned_runs = [&](std::size_t k) {
    prefetch_planned(k);
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
  // The late train's whole run: its plan before the late departure, the recovery, its plan after.
  std::vector<const physics::SimulationResult*> runs = planned_runs(train);
  std::vector<double> dwells = planned_dwells(train);
  const double first_departure = plan.trains[train].departure_s[0];
  double trip_departure = first_departure;
  if (station == 0)
    trip_departure += delay_s;
  else
    dwells[station - 1] += delay_s;
  for (const RecoverySection& s : out.sections) {
    runs[s.index] = &cache.get(s.index, recovery.time_s[s.index]).sim;
    if (s.index + 1 < n) dwells[s.index] = s.new_dwell_s;
  }
  physics::Trip leader = trip_of(library, runs, dwells, trip_departure);
  physics::Trip leader_plan =
      trip_of(library, planned_runs(train), planned_dwells(train), first_departure);
  out.train_trips.push_back(leader);
  bool last_held = false;
  for (std::size_t f = train + 1;
       f < plan.trains.size() && static_cast<int>(f - train) <= options.max_followers; ++f) {
    dp::report_progress(options.progress, "follower", static_cast<int>(f - train - 1),
                        options.max_followers);
    std::vector<physics::ControlProgram> programs;
    std::vector<physics::SimulationResult> sims;
    prefetch_planned(f);
    for (std::size_t j = 0; j < n; ++j) {
      const Run& run = cache.get(j, plan.running_time_s(f, j));
      if (run.flat_out)
        throw std::runtime_error("train " + std::to_string(f + 1) +
                                 " is planned flat out on a section; its control cannot be "
                                 "re-driven behind the late train");
      programs.push_back(run.program);
      sims.push_back(run.sim);
    }
    const service::ServicePlan fplan =
        service::plan_from_runs(library, std::move(programs), std::move(sims), planned_dwells(f));
    const double departure = plan.trains[f].departure_s[0];
    const physics::Trip follower_plan = fplan.trip.shifted(departure);
    const service::SeparationScan base =
        service::scan_separation(leader_plan, follower_plan, b, sep);
    std::vector<service::CapEvent> events;
    const TrainTimes times = train_times(library, plan, f, options);
    service::FollowerRecovery recover;
    recover.min_dwell_s = times.min_dwell_s;
    recover.lateness_first = options.lateness_first;
    // Every candidate run solved up front, sections side by side (kept in the cache for the
    // followers behind).
    recover.runs = [&](std::size_t first) {
      const std::vector<std::vector<double>> grid =
          follower_run_times(times, options.follower_time_step_s, options.follower_slower_s, first);
      cache.prefetch(grid);
      std::vector<std::vector<const physics::SimulationResult*>> runs;
      for (std::size_t k = first; k < n; ++k) {
        runs.emplace_back();
        for (double t : grid[k]) runs.back().push_back(&cache.get(k, t).sim);
      }
      return runs;
    };
    // Or lazily: only those a state the programme keeps would drive (the same path).
    if (options.lazy_follower_solves) {
      recover.run_times = [&](std::size_t first) {
        std::vector<std::vector<double>> grid = follower_run_times(
            times, options.follower_time_step_s, options.follower_slower_s, first);
        grid.erase(grid.begin(), grid.begin() + static_cast<std::ptrdiff_t>(first));
        return grid;
      };
      recover.solve = [&](std::size_t k, const std::vector<double>& times_s) {
        std::vector<std::vector<double>> batch(n);
        batch[k] = times_s;
        cache.prefetch(batch);
        std::vector<const physics::SimulationResult*> runs;
        for (double t : times_s) runs.push_back(&cache.get(k, t).sim);
        return runs;
      };
      recover.held = [&](std::size_t k, double t) -> const physics::SimulationResult* {
        const Run* r = cache.find(k, t);
        return r != nullptr ? &r->sim : nullptr;
      };
      // A run meets its time within the solver's tolerance, or is the flat-out run for a time
      // within the flat-out threshold of it; the cache answers within a millisecond.
      recover.run_time_slack_s =
          std::max(options.flat_out_threshold_s, dp::kTimeTolerance_s) + 0.002;
    }
    service::FollowerRun run = service::drive_follower(
        library, fplan, leader, departure, options.service, b, static_cast<int>(f), &events,
        options.recover_followers ? &recover : nullptr);
    FollowerCheck fc;
    fc.train = static_cast<int>(f);
    fc.behind = static_cast<int>(f - 1);
    fc.planned_run_margin_kmh = run.planned_scan.min_speed_margin_kmh;
    fc.plan_margin_kmh = base.min_speed_margin_kmh;
    fc.affected = run.held_up;
    fc.min_speed_margin_kmh = run.scan.min_speed_margin_kmh;
    fc.min_distance_margin_m = run.scan.min_distance_margin_m;
    fc.min_gap_m = run.scan.min_gap_m;
    fc.station_wait_s = run.station_wait_s;
    fc.headway_s = departure - plan.trains[f - 1].departure_s[0];
    fc.traction_kJ = run.traction_J / 1e3;
    fc.plan_traction_kJ = run.plan_traction_J / 1e3;
    for (std::size_t j = 1; j < run.late_s.size(); ++j)
      fc.lateness_sum_s += std::max(0.0, run.late_s[j]);
    ++sm.followers_checked;
    out.followers.push_back(fc);
    if (!(sm.min_follower_margin_kmh <= fc.min_speed_margin_kmh))
      sm.min_follower_margin_kmh = fc.min_speed_margin_kmh;
    last_held = run.held_up;
    if (!run.held_up) break;  // a train on its plan holds nobody up that the plan does not
    ++sm.followers_affected;
    ++sm.cascade_trains;
    if (fc.station_wait_s > fc.headway_s) sm.plan_absorbs = false;
    AffectedTrain at = lateness_of(static_cast<int>(f), run.trip, plan.trains[f], plan.stations,
                                   std::max(options.on_time_tolerance_s, dp::kTimeTolerance_s));
    if (at.back_on_time_at.empty())
      sm.warnings.push_back("train " + std::to_string(f + 1) +
                            ", held up behind the late train, is not back on time by the last "
                            "station (" +
                            two_decimals(at.final_lateness_s) + " s late)");
    sm.cascade_final_lateness_s = std::max(0.0, at.lateness_s.back());
    out.trains.push_back(at);
    out.train_trips.push_back(run.trip);
    leader_plan = follower_plan;
    leader = run.trip;
  }
  if (last_held) {
    sm.cascade_ends = false;
    sm.warnings.push_back("the knock-on delay goes on beyond the " +
                          std::to_string(sm.followers_checked) +
                          " follower(s) driven: raise --followers to follow it to its end");
  }
  if (!sm.plan_absorbs) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "the plan cannot absorb this delay: %d train(s) held up in a row, a follower "
                  "waits at its stops longer than its headway, the last one %.2f s late at %s",
                  sm.cascade_trains, sm.cascade_final_lateness_s, plan.stations.back().c_str());
    sm.warnings.push_back(buf);
  }
}

}  // namespace ecorail::recovery::detail
