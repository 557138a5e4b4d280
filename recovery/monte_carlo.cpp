#include "recovery/monte_carlo.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "fleet/fleet_pattern.hpp"
#include "recovery/monte_carlo_followers.hpp"
#include "service/separation.hpp"

namespace ecorail::recovery {

namespace {
// The day's power grid starts this much before the timetable's 0: a plan run early (or a
// train leaving early) departs before 0, and no bin may fall off the grid.
constexpr double kClockOffset_s = 600.0;
}  // namespace

const char* recovery_policy_name(RecoveryPolicy p) {
  switch (p) {
    case RecoveryPolicy::Exact:
      return "exact";
    case RecoveryPolicy::ExactPunctual:
      return "exact-punctual";
    case RecoveryPolicy::Rule:
      return "rule";
  }
  return "exact";
}

const char* follower_model_name(FollowerModel m) {
  return m == FollowerModel::Shortcut ? "shortcut" : "driven";
}

bool MonteCarloOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (!delays.IsValid(error)) return false;
  if (!(early_s >= 0.0 && early_s <= 600.0)) return fail("--early must lie in [0, 600] s");
  if (!(run_early_s >= 0.0 && run_early_s <= early_s))
    return fail("--run-early must lie in [0, --early] s");
  if (!(min_dwell_s >= 0.0 && min_dwell_s < 1e5)) return fail("--min-dwell must lie in [0, 1e5) s");
  if (!(takeover_s > 0.0 && takeover_s <= 86400.0))
    return fail("--takeover must lie in (0, 86400] s");
  if (!(punctual_s >= 0.0 && punctual_s <= 3600.0))
    return fail("--punctual must lie in [0, 3600] s");
  if (!(on_time_tolerance_s > 0.0 && on_time_tolerance_s <= 1.0))
    return fail("the on-time tolerance must lie in (0, 1] s");
  if (!(separation_s <= 3600.0) || std::isnan(separation_s))
    return fail("--separation must be at most 3600 s (< 0: from the plan)");
  if (!(knot_step_s >= 0.05 && knot_step_s <= 30.0))
    return fail("--knot-step must lie in [0.05, 30] s");
  const double ticks = 1.0 / bin_step_s;
  if (!(bin_step_s >= 0.001 && bin_step_s <= 1.0) || std::fabs(ticks - std::round(ticks)) > 1e-9)
    return fail("--step must divide one second (0.001 to 1 s)");
  return true;
}

std::string MonteCarloSummary::BriefReport() const {
  const MonteCarloStatistics& s = statistics;
  char followers_text[200];
  if (followers == "shortcut")
    std::snprintf(followers_text, sizeof followers_text,
                  "followers in the fast mode (departures at least %.1f s apart, not driven)",
                  separation_s);
  else
    std::snprintf(followers_text, sizeof followers_text,
                  "followers driven under the cap (%.2f held up a day)", s.followers_held_up.mean);
  char buf[1100];
  std::snprintf(buf, sizeof buf,
                "ecorail montecarlo days %llu-%llu: punctuality %.4f +- %.4f, mean lateness %.3f "
                "+- %.3f s, p95 lateness %.2f +- %.2f s, recovery %.1f +- %.1f s, traction %.1f "
                "+- %.1f kJ, substation %.1f +- %.1f kJ (plan %.1f kJ), taken over %.3f a day; "
                "%s; %.2f s wall, %s",
                static_cast<unsigned long long>(first_day),
                static_cast<unsigned long long>(last_day > 0 ? last_day - 1 : 0),
                s.punctuality.mean, s.punctuality.ci95, s.mean_lateness_s.mean,
                s.mean_lateness_s.ci95, s.p95_lateness_s.mean, s.p95_lateness_s.ci95,
                s.recovery_time_s.mean, s.recovery_time_s.ci95, s.traction_kJ.mean,
                s.traction_kJ.ci95, s.substation_kJ.mean, s.substation_kJ.ci95, plan_substation_kJ,
                s.takeovers.mean, followers_text, wall_s,
                std::string(dp::status_word(termination, 0)).c_str());
  return std::string(buf) + "\n";
}

std::string MonteCarloSummary::FullReport() const {
  const MonteCarloStatistics& s = statistics;
  std::string out = BriefReport();
  char buf[1600];
  std::snprintf(
      buf, sizeof buf,
      "  days                 %lld (threads %d)\n  separation           %.1f s\n"
      "  section runs         %zu\n  punctuality          %.5f +- %.5f (pooled %.5f)\n"
      "  mean lateness        %.4f +- %.4f s\n  p95 lateness         %.3f +- %.3f s\n"
      "  recovery time        %.2f +- %.2f s (%lld recoveries)\n"
      "  traction             %.1f +- %.1f kJ (plan %.1f kJ)\n"
      "  substation           %.1f +- %.1f kJ (plan %.1f kJ)\n"
      "  followers            %s, %.2f held up a day, least gap %.2f m\n"
      "  primary delays       %.2f a day (%.2f over 10 s), knock-on %.2f a day\n"
      "  taken over           %.3f a day (%.3f arrivals), not back by the last station %.3f\n"
      "  termination          %s\n",
      static_cast<long long>(s.days), threads, separation_s, section_runs, s.punctuality.mean,
      s.punctuality.ci95, s.pooled_punctuality, s.mean_lateness_s.mean, s.mean_lateness_s.ci95,
      s.p95_lateness_s.mean, s.p95_lateness_s.ci95, s.recovery_time_s.mean, s.recovery_time_s.ci95,
      static_cast<long long>(s.recoveries), s.traction_kJ.mean, s.traction_kJ.ci95,
      plan_traction_kJ, s.substation_kJ.mean, s.substation_kJ.ci95, plan_substation_kJ,
      followers.c_str(), s.followers_held_up.mean, s.min_follower_gap_m, s.primary_delays.mean,
      s.tail_delays.mean, s.knock_on_delays.mean, s.takeovers.mean, s.arrivals_taken_over.mean,
      s.unrecovered_episodes.mean, std::string(dp::termination_name(termination)).c_str());
  return out + buf;
}

double separation_time_s(const dp::SectionLibrary& library, const Plan& plan, SectionRuns& runs) {
  const std::size_t n = plan.sections();
  std::vector<const physics::SimulationResult*> sims;
  std::vector<double> dwells;
  for (std::size_t j = 0; j < n; ++j) {
    sims.push_back(
        &runs.piece_with_sim(j, std::max(plan.running_time_s(0, j), runs.min_time_s(j))).sim);
    if (j + 1 < n) dwells.push_back(plan.dwell_s(0, j + 1));
  }
  const physics::Trip trip = fleet::trip_from_runs(library, sims, dwells);
  const service::SeparationOptions sep;
  const double b = service::default_separation_braking_m_s2(library.train());
  auto exceeded = [&](double h) {
    return service::scan_separation(trip, trip.shifted(h), b, sep).exceeded;
  };
  double lo = 0.0, hi = 900.0;
  if (exceeded(hi)) return hi;
  while (hi - lo > 0.05) {
    const double mid = 0.5 * (lo + hi);
    (exceeded(mid) ? lo : hi) = mid;
  }
  return std::ceil(hi * 10.0 - 1e-9) / 10.0;
}

MonteCarlo::MonteCarlo(const dp::SectionLibrary& library, const Plan& plan,
                       const MonteCarloOptions& options, SectionRuns& runs)
    : library_(library), plan_(plan), options_(options), runs_(runs) {
  for (TrainStops& t : plan_.trains)
    for (std::size_t j = 0; j < t.arrival_s.size(); ++j) {
      t.arrival_s[j] -= options.run_early_s;
      t.departure_s[j] -= options.run_early_s;
    }
  slack_s_ = options.early_s - options.run_early_s;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (const std::string p = plan.problem(); !p.empty()) throw std::invalid_argument(p);
  const std::size_t n = plan.sections();
  if (n == 0 || plan.trains.empty()) throw std::invalid_argument("a plan with trains and sections");
  if (library.size() != n || runs.sections() != n)
    throw std::invalid_argument("the plan has " + std::to_string(n) +
                                " sections, the line's library " + std::to_string(library.size()));
  dmin_.assign(plan.trains.size(), std::vector<double>(n + 1, 0.0));
  for (std::size_t k = 0; k < plan.trains.size(); ++k)
    for (std::size_t j = 1; j < n; ++j)
      dmin_[k][j] = std::min(plan.dwell_s(k, j), options.min_dwell_s);
  std::vector<double> upper(n, 0.0);
  std::vector<std::vector<double>> exact(n);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < plan.trains.size(); ++k) {
      const double r = plan.running_time_s(k, j);
      if (exact[j].empty() || std::fabs(exact[j].back() - r) > 5e-4) exact[j].push_back(r);
      upper[j] = std::max(upper[j], r + options.early_s);  // at most slack_s_ is needed
    }
    std::sort(exact[j].begin(), exact[j].end());
    exact[j].erase(std::unique(exact[j].begin(), exact[j].end(),
                               [](double a, double b) { return std::fabs(a - b) < 5e-4; }),
                   exact[j].end());
  }
  const bool driven = options.followers == FollowerModel::Driven;
  if (driven) {
    const auto cands =
        detail::DrivenFollowers::candidate_times(library, plan_, options.min_dwell_s, runs);
    for (std::size_t j = 0; j < n; ++j)
      exact[j].insert(exact[j].end(), cands[j].begin(), cands[j].end());
  }
  runs.ensure_all(upper, exact);
  if (driven)
    followers_ =
        std::make_unique<detail::DrivenFollowers>(library, plan_, runs, options.min_dwell_s);
  separation_s_ =
      options.separation_s >= 0.0 ? options.separation_s : separation_time_s(library, plan, runs);
  horizon_s_ = 0.0;
  for (const TrainStops& t : plan.trains) horizon_s_ = std::max(horizon_s_, t.arrival_s.back());
  horizon_s_ += 3600.0 + kClockOffset_s;
}

MonteCarlo::~MonteCarlo() = default;

void MonteCarlo::allocate(std::size_t k, std::size_t a, std::size_t b, double start_s, double end_s,
                          std::vector<double>& t) const {
  const TrainStops& st = plan_.trains[k];
  double dwells = 0.0;
  for (std::size_t m = a + 1; m < b; ++m) dwells += dmin_[k][m];
  std::vector<double> lo, hi, part;
  std::vector<std::size_t> sections;
  for (std::size_t j = a; j < b; ++j) {
    sections.push_back(j);
    lo.push_back(runs_.min_time_s(j));
    hi.push_back(std::max(runs_.min_time_s(j), runs_.last_knot_s(j)));
  }
  split_by_price(runs_, sections, lo, hi, end_s - start_s - dwells, part);
  for (std::size_t j = a; j < b; ++j) t[j] = part[j - a];
  if (b - a < 2) return;
  // No arrival so early that the train would leave before its timetabled departure less the
  // early allowance; with punctual caps, no arrival later than the punctuality threshold where a
  // flat-out run from here would be punctual there. Where the split breaks a bound, the most
  // broken stop binds: the train arrives there exactly at the bound, and both sides are split
  // again.
  const bool caps = options_.recovery == RecoveryPolicy::ExactPunctual;
  double arrival = start_s, flat = start_s, worst = 1e-9, bound = 0.0;
  std::size_t at = 0;
  for (std::size_t m = a + 1; m < b; ++m) {
    arrival += t[m - 1];
    flat += runs_.min_time_s(m - 1);
    const double least = st.departure_s[m] - slack_s_ - dmin_[k][m];
    if (least - arrival > worst) {
      worst = least - arrival;
      at = m;
      bound = least;
    }
    const double latest = st.arrival_s[m] + options_.run_early_s + options_.punctual_s;
    if (caps && flat <= latest && arrival - latest > worst) {
      worst = arrival - latest;
      at = m;
      bound = latest;
    }
    arrival += dmin_[k][m];
    flat = std::max(st.departure_s[m] - slack_s_, flat + dmin_[k][m]);
  }
  if (at == 0) return;
  allocate(k, a, at, start_s, bound, t);
  allocate(k, at, b, std::max(bound + dmin_[k][at], st.departure_s[at] - slack_s_), end_s, t);
}

double MonteCarlo::exact_time(std::size_t k, std::size_t j, double departure_s,
                              bool* recoverable) const {
  return exact_target(k, j, departure_s, recoverable, nullptr);
}

double MonteCarlo::exact_target(std::size_t k, std::size_t j, double departure_s, bool* recoverable,
                                std::size_t* target) const {
  const TrainStops& st = plan_.trains[k];
  const std::size_t n = plan_.sections();
  std::size_t e = n + 1;
  double dep = departure_s;
  for (std::size_t m = j; m < n; ++m) {
    const double arr = dep + runs_.min_time_s(m);
    if (arr <= st.arrival_s[m + 1] + 1e-9) {
      e = m + 1;
      break;
    }
    if (m + 1 < n) dep = std::max(st.departure_s[m + 1] - slack_s_, arr + dmin_[k][m + 1]);
  }
  if (recoverable != nullptr) *recoverable = e <= n;
  if (target != nullptr) *target = e;
  if (e > n) return runs_.min_time_s(j);
  std::vector<double> t(n, 0.0);
  allocate(k, j, e, departure_s, st.arrival_s[e], t);
  return t[j];
}

DayRecord MonteCarlo::simulate_day(std::uint64_t day, const std::vector<ForcedDelay>* forced,
                                   std::vector<std::vector<double>>* arrivals_s) const {
  thread_local DayBins bins;
  bins.step_s = runs_.bin_step_s();
  bins.reset(static_cast<std::size_t>(std::ceil(horizon_s_ / bins.step_s)));
  const std::size_t n = plan_.sections(), trains = plan_.trains.size();
  const bool exact = options_.recovery != RecoveryPolicy::Rule;
  const double tol = options_.on_time_tolerance_s;
  const detail::DrivenFollowers* drive = followers_.get();
  DayRecord r;
  r.day = day;
  r.station_arrivals.assign(n + 1, 0);
  r.station_punctual.assign(n + 1, 0);
  r.lateness_histogram.assign(kLatenessHistogramBins, 0);
  std::vector<double> lateness;
  lateness.reserve(trains * n);
  if (arrivals_s != nullptr)
    arrivals_s->assign(trains,
                       std::vector<double>(n + 1, std::numeric_limits<double>::quiet_NaN()));
  // The last train that left each station: its actual and its planned departure (shortcut).
  std::vector<double> last_dep(n, -1e300), last_planned(n, -1e300);
  // Driven: every train's actual run; the train ahead is the last one that ran a section.
  std::vector<detail::TrainTrack> tracks(drive != nullptr ? trains : 0);
  const detail::TrainTrack* ahead = nullptr;
  for (std::size_t k = 0; k < trains; ++k) {
    const TrainStops& st = plan_.trains[k];
    double arrival = st.departure_s[0];
    bool in_recovery = false, episode = false;
    double episode_start = 0.0;
    bool served = true;
    // A held-up train's runs from the stop where it was held up (driven followers), followed
    // while no new delay strikes it.
    std::vector<detail::DrivenStep> path;
    std::size_t path_from = 0;
    bool on_path = false;
    for (std::size_t j = 0; j < n; ++j) {
      const double d = st.departure_s[j];
      const double ready = j == 0 ? d : arrival + dmin_[k][j];
      double dep = std::max(ready, exact && in_recovery ? d - slack_s_ : d);
      // Knock-on, shortcut: no sooner than the separation after the train ahead (or the plan's
      // own headway where that is shorter: the plan was made under the cap).
      if (drive == nullptr && last_dep[j] > -1e299) {
        const double gap = std::min(separation_s_, d - last_planned[j]);
        if (last_dep[j] + gap > dep + 1e-9) {
          dep = last_dep[j] + gap;
          ++r.knock_on_delays;
        }
      }
      DelayDraw delay;
      if (forced != nullptr) {
        for (const ForcedDelay& f : *forced)
          if (f.train == k && f.station == j) {
            delay.delay_s = f.delay_s;
            delay.kind = f.delay_s > options_.delays.small_max_s ? DelayKind::Tail
                         : f.delay_s > 0.0                       ? DelayKind::Small
                                                                 : DelayKind::None;
          }
      } else {
        delay = draw_delay(options_.delays, options_.seed, day, k, j);
      }
      if (delay.delay_s > 0.0) ++r.primary_delays;
      if (delay.kind == DelayKind::Tail) ++r.tail_delays;
      if (delay.delay_s > options_.takeover_s) {
        // Not recovered: the next service takes over; this train runs no further.
        ++r.takeovers;
        r.arrivals_taken_over += static_cast<std::int64_t>(n - j);
        served = false;
        break;
      }
      dep += delay.delay_s;
      if (delay.delay_s > 0.0) on_path = false;  // a new delay: the policy decides again
      const double planned = plan_.running_time_s(k, j);
      double t = planned;
      double run_time = 0.0;  // the run's own time (driven followers), 0: t
      const detail::DrivenRun* leads = nullptr;
      if (on_path) {
        const detail::DrivenStep& step = path[j - path_from];
        dep = step.departure_s;
        if (step.line_wait_s > 0.0) ++r.knock_on_delays;
        t = step.run->time_s;
        run_time = step.run->sim->running_time_s;
        leads = step.run;
      } else {
        const double late = dep - d;
        if (late > 1e-9 || in_recovery) {
          if (exact) {
            bool recoverable = false;
            std::size_t target = n + 1;
            t = exact_target(k, j, dep, &recoverable, &target);
            in_recovery = !recoverable || target > j + 1;
          } else {
            const double m = runs_.min_time_s(j);
            t = late <= planned - m ? planned - std::max(0.0, late) : m;
          }
        }
        t = std::clamp(t, runs_.min_time_s(j), std::max(runs_.min_time_s(j), runs_.last_knot_s(j)));
        if (drive != nullptr) {
          leads = &drive->at_or_above(j, t);
          if (ahead != nullptr && !drive->clear(*ahead, j, drive->at_or_below(j, t), dep)) {
            // Held up: it waits at the stop for the line ahead and is driven back on time.
            path = drive->path(k, *ahead, j, dep);
            path_from = j;
            on_path = true;
            in_recovery = true;
            tracks[k].held_up = true;
            const detail::DrivenStep& step = path.front();
            dep = step.departure_s;
            if (step.line_wait_s > 0.0) ++r.knock_on_delays;
            t = step.run->time_s;
            run_time = step.run->sim->running_time_s;
            leads = step.run;
          }
        }
      }
      last_dep[j] = dep;
      last_planned[j] = d;
      if (drive != nullptr) {
        tracks[k].departure_s.push_back(dep);
        tracks[k].runs.push_back(leads);
      }
      const double late = dep - d;
      if (!episode && late > tol) {
        episode = true;
        episode_start = dep;
      }
      runs_.lay(j, t, dep + kClockOffset_s, bins);
      arrival = dep + (run_time > 0.0 ? run_time : t);
      if (arrivals_s != nullptr) (*arrivals_s)[k][j + 1] = arrival;
      const double arr_late = arrival - st.arrival_s[j + 1];  // against the operating plan
      const double late_published = arr_late - options_.run_early_s;
      const double lat = std::max(0.0, late_published);
      ++r.arrivals;
      ++r.station_arrivals[j + 1];
      if (late_published <= options_.punctual_s + 1e-9) {
        ++r.punctual;
        ++r.station_punctual[j + 1];
      }
      r.lateness_sum_s += lat;
      r.max_lateness_s = std::max(r.max_lateness_s, lat);
      ++r.lateness_histogram[std::min<std::size_t>(kLatenessHistogramBins - 1,
                                                   static_cast<std::size_t>(lat))];
      lateness.push_back(lat);
      if (episode && arr_late <= tol) {
        ++r.recoveries;
        r.recovery_time_sum_s += arrival - episode_start;
        episode = false;
      }
    }
    if (served && episode) ++r.unrecovered_episodes;
    if (drive != nullptr) {
      detail::TrainTrack& me = tracks[k];
      if (me.held_up) {
        // The invariant, on the whole re-simulated run behind the train ahead.
        const service::SeparationScan scan = drive->check(*ahead, me, k);
        ++r.followers_held_up;
        r.min_follower_gap_m = std::min(r.min_follower_gap_m, scan.min_gap_m);
        r.min_follower_margin_m = std::min(r.min_follower_margin_m, scan.min_distance_margin_m);
      }
      if (!me.runs.empty()) {
        if (ahead != nullptr) ahead->trip = physics::Trip();  // no longer needed
        ahead = &me;
      }
    }
  }
  if (!lateness.empty()) {
    const std::size_t rank = (95 * lateness.size() + 99) / 100;  // nearest rank, 1-based
    std::nth_element(lateness.begin(), lateness.begin() + static_cast<long>(rank - 1),
                     lateness.end());
    r.p95_lateness_s = lateness[rank - 1];
  }
  const std::int64_t traction = bins.traction_uJ(), regen = bins.regen_uJ(), used = bins.used_uJ();
  r.traction_kJ = static_cast<double>(traction) / 1e9;
  r.regen_kJ = static_cast<double>(regen) / 1e9;
  r.used_regen_kJ = static_cast<double>(used) / 1e9;
  r.substation_kJ = static_cast<double>(traction - used) / 1e9;
  return r;
}

DayRecord MonteCarlo::plan_day() const {
  const std::vector<ForcedDelay> none;
  return simulate_day(0, &none);
}

std::vector<DayRecord> MonteCarlo::run_days(std::uint64_t first, std::uint64_t last, int threads,
                                            const std::function<void(int, int)>& progress) const {
  if (last < first) throw std::invalid_argument("run_days: last day before the first");
  const long count = static_cast<long>(last - first);
  std::vector<DayRecord> out(static_cast<std::size_t>(count));
  const int nt = threads > 0 ? threads : omp_get_max_threads();
  std::atomic<int> done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
  for (long i = 0; i < count; ++i) {
    try {
      out[static_cast<std::size_t>(i)] = simulate_day(first + static_cast<std::uint64_t>(i));
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
    const int d = ++done;
    if (progress && omp_get_thread_num() == 0) progress(d, static_cast<int>(count));
  }
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace ecorail::recovery
