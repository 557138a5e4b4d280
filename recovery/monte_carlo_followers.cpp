#include "recovery/monte_carlo_followers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "recovery/delay_recovery.hpp"
#include "service/separation.hpp"

namespace ecorail::recovery::detail {

namespace {

constexpr double kReachStep_m = 5.0;    // the leader summary's position grid
constexpr std::size_t kNeedBlock = 16;  // trace points per block of the follower summary

long long ms(double t) {
  return std::llround(t * 1000.0);
}

// The candidate runs of `delay` for train k (DelayRecoveryOptions' defaults), each within the
// section's frontier.
std::vector<std::vector<double>> candidates_of(const dp::SectionLibrary& library, const Plan& plan,
                                               std::size_t k, double min_dwell_s,
                                               const SectionRuns& runs, TrainTimes* times_out) {
  DelayRecoveryOptions o;
  o.min_dwell_s = min_dwell_s;
  const TrainTimes times = train_times(library, plan, k, o);
  std::vector<std::vector<double>> grid =
      follower_run_times(times, o.follower_time_step_s, o.follower_slower_s, 0);
  for (std::size_t j = 0; j < grid.size(); ++j)
    for (double& t : grid[j]) t = std::min(t, runs.max_time_s(j));
  if (times_out != nullptr) *times_out = times;
  return grid;
}

// Trains of one pattern (running times and dwells to the millisecond) share its plan.
std::vector<long long> pattern_key(const Plan& plan, std::size_t k) {
  std::vector<long long> key;
  for (std::size_t j = 0; j < plan.sections(); ++j) key.push_back(ms(plan.running_time_s(k, j)));
  for (std::size_t j = 1; j < plan.sections(); ++j) key.push_back(ms(plan.dwell_s(k, j)));
  return key;
}

}  // namespace

std::vector<std::vector<double>> DrivenFollowers::candidate_times(const dp::SectionLibrary& library,
                                                                  const Plan& plan,
                                                                  double min_dwell_s,
                                                                  const SectionRuns& runs) {
  std::vector<std::vector<double>> out(plan.sections());
  std::map<std::vector<long long>, bool> seen;
  for (std::size_t k = 0; k < plan.trains.size(); ++k) {
    if (!seen.emplace(pattern_key(plan, k), true).second) continue;
    const auto grid = candidates_of(library, plan, k, min_dwell_s, runs, nullptr);
    for (std::size_t j = 0; j < grid.size(); ++j)
      out[j].insert(out[j].end(), grid[j].begin(), grid[j].end());
  }
  return out;
}

DrivenFollowers::DrivenFollowers(const dp::SectionLibrary& library, const Plan& plan,
                                 const SectionRuns& runs, double min_dwell_s)
    : library_(library), plan_(plan) {
  // Solved once here and thinned: the full trajectories are dropped with the cache.
  RunCache cache(library, DelayRecoveryOptions().flat_out_threshold_s);
  const std::size_t n = plan.sections();
  station_m_.assign(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    station_m_[k + 1] = station_m_[k] + library.route(k).length_m();
  braking_m_s2_ = service::default_separation_braking_m_s2(library.train());
  room_m_ = separation_.train_length_m + separation_.safety_margin_m;
  // Every run with a trajectory: the planned runs and the candidates (flat out every 2 s to 10 s
  // above the plan, the range a recovery's running times lie in).
  std::vector<std::vector<double>> times(n);
  const std::vector<std::vector<double>> cands = candidate_times(library, plan, min_dwell_s, runs);
  for (std::size_t k = 0; k < n; ++k) {
    std::map<long long, double> at;
    auto add = [&](double t) {
      if (const SectionPiece* p = runs.piece_at(k, t)) at.emplace(ms(p->time_s), p->time_s);
    };
    for (std::size_t tr = 0; tr < plan.trains.size(); ++tr)
      add(std::max(plan.running_time_s(tr, k), runs.min_time_s(k)));
    for (double t : cands[k]) add(t);
    for (const auto& [key, t] : at) times[k].push_back(t);
  }
  cache.prefetch(times);
  runs_.resize(n);
  const double b = braking_m_s2_;
  for (std::size_t k = 0; k < n; ++k)
    for (double t : times[k]) {
      auto r = std::make_unique<DrivenRun>();
      r->section = k;
      r->time_s = t;
      const physics::SimulationResult& full = cache.find(k, t)->sim;
      r->thinned = full;
      r->thinned.trace.clear();
      r->thinned.checkpoints.clear();
      double next_m = 0.0, next_s = 0.0;
      for (std::size_t i = 0; i < full.trace.size(); ++i)
        if (i + 1 == full.trace.size() || full.trace[i].s_m >= next_m ||
            full.trace[i].t_s >= next_s) {
          r->thinned.trace.push_back(full.trace[i]);
          next_m = full.trace[i].s_m + kTraceStep_m;
          next_s = full.trace[i].t_s + kTraceStep_s;
        }
      r->thinned.trace.shrink_to_fit();
      r->sim = &r->thinned;
      const auto& tr = r->sim->trace;
      r->need = service::reach_blocks(*r->sim, b, room_m_, kNeedBlock);
      const double length = library.route(k).length_m();
      std::size_t q = 0;
      for (int i = 0;; ++i) {
        const double x = i * kReachStep_m;
        if (x > length) break;
        while (q < tr.size() && tr[q].s_m < x) ++q;
        if (q >= tr.size()) break;
        r->reach_t_s.push_back(tr[q].t_s);
      }
      by_sim_.emplace(r->sim, r.get());
      runs_[k].push_back(std::move(r));
    }
  // One plan per pattern, its candidate runs.
  std::map<std::vector<long long>, std::size_t> index;
  pattern_of_.assign(plan.trains.size(), 0);
  for (std::size_t tr = 0; tr < plan.trains.size(); ++tr) {
    const auto key = pattern_key(plan, tr);
    const auto it = index.find(key);
    if (it != index.end()) {
      pattern_of_[tr] = it->second;
      continue;
    }
    Pattern p;
    const auto grid = candidates_of(library, plan, tr, min_dwell_s, runs, &p.times);
    std::vector<physics::ControlProgram> programs;
    std::vector<physics::SimulationResult> sims;
    std::vector<double> dwells;
    for (std::size_t k = 0; k < n; ++k) {
      const DrivenRun& planned = at_or_below(k, std::max(plan.running_time_s(tr, k), 0.0));
      p.planned.push_back(&planned);
      programs.push_back(cache.find(k, planned.time_s)->program);
      sims.push_back(*planned.sim);
      if (k + 1 < n) dwells.push_back(plan.dwell_s(tr, k + 1));
      p.candidates.emplace_back();
      for (double t : grid[k]) p.candidates.back().push_back(at_or_below(k, t).sim);
    }
    p.plan = service::plan_from_runs(library, std::move(programs), std::move(sims), dwells);
    index.emplace(key, patterns_.size());
    pattern_of_[tr] = patterns_.size();
    patterns_.push_back(std::move(p));
  }
}

const DrivenRun& DrivenFollowers::at_or_below(std::size_t k, double time_s) const {
  const auto& v = runs_[k];
  auto it =
      std::upper_bound(v.begin(), v.end(), time_s + 1e-6,
                       [](double t, const std::unique_ptr<DrivenRun>& r) { return t < r->time_s; });
  if (it == v.begin()) return *v.front();
  return **std::prev(it);
}

const DrivenRun& DrivenFollowers::at_or_above(std::size_t k, double time_s) const {
  const auto& v = runs_[k];
  auto it =
      std::lower_bound(v.begin(), v.end(), time_s - 1e-6,
                       [](const std::unique_ptr<DrivenRun>& r, double t) { return r->time_s < t; });
  if (it == v.end()) return *v.back();
  return **it;
}

double DrivenFollowers::reach_time_s(const TrainTrack& leader, double x) const {
  const std::size_t m_count = leader.runs.size();
  if (x >= station_m_[m_count]) {  // past its last stop: it has left the line at its arrival
    const DrivenRun& last = *leader.runs.back();
    return leader.departure_s.back() + last.sim->running_time_s;
  }
  x = std::max(0.0, x);
  const auto it =
      std::upper_bound(station_m_.begin(), station_m_.begin() + static_cast<long>(m_count) + 1, x);
  const std::size_t m = static_cast<std::size_t>(it - station_m_.begin()) - 1;
  const DrivenRun& run = *leader.runs[m];
  const auto idx = static_cast<std::size_t>(std::ceil((x - station_m_[m]) / kReachStep_m));
  if (idx >= run.reach_t_s.size()) return leader.departure_s[m] + run.sim->running_time_s;
  return leader.departure_s[m] + run.reach_t_s[idx];
}

bool DrivenFollowers::clear(const TrainTrack& leader, std::size_t k, const DrivenRun& run,
                            double departure_s) const {
  if (leader.runs.empty()) return true;
  bool coarse = true;
  for (std::size_t i = 0; i < run.need.reach_m.size() && coarse; ++i)
    coarse = reach_time_s(leader, station_m_[k] + run.need.reach_m[i]) <=
             departure_s + run.need.early_s[i];
  if (coarse) return true;
  return service::clear_from_s(trip(leader), *run.sim, station_m_[k], braking_m_s2_, room_m_,
                               run.need) <= departure_s + 1e-9;
}

const physics::Trip& DrivenFollowers::trip(const TrainTrack& t) const {
  if (!t.trip.empty()) return t.trip;
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    const double dwell =
        i + 1 < t.runs.size()
            ? std::max(0.0,
                       t.departure_s[i + 1] - (t.departure_s[i] + t.runs[i]->sim->running_time_s))
            : 0.0;
    sections.push_back({&library_.route(i), t.runs[i]->sim, dwell});
  }
  t.trip = physics::Trip(sections, t.departure_s.front(), library_.train().regen_efficiency);
  return t.trip;
}

const DrivenRun* DrivenFollowers::run_of(const Pattern& p, std::size_t k,
                                         const physics::SimulationResult* sim) const {
  if (sim == &p.plan.runs[k]) return p.planned[k];
  const auto it = by_sim_.find(sim);
  if (it == by_sim_.end()) throw std::logic_error("a follower's run outside the driven runs");
  return it->second;
}

std::vector<DrivenStep> DrivenFollowers::path(std::size_t train, const TrainTrack& leader,
                                              std::size_t from, double ready_s) const {
  const Pattern& p = patterns_[pattern_of_[train]];
  const physics::Trip planned = p.plan.trip.shifted(plan_.trains[train].departure_s[0]);
  service::FollowerRecovery recovery;
  recovery.min_dwell_s = p.times.min_dwell_s;
  recovery.blocks = [this, &p](const physics::SimulationResult* sim) {
    for (std::size_t k = 0; k < p.planned.size(); ++k)
      if (sim == &p.plan.runs[k]) return &p.planned[k]->need;
    const auto it = by_sim_.find(sim);
    return it == by_sim_.end() ? nullptr : &it->second->need;
  };
  recovery.runs = [&p](std::size_t first) {
    return std::vector<std::vector<const physics::SimulationResult*>>(
        p.candidates.begin() + static_cast<long>(first), p.candidates.end());
  };
  const std::vector<service::FollowerStep> steps = service::follower_path(
      p.plan, trip(leader), planned, braking_m_s2_, room_m_, recovery, from, from, ready_s);
  std::vector<DrivenStep> out;
  for (std::size_t i = 0; i < steps.size(); ++i)
    out.push_back({run_of(p, from + i, steps[i].run), steps[i].departure_s, steps[i].line_wait_s});
  return out;
}

service::SeparationScan DrivenFollowers::check(const TrainTrack& leader, const TrainTrack& follower,
                                               std::size_t train) const {
  const service::SeparationScan scan =
      service::scan_separation(trip(leader), trip(follower), braking_m_s2_, separation_);
  if (!service::keeps_separation(scan)) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "train %zu comes %.3f m closer than its braking distance to the train ahead "
                  "(least gap %.3f m): the driven followers broke their invariant",
                  train + 1, -scan.min_distance_margin_m, scan.min_gap_m);
    throw std::logic_error(buf);
  }
  return scan;
}

}  // namespace ecorail::recovery::detail
