#include "service/service_simulator.hpp"

#include "service/follower.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::service {

namespace {}  // namespace

physics::SimulationResult drive_planned(const dp::SectionEngine& engine,
                                        const physics::ControlProgram& program,
                                        const physics::SimulationResult& planned,
                                        const physics::SpeedCap& cap, double start_clock_s,
                                        double step_m) {
  const auto& trace = planned.trace;
  auto planned_speed = [&trace](double s) {
    const auto it =
        std::lower_bound(trace.begin(), trace.end(), s,
                         [](const physics::TracePoint& p, double x) { return p.s_m < x; });
    if (it == trace.begin()) return it->v_ms;
    if (it == trace.end()) return trace.back().v_ms;
    const auto& a = *(it - 1);
    const auto& b = *it;
    const double w = b.s_m > a.s_m ? (s - a.s_m) / (b.s_m - a.s_m) : 1.0;
    return a.v_ms + w * (b.v_ms - a.v_ms);
  };
  const physics::ControlLaw law = [&](double s, double v) {
    physics::Control c = program.front().control;
    for (const auto& step : program)
      if (step.from_m <= s) c = step.control;
    if ((c == physics::Control::Coast || c == physics::Control::Hold) && v < planned_speed(s) - 0.5)
      return physics::Control::MaxTraction;
    return c;
  };
  std::vector<double> breakpoints;
  for (const auto& step : program) breakpoints.push_back(step.from_m);
  physics::SimulationOptions opt;
  opt.step_m = step_m;
  opt.rk_order = 4;
  opt.speed_cap = cap;
  opt.start_clock_s = start_clock_s;
  return physics::simulate(engine.motion(), law, breakpoints, opt);
}

ServicePlan plan_from_programs(const dp::SectionLibrary& library,
                               std::vector<physics::ControlProgram> programs,
                               std::vector<double> dwells_s) {
  const std::size_t n = library.size();
  if (programs.size() != n || dwells_s.size() + 1 != n)
    throw std::invalid_argument("a service plan needs one program per section, one dwell per stop");
  ServicePlan plan;
  plan.programs = std::move(programs);
  plan.dwells_s = std::move(dwells_s);
  for (std::size_t i = 0; i < n; ++i) {
    plan.runs.push_back(library.engine(i).simulate(plan.programs[i]));
    if (!dp::run_arrives(plan.runs.back()))
      throw std::invalid_argument("section " + std::to_string(i + 1) +
                                  ": the planned program does not arrive at its stop");
  }
  std::vector<double> dwell_after = plan.dwells_s;
  dwell_after.push_back(0.0);
  plan.trip = trip_of(library, plan.runs, dwell_after, 0.0);
  return plan;
}

ServicePlan plan_from_runs(const dp::SectionLibrary& library,
                           std::vector<physics::ControlProgram> programs,
                           std::vector<physics::SimulationResult> runs,
                           std::vector<double> dwells_s) {
  const std::size_t n = library.size();
  if (programs.size() != n || runs.size() != n || dwells_s.size() + 1 != n)
    throw std::invalid_argument("a service plan needs one program per section, one dwell per stop");
  ServicePlan plan;
  plan.programs = std::move(programs);
  plan.runs = std::move(runs);
  plan.dwells_s = std::move(dwells_s);
  std::vector<double> dwell_after = plan.dwells_s;
  dwell_after.push_back(0.0);
  plan.trip = trip_of(library, plan.runs, dwell_after, 0.0);
  return plan;
}

ServicePlan optimal_split_plan(const dp::SectionLibrary& library,
                               const std::vector<double>& dwells_s, double trip_time_s,
                               const dp::JourneyOptions& options) {
  double dwell_sum = 0.0;
  for (double d : dwells_s) dwell_sum += d;
  const dp::JourneySolution sol =
      dp::solve_journey(library, 0, library.size(), dwells_s, trip_time_s - dwell_sum, options);
  if (!sol.converged())
    throw std::runtime_error("the pattern's journey misses a stop or its running time");
  ServicePlan plan;
  plan.dwells_s = dwells_s;
  for (const dp::JourneySection& s : sol.sections) {
    plan.programs.push_back(s.run.program);
    plan.runs.push_back(s.run.sim);
  }
  std::vector<double> dwell_after = dwells_s;
  dwell_after.push_back(0.0);
  plan.trip = trip_of(library, plan.runs, dwell_after, 0.0);
  return plan;
}

bool ServiceOptions::IsValid(std::string* error) const {
  if (!separation.IsValid(error) || !capped.IsValid(error)) return false;
  if (!(resim_step_m > 0.0 && resim_step_m <= 1.0)) {
    if (error) *error = "resim_step_m: expected (0, 1] m";
    return false;
  }
  if (!(redrive_gain_s >= 0.0 && redrive_gain_s <= 3600.0)) {
    if (error) *error = "redrive_gain_s: expected 0 to 3600 s";
    return false;
  }
  return true;
}

std::string ServiceSummary::BriefReport() const {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%d trains, %d re-simulated under the separation cap; minimum margin %.2f km/h "
                "(train %d at %.0f s, %.0f m), %.1f m beyond the braking distance; cap %s; "
                "latest arrival %.2f s after plan",
                trains, trains_resimulated, min_speed_margin_kmh, min_margin_train + 1,
                min_margin_at_s, min_margin_at_m, min_distance_margin_m,
                cap_exceeded ? "EXCEEDED" : "never exceeded", max_late_s);
  return buf;
}

std::string ServiceSummary::FullReport() const {
  return "termination: " + std::string(dp::termination_name(termination)) + "\n" + BriefReport();
}

physics::Trip run_follower(const dp::SectionLibrary& library, const ServicePlan& plan,
                           const physics::Trip& leader, double departure_s,
                           const ServiceOptions& options, double b, int train,
                           std::vector<CapEvent>* events) {
  return drive_follower(library, plan, leader, departure_s, options, b, train, events).trip;
}

ServiceResult simulate_service(const dp::SectionLibrary& library, const ServicePlan& plan,
                               const std::vector<double>& departures_s,
                               const ServiceOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  for (std::size_t k = 1; k < departures_s.size(); ++k)
    if (!(departures_s[k] > departures_s[k - 1]))
      throw std::invalid_argument("departures must be in increasing clock order");
  ServiceResult out;
  out.braking_m_s2 = options.separation.braking_m_s2 > 0.0
                         ? options.separation.braking_m_s2
                         : default_separation_braking_m_s2(library.train());
  const double b = out.braking_m_s2;
  ServiceSummary& sm = out.summary;
  sm.trains = static_cast<int>(departures_s.size());
  out.planned_binding.resize(departures_s.size());
  for (std::size_t k = 0; k < departures_s.size(); ++k) {
    const physics::Trip planned = plan.trip.shifted(departures_s[k]);
    if (k == 0) {
      out.trips.push_back(planned);
      dp::report_progress(options.progress, "service", 1, sm.trains);
      continue;
    }
    const physics::Trip& leader = out.trips[k - 1];
    const SeparationScan before = scan_separation(leader, planned, b, options.separation);
    out.planned_binding[k] = before.binding;
    FollowerRun run = drive_follower(library, plan, leader, departures_s[k], options, b,
                                     static_cast<int>(k), &out.events);
    if (run.held_up) ++sm.trains_resimulated;
    out.trips.push_back(run.trip);
    const SeparationScan& after = run.scan;
    if (after.min_speed_margin_kmh < sm.min_speed_margin_kmh) {
      sm.min_speed_margin_kmh = after.min_speed_margin_kmh;
      sm.min_margin_train = static_cast<int>(k);
      sm.min_margin_at_s = after.at_s;
      sm.min_margin_at_m = after.at_m;
    }
    sm.min_distance_margin_m = std::min(sm.min_distance_margin_m, after.min_distance_margin_m);
    sm.min_gap_m = std::min(sm.min_gap_m, after.min_gap_m);
    sm.cap_exceeded |= after.exceeded;
    const physics::Trip& actual = out.trips.back();
    for (std::size_t i = 1; i <= library.size(); ++i)
      sm.max_late_s = std::max(sm.max_late_s, actual.stop(i).arrival_s - planned.stop(i).arrival_s);
    dp::report_progress(options.progress, "service", static_cast<int>(k) + 1, sm.trains);
  }
  sm.termination = sm.cap_exceeded || sm.min_gap_m < 0.0 ? dp::Termination::FAILURE
                                                         : dp::Termination::CONVERGENCE;
  return out;
}

}  // namespace ecorail::service
