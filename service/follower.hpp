// One train behind the actual run of the train ahead, on one track (questions 2.2 and 3): the
// follower model that `timetable --separation`, `delay` and the Monte Carlo share. Section by
// section the follower is ready to leave a stop at its planned departure (or its arrival plus the
// planned dwell, when it is late). It never leaves into an occupied stretch: it waits at the
// stop until its planned run of the section, started then, keeps at every sample a gap to the
// train ahead of at least its braking distance, gap >= v^2 / 2b (equivalently v <= sqrt(2 L b);
// the gap is the leader's position less the train length and safety margin less its own). That
// wait is exact on the samples: the leader's position is non-decreasing, so the sample at
// (t, s, v) needs the leader at s + room + v^2 / 2b, which it first reaches at a known clock
// time; the least wait is the largest of those times less the sample's. Where the wait makes
// the follower late, it may instead leave earlier and drive under the moving cap (re-optimised
// for its planned arrival, dp/capped_section.hpp, or its planned control braked by the
// supervisor), when that run arrives earlier and keeps the same invariant. A follower is
// re-driven only in the sections where its planned run would bind; elsewhere it runs its planned
// section. A follower given a FollowerRecovery is driven back on time instead: a dynamic
// programme over its stops chooses, section by section, one of the candidate runs (faster or
// slower than planned), the least wait at each stop that keeps that run clear of the train
// ahead, and dwells down to the least dwell when late; it is exact over the candidate runs
// (being ready to leave earlier is never worse, so dominated states are dropped, and so are
// states that a lower bound shows can no longer be chosen). The whole run is
// scanned once more against the train ahead and a run that comes closer than the braking distance
// anywhere is an error (std::logic_error), never a result.
#pragma once

#include <functional>
#include <vector>

#include "dp/section_library.hpp"
#include "physics/trip.hpp"
#include "service/separation.hpp"
#include "service/service_simulator.hpp"

namespace ecorail::service {

struct FollowerRun {
  physics::Trip trip;            // the actual run, on the clock
  bool held_up = false;          // its planned run would come closer than the braking distance
  double station_wait_s = 0.0;   // waited at stops for the line ahead to clear, in total
  int sections_redriven = 0;     // sections run other than as planned
  std::vector<double> late_s;    // arrival lateness at each stop (0 at the first: departure)
  double traction_J = 0.0;       // traction work at the wheel of the actual run, re-simulated
  double plan_traction_J = 0.0;  // of its planned run
  SeparationScan planned_scan;   // the planned run against the train ahead
  SeparationScan scan;           // the actual run against the train ahead
};

// A run's trace in blocks (see reach_blocks below).
struct RunReachBlocks {
  std::size_t block = 0;
  std::vector<double> reach_m, early_s;
};

// How a held-up follower is driven back on time: runs(first) gives, for every section from
// `first` (the first one where its planned run must wait) to the last, the runs it may drive
// there besides its planned one (e.g. the energy-optimal runs for a grid of running times;
// one list per section, index 0 for `first`; pointers valid for the whole drive_follower call);
// min_dwell_s[j] is the least dwell at stop j (0 at the ends) when it is late. Objective: back on
// time at the earliest station, then (when no station is reached on time) the least final
// lateness, then the least traction energy; lateness_first: the least sum of arrival lateness,
// then the least energy.
struct FollowerRecovery {
  std::function<std::vector<std::vector<const physics::SimulationResult*>>(std::size_t first)> runs;
  std::vector<double> min_dwell_s;
  bool lateness_first = false;
  // Drop the states that a lower bound shows cannot be the optimum: one whole path, timed
  // pessimistically, bounds the least lateness (and, energy first, the least final lateness)
  // from above, and a state whose best possible lateness (or final lateness) already exceeds
  // it by more than the ties of the objective is never chosen. The same path is chosen as
  // without (false: every Pareto state kept).
  bool prune = true;
  // Lazy candidates, used instead of `runs` when both are set: run_times(first) gives, for every
  // section from `first` on (index 0 for `first`), the running times of its candidate runs, and
  // solve(section, times) their runs (pointers valid for the whole drive_follower call; a run's
  // running time is at least its time less run_time_slack_s). The programme asks solve only for
  // the fastest candidate of each section and then for the candidates that some state which
  // the bounds keep would drive: the same path as with every run solved up front (bounds are
  // taken from the times where a run is not solved; should a solved run contradict its bound,
  // every candidate is solved and the programme runs again).
  std::function<std::vector<std::vector<double>>(std::size_t first)> run_times;
  std::function<std::vector<const physics::SimulationResult*>(std::size_t section,
                                                              const std::vector<double>& times_s)>
      solve;
  double run_time_slack_s = 0.0;
  // Lazy: a run already at hand for a section's time (nullptr: none), taken as solved at no
  // cost (its bounds are then exact from the start); may be empty.
  std::function<const physics::SimulationResult*(std::size_t section, double time_s)> held;
  // The blocks of a candidate run (reach_blocks with the programme's braking and room), when
  // the caller keeps them; may be empty or answer nullptr (then they are made here).
  std::function<const RunReachBlocks*(const physics::SimulationResult*)> blocks;
};

// One section of a held-up follower's path: the run it drives, when it leaves (after any wait
// for the line ahead) and how long it waited for the line ahead before leaving.
struct FollowerStep {
  const physics::SimulationResult* run = nullptr;
  double ready_s = 0.0;  // when it was ready to leave
  double departure_s = 0.0;
  double line_wait_s = 0.0;
};

// The dynamic programme of a held-up follower (the one drive_follower runs with a
// FollowerRecovery) over sections [from, n): the follower is ready to leave stop `from` at
// ready_s; `planned` is its planned run on the clock (plan.trip shifted to its planned first
// departure); candidate runs besides the planned one are asked of recovery.runs(first) for the
// sections from `first` (>= from) on. Returns one step per section of [from, n).
std::vector<FollowerStep> follower_path(const ServicePlan& plan, const physics::Trip& leader,
                                        const physics::Trip& planned, double braking_m_s2,
                                        double room_m, const FollowerRecovery& recovery,
                                        std::size_t from, std::size_t first, double ready_s);

// The clock time from which `run` (a section's run from rest, its own clock from 0, starting at
// section_start_m along the line) may leave and keep gap >= v^2 / 2b (and gap >= 0 at rest at
// its start) behind the leader at every trace point: the least departure, whatever the time
// the train is ready (the leader's position never decreases).
double clear_from_s(const physics::Trip& leader, const physics::SimulationResult& run,
                    double section_start_m, double braking_m_s2, double room_m);

// A run's trace in blocks of `block` consecutive points: per block the farthest position the
// line ahead must be clear to, s + room + v^2 / 2b from the section's start, and the earliest
// time. It depends on the run, the braking and the room only, so a caller that meets the same
// run many times keeps it.
RunReachBlocks reach_blocks(const physics::SimulationResult& run, double braking_m_s2,
                            double room_m, std::size_t block);
// clear_from_s with the run's blocks made beforehand (reach_blocks of the same run, braking and
// room): the same time, bit for bit.
double clear_from_s(const physics::Trip& leader, const physics::SimulationResult& run,
                    double section_start_m, double braking_m_s2, double room_m,
                    const RunReachBlocks& blocks);

// The follower of `plan` planned to leave its first stop at departure_s behind `leader` (a
// whole-line trip on the clock). events (may be null) receives one entry per re-driven section.
FollowerRun drive_follower(const dp::SectionLibrary& library, const ServicePlan& plan,
                           const physics::Trip& leader, double departure_s,
                           const ServiceOptions& options, double braking_m_s2, int train,
                           std::vector<CapEvent>* events,
                           const FollowerRecovery* recovery = nullptr);

// The least distance margin a scan may show and still count as kept: the sampled check meets
// the braking distance to within a centimetre (the wait is rounded up by 0.05 s).
inline constexpr double kDistanceMarginTolerance_m = 0.01;

// True when the scan keeps the invariant: never above the cap, never closer than the braking
// distance (within kDistanceMarginTolerance_m), never a negative gap.
bool keeps_separation(const SeparationScan& scan);

// A train's trip from its section runs on the library's routes, dwell_after_s[i] after run i,
// leaving at departure_s.
physics::Trip trip_of(const dp::SectionLibrary& library,
                      const std::vector<physics::SimulationResult>& runs,
                      const std::vector<double>& dwell_after_s, double departure_s);

}  // namespace ecorail::service
