#include "recovery/delay_recovery.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "dp/lambda_bracket.hpp"
#include "dp/time_target.hpp"
#include "recovery/delay_steps.hpp"

namespace ecorail::recovery {

bool DelayRecoveryOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (!(min_dwell_s >= 0.0 && min_dwell_s < 1e5))
    return fail("the least dwell (--min-dwell) must lie in [0, 1e5) s");
  if (!(on_time_tolerance_s > 0.0 && on_time_tolerance_s <= 1.0))
    return fail("the on-time tolerance must lie in (0, 1] s");
  if (!(flat_out_threshold_s >= 0.0 && flat_out_threshold_s <= 0.5))
    return fail("the flat-out threshold must lie in [0, 0.5] s");
  if (max_followers < 0 || max_followers > 1000)
    return fail("the followers driven at most (--followers) must lie in [0, 1000]");
  if (!(follower_time_step_s >= 0.1 && follower_time_step_s <= 60.0))
    return fail("the followers' running-time step must lie in [0.1, 60] s");
  if (!(follower_slower_s >= 0.0 && follower_slower_s <= 600.0))
    return fail("the followers' slower runs must lie in [0, 600] s above the plan");
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
  std::string out = buf;
  if (recovery_mode == "lateness-first") {
    char lf[300];
    std::snprintf(lf, sizeof lf,
                  "\n  lateness first: total lateness of the late train and its followers %.2f s, "
                  "traction %.1f kJ (energy first: %.2f s, %.1f kJ)",
                  total_lateness_s, recovery_energy_kJ, energy_first_total_lateness_s,
                  energy_first_energy_kJ);
    out += lf;
  }
  return out + "\n";
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

namespace {

// One clear error for a request the plan cannot answer (plan, train, station or delay).
void check_request(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                   std::size_t station, double delay_s, const DelayRecoveryOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (const std::string p = plan.problem(); !p.empty())
    throw DelayInputError("plan", p, options.plan_file);
  const std::size_t n = plan.sections();
  if (library.size() != n)
    throw DelayInputError("plan",
                          "the plan has " + std::to_string(n) + " sections, the line's library " +
                              std::to_string(library.size()),
                          options.plan_file);
  if (train >= plan.trains.size())
    throw DelayInputError("train", "a train from 1 to " + std::to_string(plan.trains.size()) +
                                       "; got " + std::to_string(train + 1));
  if (station >= n)
    throw DelayInputError("station", "a station the train departs from (" + plan.stations.front() +
                                         " to " + plan.stations[n - 1] + "); got " +
                                         plan.stations.at(std::min(station, n)));
  if (!(delay_s >= 0.0) || !std::isfinite(delay_s) || delay_s > kMaxDelay_s) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "a delay in seconds, 0 <= D <= %.0f (a longer one is a disruption, not a "
                  "delay to recover); got %g",
                  kMaxDelay_s, delay_s);
    throw DelayInputError("delay", buf);
  }
}

// What every recovery of one request shares: the request, the late train's times and the
// stretch [station, last) it recovers over (steps 1 and 3 of recover_delay).
struct Request {
  const dp::SectionLibrary& library;
  const Plan& plan;
  std::size_t train, station;
  double delay_s;
  const DelayRecoveryOptions& options;
  dp::FrontierStore* store;
  detail::TrainTimes times;
  double late_departure_s;
  std::size_t back_on_time;  // e: the earliest station back on time; > n: none
  bool recoverable;
  std::size_t last;  // sections [station, last)
  std::vector<double> rule_s;
};

// Steps 4 and 5 for one set of running times: every run solved, re-simulated and laid out on
// the clock, the late train as an affected train, and its followers under the separation cap.
DelayRecoveryResult lay_out_and_follow(const Request& rq, const detail::RecoveryTimes& rt,
                                       const DelayRecoveryOptions& opt, detail::RunCache& cache) {
  const Plan& plan = rq.plan;
  const TrainStops& st = plan.trains[rq.train];
  const std::size_t n = plan.sections(), last = rq.last, count = last - rq.station;
  DelayRecoveryResult out;
  DelayRecoverySummary& sm = out.summary;
  sm.train = static_cast<int>(rq.train);
  sm.station = plan.stations[rq.station];
  sm.delay_s = rq.delay_s;
  out.allocation = rt.allocation;
  for (const std::string& w : rt.warnings) sm.warnings.push_back(w);
  const double arrival = detail::lay_out_runs(rq.library, plan, rq.train, rq.times, rq.station,
                                              last, rq.late_departure_s, rt, rq.rule_s, cache, out);
  sm.sections = static_cast<int>(count);
  sm.recovered = rq.recoverable;
  const double final_late = count > 0 ? arrival - st.arrival_s[last] : 0.0;
  if (rq.recoverable) {
    sm.back_on_time_at = plan.stations[rq.back_on_time];
    sm.final_lateness_s = std::max(0.0, final_late);
    if (final_late > rq.options.on_time_tolerance_s) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "the re-simulated recovery arrives at %s %.3f s after the plan (tolerance "
                    "%.3f s); nothing is reported",
                    sm.back_on_time_at.c_str(), final_late, rq.options.on_time_tolerance_s);
      throw std::runtime_error(buf);
    }
  } else {
    sm.final_lateness_s = final_late;
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "a delay of %.2f s at %s cannot be recovered by %s: every section runs flat "
                  "out and every dwell is at its minimum, and the train arrives %.2f s late",
                  rq.delay_s, sm.station.c_str(), plan.stations.back().c_str(), final_late);
    sm.warnings.push_back(buf);
  }
  AffectedTrain self;
  self.train = static_cast<int>(rq.train);
  self.back_on_time_at = sm.back_on_time_at;
  self.final_lateness_s = sm.final_lateness_s;
  self.max_lateness_s = rq.delay_s;
  self.lateness_s.assign(n + 1, 0.0);
  for (const RecoverySection& s : out.sections)
    self.lateness_s[s.index + 1] = s.new_arrival_s - s.planned_arrival_s;
  out.trains.push_back(self);
  detail::follow_the_late_train(rq.library, plan, rq.train, rq.station, rq.delay_s, rt, opt, cache,
                                out);
  sm.total_lateness_s = 0.0;
  for (const AffectedTrain& a : out.trains)
    for (std::size_t j = 1; j < a.lateness_s.size(); ++j)
      sm.total_lateness_s += std::max(0.0, a.lateness_s[j]);
  return out;
}

// The lateness-first recovery of a train that has sections to recover over. Its lateness at
// each stop before e is least flat out with least dwells (it is late there even so), and it is
// on time at e for any time of the last section up to the rule's, which closes the delay
// exactly: the family below holds every run of least lateness for the late train. The
// followers' least lateness is taken at the flat-out end (the late train then clears every
// stretch earliest); the last section is given the longest time (least energy) that keeps the
// total lateness within kLatenessTie_s of it, by bisection on its time (the rule's time when
// that already does).
DelayRecoveryResult lateness_first(const Request& rq, detail::RunCache& cache) {
  constexpr double kLatenessTie_s = 0.05;
  const std::size_t n = rq.plan.sections(), k = rq.back_on_time - 1;
  auto with_last = [&](double t) {
    detail::RecoveryTimes rt;
    rt.time_s = rq.rule_s;
    rt.marginal_J_per_s.assign(n, std::numeric_limits<double>::infinity());
    for (std::size_t j = rq.station; j < k; ++j) rt.time_s[j] = rq.times.min_s[j];
    rt.time_s[k] = t;
    if (t > rq.times.min_s[k] + rq.options.flat_out_threshold_s)
      rt.marginal_J_per_s[k] = rq.library.frontier(k, rq.store).marginal_at(t);
    return rt;
  };
  const double t_close = rq.rule_s[k];
  const double lo = rq.times.min_s[k], hi = t_close;
  DelayRecoveryResult fastest = lay_out_and_follow(rq, with_last(lo), rq.options, cache);
  DelayRecoveryResult best = lay_out_and_follow(rq, with_last(hi), rq.options, cache);
  const double least = fastest.summary.total_lateness_s;
  int steps = 0;
  if (best.summary.total_lateness_s > least + kLatenessTie_s) {
    best = std::move(fastest);
    // The library's root search on the sign alone (+infinity: within the tie, keep it and go
    // longer), which bisects when an end is infinite: 8 steps at most, to 0.1 s.
    const double inf = std::numeric_limits<double>::infinity();
    dp::LambdaBracket bracket(
        [&](double t) {
          DelayRecoveryResult r = lay_out_and_follow(rq, with_last(t), rq.options, cache);
          if (r.summary.total_lateness_s > least + kLatenessTie_s) return -inf;
          best = std::move(r);
          return inf;
        },
        lo, inf, hi, -inf, 8);
    bracket.narrow([] { return false; }, 0.1);
    steps = bracket.evaluations();
  }
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "lateness first: %s -> %s in %.2f s (flat out %.2f s, the rule %.2f s) after "
                "%d bisection step(s)",
                rq.plan.stations[k].c_str(), rq.plan.stations[k + 1].c_str(),
                best.sections.back().new_time_s, rq.times.min_s[k], t_close, steps);
  best.allocation.message = buf;
  return best;
}

// A follower never on the line with the train ahead has no margin to speak of: infinite.
void margins_of_absent_followers_infinite(DelayRecoveryResult& out) {
  for (FollowerCheck& f : out.followers)
    for (double* v : {&f.planned_run_margin_kmh, &f.plan_margin_kmh, &f.min_speed_margin_kmh,
                      &f.min_distance_margin_m, &f.min_gap_m})
      if (*v >= 1e299) *v = std::numeric_limits<double>::infinity();
  if (out.summary.min_follower_margin_kmh >= 1e299)
    out.summary.min_follower_margin_kmh = std::numeric_limits<double>::infinity();
}

}  // namespace

DelayRecoveryResult recover_delay(const dp::SectionLibrary& library, const Plan& plan,
                                  std::size_t train, std::size_t station, double delay_s,
                                  const DelayRecoveryOptions& options, dp::FrontierStore* store) {
  const auto wall0 = std::chrono::steady_clock::now();
  check_request(library, plan, train, station, delay_s, options);
  const std::size_t n = plan.sections();
  const TrainStops& st = plan.trains[train];
  // Every section's engine is needed (the followers run the whole line): built side by side.
  library.build_engines(0, n);
  const detail::TrainTimes times = detail::train_times(library, plan, train, options);
  const double late_departure_s = st.departure_s[station] + delay_s;

  dp::report_progress(options.progress, "recovery", 0, 1);
  // 1. The earliest station back on time: flat out with minimum dwells, never leaving early.
  const std::size_t e =
      detail::earliest_station_back(st, times, station, late_departure_s, delay_s);
  const bool recoverable = e <= n;
  const std::size_t last = recoverable ? e : n;
  // 2. New running times: exact allocation over the frontiers (or flat out).
  const detail::RecoveryTimes recovery = detail::split_recovery_time(
      library, plan, train, times, station, e, late_departure_s, options, store);
  // 3. The rule: flat out until the delay is gone, the last section in the time that closes it.
  const Request rq{library,
                   plan,
                   train,
                   station,
                   delay_s,
                   options,
                   store,
                   times,
                   late_departure_s,
                   e,
                   recoverable,
                   last,
                   detail::rule_times(st, times, station, last, late_departure_s)};
  detail::RunCache cache(library, options.flat_out_threshold_s);

  // 4 and 5: the energy-first recovery (its followers energy first too); in lateness-first mode
  // it is reported beside the lateness-first one.
  DelayRecoveryOptions energy_first = options;
  energy_first.lateness_first = false;
  DelayRecoveryResult out = lay_out_and_follow(rq, recovery, energy_first, cache);
  out.summary.recovery_mode = options.lateness_first ? "lateness-first" : "energy-first";
  if (options.lateness_first) {
    // With nothing to choose for the late train (flat out throughout, or not late) only its
    // followers go lateness first.
    DelayRecoveryResult lf = rq.recoverable && rq.last > station
                                 ? lateness_first(rq, cache)
                                 : lay_out_and_follow(rq, recovery, options, cache);
    lf.summary.recovery_mode = "lateness-first";
    lf.summary.energy_first_energy_kJ = out.summary.recovery_energy_kJ;
    lf.summary.energy_first_total_lateness_s = out.summary.total_lateness_s;
    out = std::move(lf);
  }
  dp::report_progress(options.progress, "recovery", 1, 1);
  margins_of_absent_followers_infinite(out);
  out.summary.termination = dp::Termination::CONVERGENCE;
  out.summary.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace ecorail::recovery
