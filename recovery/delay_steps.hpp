// The five steps of recover_delay (recovery/delay_recovery.hpp), each a function of its own:
// (1) the earliest station back on time, (2) the running times split over the frontiers,
// (3) the seed paper's rule, (4) every run solved, re-simulated and laid out on the clock,
// (5) the trains behind, driven by the follower model of service/follower.hpp until one is no
// longer held up. Internal to recovery/.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dp/section_library.hpp"
#include "recovery/delay_recovery.hpp"

namespace ecorail::recovery::detail {

// A section's re-simulated run for one running time: the energy-optimal run (library.solve) or,
// at the minimum time, the flat-out run.
struct Run {
  physics::SimulationResult sim;
  physics::ControlProgram program;  // empty for the flat-out run
  bool flat_out = false;
};

// Runs by (section, running time to the microsecond), solved once. std::runtime_error when no
// run meets its time.
class RunCache {
 public:
  RunCache(const dp::SectionLibrary& library, double flat_out_threshold_s)
      : library_(library), threshold_s_(flat_out_threshold_s), lattice_(library.size()) {}
  const Run& get(std::size_t section, double time_s);
  // Solves the runs of times_s[section] not yet held, sections side by side (OpenMP).
  void prefetch(const std::vector<std::vector<double>>& times_s);
  // The run held within a millisecond of the time, or nullptr (never solves: safe to call from
  // many threads once the cache is filled).
  const Run* find(std::size_t section, double time_s) const;

 private:
  std::unique_ptr<Run> make(std::size_t section, double time_s) const;
  const dp::SectionLibrary& library_;
  double threshold_s_;
  std::map<std::pair<std::size_t, long long>, std::unique_ptr<Run>> runs_;
  // Per section, the lattice prices the solves walk (the same runs as solving each time alone).
  mutable std::vector<dp::LatticeRuns> lattice_;
};

// The late train's minimum running times, planned running times and least dwells (per
// station; 0 at the ends). DelayInputError when the plan is below a flat-out run.
struct TrainTimes {
  std::vector<double> min_s, planned_s, min_dwell_s;
};
TrainTimes train_times(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                       const DelayRecoveryOptions& options);

// The running times a held-up follower chooses from on each section from `first` on: flat out
// (times.min_s), then every step_s, up to slower_s above its planned time (that time included),
// to the millisecond; empty lists before `first`. What `delay` and the Monte Carlo both drive.
std::vector<std::vector<double>> follower_run_times(const TrainTimes& times, double step_s,
                                                    double slower_s, std::size_t first);

// 1. The first station a flat-out run with least dwells (never leaving early) reaches no later
// than planned; plan.sections() + 1 when none does.
std::size_t earliest_station_back(const TrainStops& stops, const TrainTimes& times,
                                  std::size_t station, double late_departure_s, double delay_s);

// 2. New running times (and the marginal price of each) over sections [station, last): the exact
// split over the frontiers when the station e = last is reached in time, flat out otherwise.
struct RecoveryTimes {
  std::vector<double> time_s, marginal_J_per_s;  // per section of the line
  AllocationSummary allocation;
  std::vector<std::string> warnings;
};
RecoveryTimes split_recovery_time(const dp::SectionLibrary& library, const Plan& plan,
                                  std::size_t train, const TrainTimes& times, std::size_t station,
                                  std::size_t e, double late_departure_s,
                                  const DelayRecoveryOptions& options, dp::FrontierStore* store);

// 3. The rule's running times over [station, last).
std::vector<double> rule_times(const TrainStops& stops, const TrainTimes& times,
                               std::size_t station, std::size_t last, double late_departure_s);

// 4. Every run of [station, last) solved and re-simulated for the recovery, the rule and the
// plan; out.sections, the three trips and the summary's energies filled. Returns the late
// train's re-simulated arrival at `last`.
double lay_out_runs(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                    const TrainTimes& times, std::size_t station, std::size_t last,
                    double late_departure_s, const RecoveryTimes& recovery,
                    const std::vector<double>& rule, RunCache& cache, DelayRecoveryResult& out);

// 5. The trains behind, each behind the actual run of the one ahead, until one is not held up
// (or options.max_followers have been driven); out.followers, out.trains and the cascade filled.
void follow_the_late_train(const dp::SectionLibrary& library, const Plan& plan, std::size_t train,
                           std::size_t station, double delay_s, const RecoveryTimes& recovery,
                           const DelayRecoveryOptions& options, RunCache& cache,
                           DelayRecoveryResult& out);

// Lateness of a trip's arrivals against a train's plan, and where it is back on time: the
// station after its last late arrival (none when it is late at the last station).
AffectedTrain lateness_of(int train, const physics::Trip& trip, const TrainStops& plan,
                          const std::vector<std::string>& stations, double tolerance_s);

}  // namespace ecorail::recovery::detail
