#include "service/follower.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace ecorail::service {

namespace {

// A held-up follower's wait is rounded up by this much (and then to 0.01 s), so that the
// sampled check is met with room to spare rather than to the last bit.
constexpr double kWaitMargin_s = 0.05;
// A candidate that drives under the cap replaces the wait only when it arrives this much earlier.
constexpr double kEarlierBy_s = 0.05;
// Waits and faster runs tried in turn (each faster run may need a longer wait).
constexpr int kFasterTries = 4;

// The clock time from which the leader is at or beyond position_m for good: when it first
// reaches it, or its arrival when the position lies at or past the end of its run (it then
// leaves the line).
double leader_clear_at(const physics::Trip& leader, double position_m) {
  const double length = leader.length_m();
  if (position_m >= length) return leader.arrival_s();
  return leader.time_at(std::max(0.0, position_m));
}

// The same, searching the leader's samples from *hint (physics::Trip::time_at).
double leader_clear_at(const physics::Trip& leader, double position_m, std::size_t* hint) {
  const double length = leader.length_m();
  if (position_m >= length) return leader.arrival_s();
  return leader.time_at(std::max(0.0, position_m), hint);
}

// The least wait before leaving at start_s for which `run` (a section's run from rest, its own
// clock from 0) keeps gap >= v^2 / 2b behind the leader at every trace point and at the start.
double clearance_wait_s(const physics::Trip& leader, const physics::SimulationResult& run,
                        double section_start_m, double start_s, double b, double room_m) {
  double need = leader_clear_at(leader, section_start_m + room_m) - start_s;
  for (const physics::TracePoint& p : run.trace) {
    const double ahead = section_start_m + p.s_m + room_m + p.v_ms * p.v_ms / (2.0 * b);
    need = std::max(need, leader_clear_at(leader, ahead) - (start_s + p.t_s));
  }
  return std::max(0.0, need);
}

// The least distance margin (gap - v^2 / 2b) of a section run leaving at start_s.
double section_distance_margin_m(const physics::Trip& leader, const physics::SimulationResult& run,
                                 double section_start_m, double start_s, double b, double room_m) {
  const LeaderTrack track(leader);
  double least = 1e300;
  for (const physics::TracePoint& p : run.trace) {
    const double lead = track.position_m(start_s + p.t_s);
    if (!std::isfinite(lead)) break;
    least = std::min(least, lead - room_m - (section_start_m + p.s_m) - p.v_ms * p.v_ms / (2 * b));
  }
  return least;
}

bool arrives(const physics::SimulationResult& sim) {
  return dp::run_arrives(sim) && !sim.stopped_early;
}

}  // namespace

// A held-up follower given a recovery: a dynamic programme over its stops. A state is the time
// it is ready to leave a stop (its planned departure, or its arrival plus the least dwell when
// late), the lateness so far and the energy so far; a move runs one of the section's candidate
// runs, leaving when ready or after the least wait that keeps that run clear of the train ahead
// (exact on the samples, rounded up as every wait is). Being ready earlier is never worse (the
// follower could wait), so a state is dropped when another is ready no later with no more
// lateness and no more energy: the programme is exact over the candidate runs. A state is also
// dropped when a lower bound of its lateness (or, energy first, of its final lateness) already
// exceeds what one pessimistically timed whole path reaches (FollowerRecovery::prune): such a
// state is never chosen, and the states it would lead to are the most numerous. Objective:
// back on time at the earliest station, then the least final lateness (when it cannot be back
// on time by the last stop), then least energy; or, lateness first, the least sum of arrival
// lateness, then least energy.
std::vector<FollowerStep> follower_path(const ServicePlan& plan, const physics::Trip& leader,
                                        const physics::Trip& planned, double b, double room,
                                        const FollowerRecovery& recovery, std::size_t from,
                                        std::size_t first, double ready_s) {
  const std::size_t n = plan.runs.size();
  if (from >= n || first < from) throw std::invalid_argument("follower_path: a stop to leave");
  constexpr double kLate_s = 0.05;  // later than this is late; lateness sums within it are tied
  struct State {
    double ready_s, lateness, energy_J;
    int parent;                            // index in the previous stop's states
    const physics::SimulationResult* run;  // the run that reached it
    double departure_s;                    // of that run
    double line_wait_s;                    // of the wait before it, for the line ahead
  };
  auto rounded_departure = [](double ready, double clear) {
    if (clear <= ready) return ready;
    return ready + std::ceil((clear - ready + kWaitMargin_s) * 100.0) / 100.0;
  };
  const bool lazy = recovery.run_times && recovery.solve;
  std::vector<std::vector<const physics::SimulationResult*>> extra;
  std::vector<std::vector<double>> extra_times;
  if (first < n && lazy)
    extra_times = recovery.run_times(first);
  else if (first < n && recovery.runs)
    extra = recovery.runs(first);
  // Each section's candidates (lazy: nullptr until solved, with their times), when each may
  // leave (clear_from_s), the planned arrival, the next planned departure and the least dwell
  // at its end.
  struct Stage {
    std::vector<const physics::SimulationResult*> cands;
    std::vector<double> time_s, clear_s;
    std::vector<char> solved;  // its run is known (lazy: asked for, or held)
    std::vector<char> live;    // solved, and neither absent nor the planned run again
    double section_start_m = 0.0;
    double planned_arrival_s = 0.0, next_departure_s = 0.0, least_dwell_s = 0.0;
    double min_run_s = 1e300;         // the least running time of the candidates
    double earliest_arrival_s = 0.0;  // least of clear + running time over the candidates
    // Lazy: bounds of an unsolved candidate's clear time plus running time (from the leader
    // clear of the section's start, and of its end, at which every run comes to rest).
    double start_clear_s = 0.0, end_clear_s = 0.0;
  };
  std::vector<Stage> data(n);
  auto clear_of = [&](Stage& d, std::size_t c) {
    const RunReachBlocks* kept = recovery.blocks ? recovery.blocks(d.cands[c]) : nullptr;
    d.clear_s[c] = kept != nullptr
                       ? clear_from_s(leader, *d.cands[c], d.section_start_m, b, room, *kept)
                       : clear_from_s(leader, *d.cands[c], d.section_start_m, b, room);
  };
  auto least_run_s = [&](const Stage& d, std::size_t c) {
    return d.live[c] ? d.cands[c]->running_time_s : d.time_s[c] - recovery.run_time_slack_s;
  };
  auto arrival_bound_s = [&](const Stage& d, std::size_t c) {
    return std::max(d.start_clear_s + least_run_s(d, c), d.end_clear_s);
  };
  // Lazy: solves the candidates `which` of section k; false when a run contradicts a bound.
  bool bounds_hold = true;
  auto solve_lazily = [&](std::size_t k, const std::vector<std::size_t>& which) {
    Stage& d = data[k];
    std::vector<double> times;
    for (std::size_t c : which) times.push_back(d.time_s[c]);
    const std::vector<const physics::SimulationResult*> got = recovery.solve(k, times);
    for (std::size_t i = 0; i < which.size(); ++i) {
      const std::size_t c = which[i];
      const physics::SimulationResult* r = i < got.size() ? got[i] : nullptr;
      const double least = least_run_s(d, c), bound = arrival_bound_s(d, c);
      d.cands[c] = r;
      d.solved[c] = 1;
      if (r == nullptr || r == &plan.runs[k]) continue;
      d.live[c] = 1;
      clear_of(d, c);
      if (r->running_time_s < least - 1e-9 || d.clear_s[c] + r->running_time_s < bound - 1e-9)
        bounds_hold = false;
    }
  };
  for (std::size_t k = from; k < n; ++k) {
    Stage& d = data[k];
    d.cands = {&plan.runs[k]};
    d.time_s = {plan.runs[k].running_time_s};
    if (k >= first && k - first < extra.size())
      for (const physics::SimulationResult* r : extra[k - first])
        if (r != nullptr && r != &plan.runs[k]) d.cands.push_back(r), d.time_s.push_back(0.0);
    if (k >= first && k - first < extra_times.size())
      for (double t : extra_times[k - first]) d.cands.push_back(nullptr), d.time_s.push_back(t);
    d.section_start_m = plan.trip.section_start_m(k);
    d.clear_s.assign(d.cands.size(), 0.0);
    d.live.assign(d.cands.size(), 0);
    d.solved.assign(d.cands.size(), 0);
    for (std::size_t c = 0; c < d.cands.size(); ++c)
      if (d.cands[c] != nullptr) {
        d.solved[c] = d.live[c] = 1;
        clear_of(d, c);
      }
    if (lazy && recovery.held)
      for (std::size_t c = 1; c < d.cands.size(); ++c) {
        const physics::SimulationResult* r = recovery.held(k, d.time_s[c]);
        if (r == nullptr) continue;
        d.cands[c] = r;
        d.solved[c] = 1;
        if (r == &plan.runs[k]) continue;
        d.live[c] = 1;
        clear_of(d, c);
      }
    if (lazy) {
      d.start_clear_s = leader_clear_at(leader, d.section_start_m + room);
      const double end = plan.runs[k].trace.empty() ? 0.0 : plan.runs[k].trace.back().s_m;
      d.end_clear_s = leader_clear_at(leader, d.section_start_m + end - 1.0 + room);
      std::size_t fastest = d.cands.size();
      for (std::size_t c = 1; c < d.cands.size(); ++c)
        if (fastest == d.cands.size() || d.time_s[c] < d.time_s[fastest]) fastest = c;
      if (fastest < d.cands.size() && !d.solved[fastest]) solve_lazily(k, {fastest});
    }
    d.earliest_arrival_s = 1e300;
    for (std::size_t c = 0; c < d.cands.size(); ++c) {
      const bool unsolved = !d.solved[c];
      if (!d.live[c] && !unsolved) continue;
      d.min_run_s = std::min(d.min_run_s, least_run_s(d, c));
      d.earliest_arrival_s =
          std::min(d.earliest_arrival_s,
                   unsolved ? arrival_bound_s(d, c) : d.clear_s[c] + d.cands[c]->running_time_s);
    }
    d.planned_arrival_s = planned.stop(k + 1).arrival_s;
    d.next_departure_s = k + 1 < n ? planned.stop(k + 1).departure_s : 0.0;
    d.least_dwell_s = k + 1 < n ? std::min(plan.dwells_s[k], k + 1 < recovery.min_dwell_s.size()
                                                                 ? recovery.min_dwell_s[k + 1]
                                                                 : plan.dwells_s[k])
                                : 0.0;
  }
  const double last_planned = planned.stop(n).arrival_s;
  // The move of the programme: candidate c of section k from a state ready at `ready`.
  struct Move {
    double departure_s, arrival_s, ready_s, clear_departure_s;
  };
  auto move = [&](std::size_t k, std::size_t c, double ready) {
    const Stage& d = data[k];
    const double rt = d.cands[c]->running_time_s;
    const double clear_dep = rounded_departure(ready, d.clear_s[c]);
    // Never arriving before the timetable: a run that would leaves later (waiting longer at the
    // stop is always clear, the leader's position never decreases).
    const double dep = std::max(clear_dep, d.planned_arrival_s - rt);
    const double arr = dep + rt;
    const double next = k + 1 < n ? std::max(d.next_departure_s, arr + d.least_dwell_s) : arr;
    return Move{dep, arr, next, clear_dep};
  };
  auto add_lateness = [&](std::size_t k, double lateness, double late) {
    if (recovery.lateness_first) return lateness + std::max(0.0, late);
    return late > kLate_s ? static_cast<double>(k + 1) : lateness;  // the last late stop so far
  };
  // Bounds that drop states which cannot be the optimum (FollowerRecovery::prune). A lower bound
  // of what a state at stop k (ready at `ready`, lateness so far) reaches at the last stop: no
  // run leaves before the follower is ready nor before that run is clear, nor arrives before
  // the timetable, so each arrival is at least max(planned, ready + the least running time, the
  // least clear time + running time); lateness only grows.
  struct Bound {
    double lateness, final_late_s;
  };
  auto lower_bound = [&](std::size_t k, double ready, double lateness) {
    for (std::size_t j = k; j < n; ++j) {
      const Stage& d = data[j];
      const double arr = std::max({d.planned_arrival_s, ready + d.min_run_s, d.earliest_arrival_s});
      const double late = arr - d.planned_arrival_s;
      if (recovery.lateness_first)
        lateness += std::max(0.0, late);
      else if (late > kLate_s + 1e-9)
        lateness = static_cast<double>(j + 1);
      ready = j + 1 < n ? std::max(d.next_departure_s, arr + d.least_dwell_s) : arr;
    }
    return Bound{lateness, ready - last_planned};
  };
  // An upper bound: one whole path (at each stop the run that is ready earliest at the next,
  // then the least energy), timed pessimistically: a wait is taken as ending 0.061 s after the
  // clear time, at least the most the rounding of any state's wait adds (under 0.06 s). By
  // induction over the stops, the programme keeps at each stop a state that is ready no later
  // and no more late than this path (a state that dominates its predecessor is ready no later,
  // so it leaves no later on the same run), hence a final state no worse in lateness and time.
  bool bounded = recovery.prune;
  double ub_lateness = 0.0, ub_final_late_s = 0.0;
  if (bounded) {
    double ready = ready_s, lateness = 0.0;
    for (std::size_t k = from; k < n; ++k) {
      const Stage& d = data[k];
      double best_ready = 1e300, best_energy = 1e300, best_late = 0.0;
      for (std::size_t c = 0; c < d.cands.size(); ++c) {
        if (!d.live[c]) continue;
        const double rt = d.cands[c]->running_time_s;
        const double dep = std::max({ready, d.clear_s[c] + 0.061, d.planned_arrival_s - rt});
        const double arr = dep + rt;
        const double next = k + 1 < n ? std::max(d.next_departure_s, arr + d.least_dwell_s) : arr;
        const double e = d.cands[c]->energy.traction_work_J;
        if (next < best_ready || (next == best_ready && e < best_energy)) {
          best_ready = next;
          best_energy = e;
          best_late = arr - d.planned_arrival_s;
        }
      }
      lateness = add_lateness(k, lateness, best_late);
      ready = best_ready;
    }
    ub_lateness = lateness;
    ub_final_late_s = ready - last_planned;
  }
  // Energy first: the least final lateness index is at most the path's; when it is also the
  // least any state can reach, the least final lateness in time is at most the path's too.
  // A state that cannot reach a lateness index below the path's is chosen only when the least
  // index is the path's, and then only within kLate_s of the least final lateness, which is at
  // most the path's: beyond that its final lateness in time rules it out too.
  const Bound from_start = lower_bound(from, ready_s, 0.0);
  const bool time_bound =
      bounded && !recovery.lateness_first && from_start.lateness >= ub_lateness - 0.5;
  auto hopeless = [&](std::size_t k, double ready, double lateness) {
    const Bound lb = lower_bound(k, ready, lateness);
    if (recovery.lateness_first) return lb.lateness > ub_lateness + kLate_s + 1e-6;
    if (lb.lateness > ub_lateness + 0.5) return true;
    const bool no_earlier_index = time_bound || lb.lateness >= ub_lateness - 0.5;
    return no_earlier_index && lb.final_late_s > std::max(ub_final_late_s, 0.0) + kLate_s + 1e-6;
  };
  std::vector<std::vector<State>> stages(n + 1);
  stages[from].push_back({ready_s, 0.0, 0.0, -1, nullptr, ready_s, 0.0});
  for (std::size_t k = from; k < n; ++k) {
    if (lazy) {
      // The unsolved candidates that some state may drive: its move timed as if the run were
      // clear at once and as fast as its time allows (the real move is no earlier and no less
      // late) is not already hopeless.
      const Stage& d = data[k];
      std::vector<std::size_t> wanted;
      for (std::size_t c = 0; c < d.cands.size(); ++c) {
        if (d.solved[c]) continue;
        const double rt = least_run_s(d, c);
        for (const State& s : stages[k]) {
          const double arr = std::max(s.ready_s + rt, d.planned_arrival_s);
          const double next = k + 1 < n ? std::max(d.next_departure_s, arr + d.least_dwell_s) : arr;
          const double lateness = add_lateness(k, s.lateness, arr - d.planned_arrival_s);
          if (!bounded || !hopeless(k + 1, next, lateness)) {
            wanted.push_back(c);
            break;
          }
        }
      }
      if (!wanted.empty()) solve_lazily(k, wanted);
    }
    const Stage& d = data[k];
    std::vector<State> next;
    next.reserve(stages[k].size() * d.cands.size());
    for (std::size_t si = 0; si < stages[k].size(); ++si) {
      const State& s = stages[k][si];
      for (std::size_t c = 0; c < d.cands.size(); ++c) {
        if (!d.live[c]) continue;
        const Move m = move(k, c, s.ready_s);
        const double lateness = add_lateness(k, s.lateness, m.arrival_s - d.planned_arrival_s);
        if (bounded && hopeless(k + 1, m.ready_s, lateness)) continue;
        next.push_back({m.ready_s, lateness, s.energy_J + d.cands[c]->energy.traction_work_J,
                        static_cast<int>(si), d.cands[c], m.departure_s,
                        m.clear_departure_s - s.ready_s});
      }
    }
    // Pareto front over (ready, lateness, energy); the tolerance on lateness ties near-equal
    // sums, on ready the rounding of the waits.
    // Sorted by key (small records; ties in every key by the order made, so the states kept do
    // not depend on the sort's implementation).
    struct Key {
      double ready_s, lateness, energy_J;
      std::size_t index;
    };
    std::vector<Key> keys(next.size());
    for (std::size_t i = 0; i < next.size(); ++i)
      keys[i] = {next[i].ready_s, next[i].lateness, next[i].energy_J, i};
    std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
      if (x.ready_s != y.ready_s) return x.ready_s < y.ready_s;
      if (x.lateness != y.lateness) return x.lateness < y.lateness;
      if (x.energy_J != y.energy_J) return x.energy_J < y.energy_J;
      return x.index < y.index;
    });
    // Every state kept before s is ready no later, so s is dominated when a kept state has no
    // more lateness (within 1e-9) and no more energy (within 1e-6): the least energy of the
    // kept states up to a lateness is a staircase (lateness up, energy down), one look-up.
    std::vector<State> kept;
    std::map<double, double> least_energy;  // lateness -> least energy of kept states up to it
    for (const Key& key : keys) {
      const State& s = next[key.index];
      auto it = least_energy.upper_bound(s.lateness + 1e-9);
      if (it != least_energy.begin() && std::prev(it)->second <= s.energy_J + 1e-6) continue;
      kept.push_back(s);
      it = least_energy.lower_bound(s.lateness);
      while (it != least_energy.end() && it->second >= s.energy_J) it = least_energy.erase(it);
      if (it != least_energy.begin() && std::prev(it)->second <= s.energy_J) continue;
      least_energy[s.lateness] = s.energy_J;
    }
    stages[k + 1] = std::move(kept);
  }
  // The best final state. Lateness first: the least lateness sum (sums within kLate_s tied),
  // then the least energy. Otherwise: back on time at the earliest station, then (when it is
  // late at the last stop whatever it does) the least final lateness, within kLate_s, as the
  // late train runs flat out when no station absorbs its delay, then the least energy.
  if (!bounds_hold) {
    // A solved run broke a bound taken from its time: every candidate solved, and again.
    FollowerRecovery eager = recovery;
    eager.run_times = nullptr;
    eager.solve = nullptr;
    eager.runs = [&](std::size_t f) {
      const std::vector<std::vector<double>> times = recovery.run_times(f);
      std::vector<std::vector<const physics::SimulationResult*>> runs;
      for (std::size_t j = 0; j < times.size(); ++j)
        runs.push_back(recovery.solve(f + j, times[j]));
      return runs;
    };
    return follower_path(plan, leader, planned, b, room, eager, from, first, ready_s);
  }
  const std::vector<State>& final_states = stages[n];
  if (final_states.empty()) {
    // The bounds keep a state no worse than their path at every stop, so this is not expected;
    // should rounding ever drop them all, the plain programme answers.
    if (!bounded) throw std::logic_error("follower_path: no state reaches the last stop");
    FollowerRecovery plain = recovery;
    plain.prune = false;
    return follower_path(plan, leader, planned, b, room, plain, from, first, ready_s);
  }
  double least = 1e300;
  for (const State& s : final_states) least = std::min(least, s.lateness);
  const double tie = recovery.lateness_first ? kLate_s : 0.5;
  double least_final = 1e300;
  for (const State& s : final_states)
    if (s.lateness <= least + tie) least_final = std::min(least_final, s.ready_s - last_planned);
  int best = -1;
  for (std::size_t i = 0; i < final_states.size(); ++i) {
    const State& s = final_states[i];
    if (s.lateness > least + tie) continue;
    if (!recovery.lateness_first && s.ready_s - last_planned > std::max(least_final, 0.0) + kLate_s)
      continue;
    if (best < 0 || s.energy_J < final_states[static_cast<std::size_t>(best)].energy_J)
      best = static_cast<int>(i);
  }
  // Back through the stages: the runs, the waits, the readiness.
  std::vector<FollowerStep> path(n - from);
  for (std::size_t k = n; k > from; --k) {
    const State& s = stages[k][static_cast<std::size_t>(best)];
    const double ready =
        k - 1 == from ? ready_s : stages[k - 1][static_cast<std::size_t>(s.parent)].ready_s;
    path[k - 1 - from] = {s.run, ready, s.departure_s, s.line_wait_s};
    best = s.parent;
  }
  return path;
}

// The clock time from which `run` (a section's run from rest, its own clock from 0) may leave
// and keep gap >= v^2 / 2b behind the leader at every trace point and at the start: the least
// departure, whatever the time the train is ready (the leader's position never decreases).
double clear_from_s(const physics::Trip& leader, const physics::SimulationResult& run,
                    double section_start_m, double b, double room_m) {
  return clear_from_s(leader, run, section_start_m, b, room_m, reach_blocks(run, b, room_m, 32));
}

RunReachBlocks reach_blocks(const physics::SimulationResult& run, double b, double room_m,
                            std::size_t block) {
  RunReachBlocks out;
  out.block = std::max<std::size_t>(block, 1);
  const auto& trace = run.trace;
  for (std::size_t i = 0; i < trace.size(); i += out.block) {
    double far = -1e300, early = 1e300;
    const std::size_t end = std::min(trace.size(), i + out.block);
    for (std::size_t q = i; q < end; ++q) {
      far = std::max(far, trace[q].s_m + room_m + trace[q].v_ms * trace[q].v_ms / (2.0 * b));
      early = std::min(early, trace[q].t_s);
    }
    out.reach_m.push_back(far);
    out.early_s.push_back(early);
  }
  return out;
}

double clear_from_s(const physics::Trip& leader, const physics::SimulationResult& run,
                    double section_start_m, double b, double room_m, const RunReachBlocks& blocks) {
  // The largest of leader_clear_at(ahead) - t over the samples, found block by block: the
  // leader's clear time never falls as the position grows, so a block's farthest need at its
  // earliest time bounds every sample in it, and only blocks whose bound exceeds the largest
  // value found so far are evaluated sample by sample (the same maximum as a full pass). The
  // farthest need is summed in another order than a sample's, so it is taken a micrometre
  // farther: still a bound, and the maximum is the samples' own.
  const auto& trace = run.trace;
  auto ahead_of = [&](const physics::TracePoint& p) {
    return section_start_m + p.s_m + room_m + p.v_ms * p.v_ms / (2.0 * b);
  };
  std::size_t hint = 0;
  double from = leader_clear_at(leader, section_start_m + room_m, &hint);
  // Two levels: groups of kGroup blocks first (their farthest need at their earliest time bounds
  // every block in them), then the blocks of a group whose bound exceeds the largest value so
  // far, then the samples of such a block.
  constexpr std::size_t kGroup = 8;
  struct Bounded {
    double bound;
    std::size_t first;  // block index
  };
  auto by_bound = [](const Bounded& x, const Bounded& y) {
    return x.bound > y.bound || (x.bound == y.bound && x.first < y.first);
  };
  const std::size_t count = blocks.reach_m.size();
  std::vector<Bounded> groups;
  groups.reserve(count / kGroup + 1);
  for (std::size_t g = 0; g < count; g += kGroup) {
    double far = -1e300, early = 1e300;
    for (std::size_t i = g; i < std::min(count, g + kGroup); ++i) {
      far = std::max(far, blocks.reach_m[i]);
      early = std::min(early, blocks.early_s[i]);
    }
    groups.push_back({leader_clear_at(leader, section_start_m + far + 1e-6, &hint) - early, g});
  }
  std::sort(groups.begin(), groups.end(), by_bound);
  std::vector<Bounded> order;
  for (const Bounded& grp : groups) {
    if (grp.bound <= from) break;
    order.clear();
    for (std::size_t i = grp.first; i < std::min(count, grp.first + kGroup); ++i)
      order.push_back({leader_clear_at(leader, section_start_m + blocks.reach_m[i] + 1e-6, &hint) -
                           blocks.early_s[i],
                       i});
    std::sort(order.begin(), order.end(), by_bound);
    for (const Bounded& blk : order) {
      if (blk.bound <= from) break;
      const std::size_t first = blk.first * blocks.block;
      const std::size_t end = std::min(trace.size(), first + blocks.block);
      for (std::size_t q = first; q < end; ++q)
        from = std::max(from, leader_clear_at(leader, ahead_of(trace[q]), &hint) - trace[q].t_s);
    }
  }
  return from;
}

namespace {

void drive_recovering(const dp::SectionLibrary& library, const ServicePlan& plan,
                      const physics::Trip& leader, const physics::Trip& planned, double b,
                      double room, int train, const FollowerRecovery& recovery,
                      std::vector<physics::SimulationResult>& sims,
                      std::vector<double>& dwell_after, double& trip_departure, FollowerRun& out,
                      std::vector<CapEvent>* events) {
  const std::size_t n = library.size();
  // The first section whose planned run, left at its planned departure, must wait: before it
  // the follower runs its plan (it cannot leave earlier, and slower only makes it late).
  std::size_t first = 0;
  for (; first < n; ++first) {
    const double dep = planned.stop(first).departure_s;
    if (clear_from_s(leader, plan.runs[first], plan.trip.section_start_m(first), b, room) >
        dep + 1e-9)
      break;
  }
  const std::vector<FollowerStep> path =
      follower_path(plan, leader, planned, b, room, recovery, 0, first, trip_departure);
  out.late_s.assign(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const FollowerStep& s = path[k];
    const double ready = s.ready_s;
    const double wait = s.line_wait_s;  // for the line ahead (the rest, for the timetable)
    const double planned_arrival = planned.stop(k + 1).arrival_s;
    if (wait > 0.0 || s.run != &plan.runs[k]) {
      ++out.sections_redriven;
      if (events != nullptr) {
        CapEvent ev;
        ev.train = train;
        ev.section = static_cast<int>(k);
        ev.planned_cost_J = library.engine(k).energy_cost_J(plan.runs[k]);
        ev.supervised_cost_J = NAN;
        ev.reoptimised_cost_J = library.engine(k).energy_cost_J(*s.run);
        ev.reoptimised_wait_s = wait;
        ev.station_wait_s = wait;
        ev.waited_late_s = ready + wait + plan.runs[k].running_time_s - planned_arrival;
        ev.driven = s.run == &plan.runs[k] ? "waited"
                    : wait > 0.0           ? "waited, then recovered"
                                           : "recovered";
        ev.late_s = s.departure_s + s.run->running_time_s - planned_arrival;
        ev.reoptimised_late_s = ev.late_s;
        events->push_back(ev);
      }
    }
    out.station_wait_s += wait;
    sims[k] = *s.run;
    const double arrival = s.departure_s + s.run->running_time_s;
    out.late_s[k + 1] = arrival - planned_arrival;
    if (k == 0)
      trip_departure = s.departure_s;
    else
      dwell_after[k - 1] =
          s.departure_s - (path[k - 1].departure_s + path[k - 1].run->running_time_s);
  }
}

}  // namespace

bool keeps_separation(const SeparationScan& scan) {
  return scan.min_distance_margin_m >= -kDistanceMarginTolerance_m &&
         scan.min_gap_m >= -kDistanceMarginTolerance_m;
}

FollowerRun drive_follower(const dp::SectionLibrary& library, const ServicePlan& plan,
                           const physics::Trip& leader, double departure_s,
                           const ServiceOptions& options, double b, int train,
                           std::vector<CapEvent>* events, const FollowerRecovery* recovery) {
  if (!(b > 0.0)) throw std::invalid_argument("the separation braking must be positive");
  const std::size_t n = library.size();
  const double room = options.separation.train_length_m + options.separation.safety_margin_m;
  const physics::Trip planned = plan.trip.shifted(departure_s);
  FollowerRun out;
  out.planned_scan = scan_separation(leader, planned, b, options.separation);
  const SeparationScan& before = out.planned_scan;
  out.held_up = before.exceeded || before.min_distance_margin_m < 0.0 || before.min_gap_m < 0.0;
  for (const physics::SimulationResult& r : plan.runs)
    out.plan_traction_J += r.energy.traction_work_J;
  if (!out.held_up) {
    out.traction_J = out.plan_traction_J;
    out.trip = planned;
    out.scan = before;
    out.late_s.assign(n + 1, 0.0);
    return out;
  }
  std::vector<physics::SimulationResult> sims(n);
  std::vector<double> dwell_after(n, 0.0);
  double trip_departure = departure_s, start = departure_s;
  out.late_s.assign(n + 1, 0.0);
  const bool recovering = recovery != nullptr;
  if (recovering)
    drive_recovering(library, plan, leader, planned, b, room, train, *recovery, sims, dwell_after,
                     trip_departure, out, events);
  for (std::size_t i = 0; !recovering && i < n; ++i) {
    const dp::SectionEngine& engine = library.engine(i);
    const double section_start = plan.trip.section_start_m(i);
    const double planned_arrival = planned.stop(i + 1).arrival_s;
    double wait = clearance_wait_s(leader, plan.runs[i], section_start, start, b, room);
    physics::SimulationResult run = plan.runs[i];
    if (wait > 0.0) {
      wait = std::ceil((wait + kWaitMargin_s) * 100.0) / 100.0;
      CapEvent ev;
      ev.train = train;
      ev.section = static_cast<int>(i);
      const double section_end = section_start + library.route(i).length_m();
      for (const CapStretch& c : before.binding)
        if (c.to_m >= section_start && c.from_m <= section_end) {
          ev.first_binding = c;
          break;
        }
      ev.planned_cost_J = engine.energy_cost_J(plan.runs[i]);
      ev.station_wait_s = wait;
      ev.waited_late_s = start + wait + plan.runs[i].running_time_s - planned_arrival;
      ev.supervised_cost_J = NAN;
      ev.reoptimised_cost_J = NAN;
      // Leaving earlier and driving under the cap is tried only when the wait makes it late.
      const physics::SpeedCap cap = separation_cap(leader, section_start, b, options.separation);
      physics::SimulationResult best;
      double best_wait = wait, best_arrival = start + wait + plan.runs[i].running_time_s;
      bool replaced = false;
      // Lateness first (no credit for arriving early), then energy.
      double best_cost = ev.planned_cost_J;
      const char* best_kind = "waited";
      auto consider = [&](physics::SimulationResult&& sim, double w, const char* kind) {
        if (!arrives(sim)) return;
        const double arrival = start + w + sim.running_time_s;
        const double late = std::max(0.0, arrival - planned_arrival);
        const double best_late = std::max(0.0, best_arrival - planned_arrival);
        const double cost = engine.energy_cost_J(sim);
        if (late > best_late - kEarlierBy_s && !(late <= best_late + 1e-9 && cost < best_cost))
          return;
        if (section_distance_margin_m(leader, sim, section_start, start + w, b, room) <
            -kDistanceMarginTolerance_m)
          return;
        best = std::move(sim);
        best_wait = w;
        best_arrival = arrival;
        best_cost = cost;
        best_kind = kind;
        replaced = true;
      };
      // Wait, then run the section faster than planned for the time left (the section
      // library's energy-optimal run for that time, down to the flat-out run); a faster run may
      // need a longer wait, so the two are iterated a few times.
      if (ev.waited_late_s > kEarlierBy_s) {
        double w = wait;
        for (int it = 0; it < kFasterTries; ++it) {
          const double time_left = planned_arrival - start - w;
          const bool flat_out = time_left <= library.min_time_s(i) + 0.02;
          physics::SimulationResult faster =
              flat_out ? library.min_time_run(i) : library.solve(i, time_left).search.run.sim;
          const double w2 = clearance_wait_s(leader, faster, section_start, start, b, room);
          const double w_round = std::ceil((w2 + kWaitMargin_s) * 100.0) / 100.0;
          consider(std::move(faster), w_round, "waited, then faster");
          if (flat_out || w2 <= w + 1e-9) break;
          w = w_round;
        }
        ev.faster_tried = true;
      }
      // Leaving earlier and driving under the cap, when waiting still makes it late and an
      // earlier arrival is possible at all: no run arrives before the flat-out time, nor before
      // the leader is clear of the stop by the room (a follower at rest there needs gap >= 0).
      const double earliest_arrival =
          std::max(start + library.min_time_s(i), leader_clear_at(leader, section_end + room));
      if (options.mode != FollowerMode::Wait && best_arrival - planned_arrival > kEarlierBy_s &&
          best_arrival - earliest_arrival > std::max(kEarlierBy_s, options.redrive_gain_s)) {
        // The planned control braked by the supervisor, leaving now: reported in both modes
        // (what the cap alone would do), driven in the supervised one.
        physics::SimulationResult sup =
            drive_planned(engine, plan.programs[i], plan.runs[i], cap, start, options.resim_step_m);
        ev.supervised_cost_J = engine.energy_cost_J(sup);
        ev.supervised_late_s = start + sup.running_time_s - planned_arrival;
        if (options.mode == FollowerMode::Supervised) {
          consider(std::move(sup), 0.0, "supervised");
        } else {
          dp::CappedSectionOptions capped = options.capped;
          capped.max_wait_s = std::min(capped.max_wait_s, wait);
          dp::CappedSectionResult r = dp::solve_capped_section(
              engine, cap, start, planned_arrival - start, capped, plan.programs[i]);
          ev.report = r.summary.BriefReport();
          if (r.summary.termination != dp::Termination::FAILURE) {
            ev.reoptimised_cost_J = r.summary.cost_J;
            ev.reoptimised_wait_s = r.wait_s;
            ev.reoptimised_late_s = start + r.wait_s + r.sim.running_time_s - planned_arrival;
            consider(std::move(r.sim), r.wait_s, "reoptimised");
          }
        }
      }
      if (replaced) {
        run = std::move(best);
        wait = best_wait;
      }
      ev.driven = best_kind;
      ev.station_wait_s = wait;
      ev.late_s = best_arrival - planned_arrival;
      if (events) events->push_back(ev);
      ++out.sections_redriven;
      out.station_wait_s += wait;
      if (i == 0)
        trip_departure += wait;
      else
        dwell_after[i - 1] += wait;
      start += wait;
    }
    sims[i] = std::move(run);
    const double arrival = start + sims[i].running_time_s;
    out.late_s[i + 1] = arrival - planned_arrival;
    if (i + 1 < n) {
      const double next = std::max(planned.stop(i + 1).departure_s, arrival + plan.dwells_s[i]);
      dwell_after[i] = next - arrival;
      start = next;
    }
  }
  out.late_s[0] = trip_departure - departure_s;
  for (const physics::SimulationResult& r : sims) out.traction_J += r.energy.traction_work_J;
  out.trip = trip_of(library, sims, dwell_after, trip_departure);
  out.scan = scan_separation(leader, out.trip, b, options.separation);
  if (!keeps_separation(out.scan)) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "train %d comes %.3f m closer than its braking distance to the train ahead "
                  "(least gap %.3f m): the follower model broke its invariant",
                  train + 1, -out.scan.min_distance_margin_m, out.scan.min_gap_m);
    throw std::logic_error(buf);
  }
  return out;
}

physics::Trip trip_of(const dp::SectionLibrary& library,
                      const std::vector<physics::SimulationResult>& runs,
                      const std::vector<double>& dwell_after_s, double departure_s) {
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < runs.size(); ++i)
    sections.push_back({&library.route(i), &runs[i], dwell_after_s[i]});
  return physics::Trip(sections, departure_s, library.train().regen_efficiency);
}

}  // namespace ecorail::service
