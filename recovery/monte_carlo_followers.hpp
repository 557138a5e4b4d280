// The driven followers of the Monte Carlo days (question 3.2): what a simulated day needs to run
// each train behind the actual run of the train ahead by the follower model of
// service/follower.hpp, the model `ecorail delay` drives (recovery/knock_on.cpp). Made once per
// plan before the days, then only read (safe from many threads):
//  - the section runs with a re-simulated trajectory (detail::RunCache, the section library's
//    energy-optimal run for that time): the planned runs and the runs a held-up follower
//    chooses from in `delay` (detail::follower_run_times: flat out, every 2 s, to 10 s above
//    the plan). A train not held up runs the time its recovery policy asks for, priced as the
//    blend of the two knots around it (recovery/section_runs.hpp); for the separation its run
//    is the next faster of those runs when it follows (it reaches every point sooner) and the
//    next slower when it leads (it clears every point later): both on the safe side where the
//    runs of a section are ordered by running time, equal at a planned run;
//  - per run, a conservative summary on a coarse grid: where the line ahead must be clear by
//    when (as a follower) and by when it has passed each position (as a leader). A follower's
//    run that the summary clears is clear on every sample; otherwise the exact test of
//    service::clear_from_s decides, on the leader's whole trip made then.
// A held-up follower (its run, left when it is ready, would come closer than the braking
// distance) is driven by service::follower_path from that stop: back on time at the earliest
// station, then least energy, waiting at a stop rather than leaving into an occupied stretch,
// over the planned run and the candidate runs of `delay`. Internal to recovery/.
#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

#include "dp/section_library.hpp"
#include "physics/trip.hpp"
#include "recovery/delay_steps.hpp"
#include "recovery/plan.hpp"
#include "recovery/section_runs.hpp"
#include "service/follower.hpp"

namespace ecorail::recovery::detail {

struct DrivenRun {
  std::size_t section = 0;
  double time_s = 0.0;  // the piece's running time: what the day's clock and power bins use
  // The re-simulated run, its trajectory thinned (DrivenFollowers::kTraceStep_m, _s: the
  // separation is checked on these samples; time, energy and the run's end are its own).
  physics::SimulationResult thinned;
  const physics::SimulationResult* sim = &thinned;
  // As a follower leaving at d: the line ahead must be clear to section start + need.reach_m[i]
  // by d + need.early_s[i] (each a block of trace points: the farthest need, the earliest time);
  // also what service::clear_from_s and follower_path take instead of making them again.
  service::RunReachBlocks need;
  // As a leader leaving at D: past section start + i kReachStep_m by D + reach_t_s[i] at the
  // latest.
  std::vector<double> reach_t_s;
};

// One train's actual run on a day: its departure and run (as a leader) of each section it ran
// (fewer than the line's when it was taken out of service), and its trip once a follower needs
// it.
struct TrainTrack {
  std::vector<double> departure_s;
  std::vector<const DrivenRun*> runs;
  bool held_up = false;
  mutable physics::Trip trip;  // made on demand by DrivenFollowers::trip
};

struct DrivenStep {
  const DrivenRun* run = nullptr;
  double departure_s = 0.0;
  double line_wait_s = 0.0;
};

class DrivenFollowers {
 public:
  // The running times, per section, that the followers may drive beyond the knots and the plan
  // (the candidate runs of `delay` for every train's planned times), for SectionRuns::ensure_all
  // before construction (each within the section's frontier).
  static std::vector<std::vector<double>> candidate_times(const dp::SectionLibrary& library,
                                                          const Plan& plan, double min_dwell_s,
                                                          const SectionRuns& runs);
  // plan: the operating plan; runs holds every knot, planned and candidate time.
  DrivenFollowers(const dp::SectionLibrary& library, const Plan& plan, const SectionRuns& runs,
                  double min_dwell_s);

  // The run at the largest time not above time_s (the flat-out run below it), and at the least
  // time not below it (the longest run above it).
  const DrivenRun& at_or_below(std::size_t section, double time_s) const;
  const DrivenRun& at_or_above(std::size_t section, double time_s) const;
  // True when `run` of section k left at departure_s keeps the braking distance behind the
  // leader at every sample.
  bool clear(const TrainTrack& leader, std::size_t k, const DrivenRun& run,
             double departure_s) const;
  // The held-up follower's runs from stop `from` (ready to leave at ready_s) to the last.
  std::vector<DrivenStep> path(std::size_t train, const TrainTrack& leader, std::size_t from,
                               double ready_s) const;
  // The follower's whole run against the leader's, re-simulated: the scan, or std::logic_error
  // when it comes closer than the braking distance anywhere.
  service::SeparationScan check(const TrainTrack& leader, const TrainTrack& follower,
                                std::size_t train) const;
  const physics::Trip& trip(const TrainTrack& t) const;
  double braking_m_s2() const { return braking_m_s2_; }

 private:
  // The separation is checked on trajectory samples at most this far apart in distance or in
  // time, whichever comes first (the re-simulation's own step is 5 cm; this keeps a day's trips
  // small and the slow start from a stop, where the separation binds, sampled finely).
  static constexpr double kTraceStep_m = 1.0, kTraceStep_s = 0.1;
  struct Pattern {
    service::ServicePlan plan;
    std::vector<const DrivenRun*> planned;  // per section
    TrainTimes times;
    std::vector<std::vector<const physics::SimulationResult*>> candidates;  // per section
  };
  double reach_time_s(const TrainTrack& leader, double position_m) const;
  const DrivenRun* run_of(const Pattern& p, std::size_t k,
                          const physics::SimulationResult* sim) const;

  const dp::SectionLibrary& library_;
  const Plan& plan_;
  std::vector<std::vector<std::unique_ptr<DrivenRun>>> runs_;  // per section, by time
  std::unordered_map<const physics::SimulationResult*, const DrivenRun*> by_sim_;
  std::vector<Pattern> patterns_;
  std::vector<std::size_t> pattern_of_;  // per train
  std::vector<double> station_m_;        // position of each stop along the line
  double braking_m_s2_ = 0.0, room_m_ = 0.0;
  service::SeparationOptions separation_;
};

}  // namespace ecorail::recovery::detail
