// Monte Carlo simulation of whole service days under random delays (question 3.2). A day: every
// train of the plan, in departure order, station by station. At each departure a delay is drawn
// (recovery/delay_model.hpp, keyed by seed, day, train and station); a train that is late, or
// still inside a recovery, runs the next section by the policy: the exact policy of question
// 3.1 re-applied at every departure (earliest station back on time by a flat-out run with
// minimum dwells, then the time split over the sections to there by one time price on their
// frontiers), with early running allowed (a train may depart up to early_s before its
// timetabled departure inside a recovery, so it may also run a section slower than planned to
// arrive on time), or the seed paper's rule (flat out until on time, never early). A train
// is checked against the actual run of the train ahead and, when held up, driven by the follower
// model of `ecorail delay` (FollowerModel::Driven, the default), or, in the fast mode
// (FollowerModel::Shortcut, reported as such), departs no sooner than separation_s after the
// train ahead left the same station (docs/delays.md gives the fast mode's error); a drawn delay
// over takeover_s takes the train out of service at that station: the next service takes over its
// passengers, its remaining sections are not run (no energy) and its remaining arrivals are counted
// as taken over, not as late. Energy: traction at the wheel and substation energy after regenerated
// energy is used, in the power-flow model of one supply section (min of traction and regenerated
// energy per bin), from precomputed section runs laid on the day's grid
// (recovery/section_runs.hpp). Days run in parallel (OpenMP) into an array indexed by day, so
// results do not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dp/section_library.hpp"
#include "dp/termination.hpp"
#include "recovery/delay_model.hpp"
#include "recovery/monte_carlo_stats.hpp"
#include "recovery/plan.hpp"
#include "recovery/section_runs.hpp"

namespace ecorail::recovery {

namespace detail {
class DrivenFollowers;
}

// Exact: question 3.1's policy (earliest station back on time, then least energy). Rule: the
// seed paper's. ExactPunctual: Exact with one more constraint before the energy: every arrival
// on the way that a flat-out run could make punctual is punctual.
enum class RecoveryPolicy { Exact, Rule, ExactPunctual };
const char* recovery_policy_name(RecoveryPolicy p);

// How a train held up by the one ahead runs. Driven: by the follower model of `ecorail delay`
// (service/follower.hpp, recovery/monte_carlo_followers.hpp): every train is checked against the
// actual run of the train ahead under the cap v <= sqrt(2 L b), and one that would come closer
// than its braking distance waits at the stop and is driven back on time over the section runs
// of `delay`, its runs priced as every other. Shortcut (the fast mode): consecutive departures
// from a station at least separation_s apart, nothing re-simulated.
enum class FollowerModel { Driven, Shortcut };
const char* follower_model_name(FollowerModel m);

struct MonteCarloOptions {
  DelayDistribution delays;
  std::uint64_t seed = 1;
  RecoveryPolicy recovery = RecoveryPolicy::Exact;
  double early_s = 10.0;  // a train may arrive and depart this much before the timetable
  // The operating plan runs this much ahead of the published timetable (0 <= it <= early_s):
  // every departure and arrival that much early, a buffer a delay uses up before it makes the
  // train late. Recovery aims at the operating plan; lateness is counted against the timetable.
  double run_early_s = 0.0;
  double min_dwell_s = 30.0;          // a stop's dwell never goes below min(this, planned)
  double takeover_s = 120.0;          // a drawn delay above this is not recovered: taken over
  double punctual_s = 10.0;           // an arrival at most this late is punctual
  double on_time_tolerance_s = 0.05;  // a late episode ends at an arrival this close to the plan
  double separation_s = -1.0;  // least time between departures from a station (< 0: from the plan)
  double knot_step_s = 1.0;    // section runs every this many seconds of running time
  double bin_step_s = 0.1;     // power-flow grid; must divide 1 s
  FollowerModel followers = FollowerModel::Driven;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// A delay imposed instead of the random ones (tests, and the check against question 3.1).
struct ForcedDelay {
  std::size_t train = 0, station = 0;
  double delay_s = 0.0;
};

struct MonteCarloSummary {
  dp::Termination termination = dp::Termination::FAILURE;
  std::uint64_t first_day = 0, last_day = 0;  // days [first, last)
  int threads = 1;
  std::string followers = "driven";  // follower_model_name of the run
  double separation_s = 0.0;
  std::size_t section_runs = 0;  // pieces precomputed
  MonteCarloStatistics statistics;
  double plan_traction_kJ = 0.0, plan_substation_kJ = 0.0;
  double wall_s = 0.0;
  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return dp::is_usable(termination); }
};

class MonteCarlo {
 public:
  // Checks the options (std::invalid_argument) and the plan (every running time within its
  // section's frontier); makes the section runs the plan needs in runs (shared between plans
  // of one line, e.g. the candidates of plan adjustment).
  MonteCarlo(const dp::SectionLibrary& library, const Plan& plan, const MonteCarloOptions& options,
             SectionRuns& runs);
  ~MonteCarlo();

  // The operating plan (the timetable shifted by run_early_s).
  const Plan& plan() const { return plan_; }
  const MonteCarloOptions& options() const { return options_; }
  double separation_s() const { return separation_s_; }

  // One day (0-based). forced: delays imposed instead of the random draws (all others 0).
  // arrivals_s (may be null): every train's actual arrival at each stop on the day's clock (NaN
  // at the first stop and where it did not run).
  DayRecord simulate_day(std::uint64_t day, const std::vector<ForcedDelay>* forced = nullptr,
                         std::vector<std::vector<double>>* arrivals_s = nullptr) const;
  // The plan run without any delay: its traction and substation energy.
  DayRecord plan_day() const;
  // Days [first, last) on `threads` OpenMP threads (0: all); records in day order. progress
  // (may be empty) is called from one thread with (days done, days total).
  std::vector<DayRecord> run_days(std::uint64_t first, std::uint64_t last, int threads,
                                  const std::function<void(int, int)>& progress = {}) const;

  // The exact policy's running time for the section leaving `station` at departure_s, for train
  // k (what simulate_day uses), and whether a station is reached on time.
  double exact_time(std::size_t train, std::size_t station, double departure_s,
                    bool* recoverable = nullptr) const;

 private:
  double exact_target(std::size_t train, std::size_t station, double departure_s, bool* recoverable,
                      std::size_t* target) const;
  void allocate(std::size_t train, std::size_t a, std::size_t b, double start_s, double end_s,
                std::vector<double>& t) const;

  const dp::SectionLibrary& library_;
  Plan plan_;
  MonteCarloOptions options_;
  SectionRuns& runs_;
  std::vector<std::vector<double>> dmin_;  // per train, per station
  double separation_s_ = 0.0;
  double horizon_s_ = 0.0;
  double slack_s_ = 0.0;  // how much earlier than the operating plan a train may leave
  std::unique_ptr<detail::DrivenFollowers> followers_;  // FollowerModel::Driven only
};

// The least time between two departures from a station for which a train running the plan's
// first train's pattern behind another never exceeds the separation cap sqrt(2 L b) of question
// 2.2 (bisection to 0.1 s on the cap scan of service/separation.hpp).
double separation_time_s(const dp::SectionLibrary& library, const Plan& plan, SectionRuns& runs);

}  // namespace ecorail::recovery
