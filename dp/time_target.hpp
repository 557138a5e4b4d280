// Running-time search: finds the time price lambda whose optimal run, re-simulated, takes the
// requested running time. Running time falls as lambda grows; the search brackets lambda by
// expansion in log space and closes the bracket by regula falsi (Illinois variant) on the
// re-simulated time, so the time it reports is the measured one.
//
// On a grid, T(lambda) is ragged (by hundredths of a second, and in places by seconds where the
// optimal program changes shape), while every run lies on the same energy-time frontier. So the
// lambda search stops within a coarse tolerance (lambda_tolerance_s, half a second) and the rest
// is closed by trimming one switch point out of full traction: at an optimum the marginal energy
// per second of moving any switch point equals lambda, so the trim moves along the frontier and
// costs only a second-order error (measured on the A6 -> A7 frontier: within +-0.013 % of a
// search to 0.05 s, mean -0.00002 %, docs/performance.md).

// Long running times have an upper end too. From rest the first grid step admits only full
// traction (every other control stalls at v = 0), and at low speeds a coast that the grid
// believes reaches the next stage (its end speed interpolated towards the v = 0 node) may stall
// in the continuous re-simulation: below some price the extracted run comes to rest before the
// station, or the running time stops growing as lambda falls. So a run that does not arrive is
// never a candidate of the search (it counts as "too slow"), and when a time cannot be met the
// engine measures the longest running time it solves reliably (find_slow_limit) and refuses a
// longer one with LongTimeError, as it refuses one below the flat-out run.
#pragma once

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/error.hpp"
#include "dp/cruise_polish.hpp"
#include "dp/progress_callback.hpp"
#include "dp/section_engine.hpp"

namespace ecorail::dp {

// A running time the engine cannot solve: the base of the errors below (and of a journey's
// proportional share that falls below a section's minimum). what() says what went wrong.
class TimeRequestError : public std::invalid_argument, public Error {
 public:
  explicit TimeRequestError(const std::string& what)
      : std::invalid_argument(what), Error(ErrorKind::kRunningTime) {}
};

// The requested running time is shorter than the flat-out run. subject (may be empty) says
// what the minimum is of, e.g. "A6 -> A7 (flat-out run)", so a caller can phrase its own message.
class InfeasibleTimeError : public TimeRequestError {
 public:
  InfeasibleTimeError(double requested_s, double minimum_s, std::string subject = "");
  double minimum_s() const { return minimum_s_; }
  double requested_s() const { return requested_s_; }
  const std::string& subject() const { return subject_; }

 private:
  double minimum_s_;
  double requested_s_;
  std::string subject_;
};

// The longest running time the engine solves reliably for a section is below the request.
class LongTimeError : public TimeRequestError {
 public:
  LongTimeError(double requested_s, double maximum_s);
  double maximum_s() const { return maximum_s_; }

 private:
  double maximum_s_;
};

// What every result must meet: it comes to rest at the stop (within kStopTolerance_m) and, for
// a target time, runs within kTimeTolerance_s of it.
inline constexpr double kStopTolerance_m = 0.5;
inline constexpr double kTimeTolerance_s = 0.1;
// The run comes to rest at the end of the section (not before it, not past it).
bool run_arrives(const physics::SimulationResult& sim);

// The slow end of what the engine solves: lambda is lowered from kSlowScanStart_J_per_s by
// halves while the run still arrives and its running time still grows, then the last step is
// bisected (kSlowScanRefinements times in log lambda). max_time_s is the longest arriving run
// found and lambda_J_per_s its price; below that price the grid's slow runs are not trusted.
// Depends on the engine and the start state only, so every command states the same limit.
struct SlowLimit {
  double max_time_s = 0.0;
  double lambda_J_per_s = 0.0;
  LambdaRun run;
  int evaluations = 0;
  // Every arriving run of the scan, by falling lambda: (lambda, running time).
  std::vector<std::pair<double, double>> scan;
};
inline constexpr double kSlowScanStart_J_per_s = 3e5;
inline constexpr int kSlowScanRefinements = 6;
SlowLimit find_slow_limit(const SectionEngine& engine, const StartState& start = {});

// Where the trim cannot close lambda_tolerance_s (or only at a price far above lambda), the
// search narrows on to this before trimming again (the price tolerance of an all-fine search).
inline constexpr double kFallbackLambdaTolerance_s = 0.05;

struct TimeSearchOptions {
  double tolerance_s = 0.001;       // final, after the trim
  double lambda_tolerance_s = 0.5;  // lambda search alone; the trim closes the rest
  bool trim = true;
  int max_iterations = 60;
  double lambda_guess = 3e5;  // J/s; only a starting point
  // lambda is multiplied or divided by this while bracketing: the lattice of prices a frontier's
  // searches share (LatticeRuns); a factor of 2 leaves the regula falsi about one evaluation
  // per frontier point.
  double bracket_factor = 2.0;
  // Re-simulation step (RK4) of the runs that bracket and narrow lambda to lambda_tolerance_s;
  // the best is then re-run at the engine's fine step (from its kept value function, no second
  // sweep), which alone is trimmed and returned. RK4 at 0.5 m puts a run's time within about a
  // millisecond of the fine run's, far inside lambda_tolerance_s, at a tenth of its cost. 0, or
  // at most the engine's resim_step_m: every run is fine (an all-fine search; the energies
  // it gives differ by under 0.005 %, docs/performance.md).
  double search_step_m = 0.5;
  // Called after each lambda evaluation ("lambda evaluation", count, 0); may be empty.
  ProgressFn progress;
  // A long cruise of the converged run is made one hold with its coasting point searched
  // (dp/cruise_polish.hpp); only a cheaper run that meets the time replaces the grid's.
  CruisePolishOptions cruise_polish;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

struct TimeSearchResult {
  LambdaRun run;
  int iterations = 0;       // lambda evaluations (sweep + extraction + re-simulation)
  int trim_iterations = 0;  // re-simulations of the trim
  double trim_shift_m = 0.0;
  bool converged = false;
  // Measured when the search could not meet a time (0: not measured).
  double max_time_s = 0.0;
  CruisePolishReport cruise_polish;  // what the cruise polish did to the converged run
  // How much more the converged run (before its polish) cost held than the grid's own run at
  // its price, as a share of the priced cost (LambdaRun::held_excess_share); above
  // kGridCruisesCheckShare the time is searched again with the grid's own cruises
  // (grid_cruises_searched), and that run is kept when it costs less (grid_cruises_kept,
  // saving grid_cruises_saving_J).
  double held_excess_share = 0.0;
  bool grid_cruises_searched = false;
  bool grid_cruises_kept = false;
  double grid_cruises_saving_J = 0.0;
};

// A search whose converged run costs this share more held than as the grid has it, at its time
// price, is searched again with the grid's own cruises (dp::solve_for_time). Measured at the
// converged runs (2026-12-07): 0 on the reference line's A5 -> A6 every 2 s from 140 s to
// 160 s but at 146 s (0.003 %); on TTOBench tracks at their minimum time + 10 %, CH_Fribourg_Bern
// 0.087 % (FLIRT; the grid's own run 0.30 % cheaper in the end) and 0.92 % (VIRM6; 4.3 %
// cheaper), 00_var_speed_limit_110 0.72 % (KISS) and 00_var_gradient_minus_10 0.29 % (VIRM6),
// where the held run's polish ends cheaper and is kept. It decides only whether the second
// search runs (it costs about one more search); the cheaper run is kept either way.
inline constexpr double kGridCruisesCheckShare = 2e-4;

// Moves one switch point out of full traction so the re-simulated time matches the target.
// Returns false if no switch point can reach it. With search_step_m above the engine's fine step
// the switch is searched on runs re-simulated at that step (a tenth of the cost at 0.5 m),
// aiming at the target moved by the fine run's offset from the coarse one; the trimmed program
// is then re-simulated at the fine step, which alone is accepted (within tolerance_s) and
// returned. If that does not meet the time, the search runs on fine runs as before.
// A trimmed run of an optimum (from_optimum, the default) is accepted only if it costs at most
// about what moving along the frontier costs (its cost plus lambda times the time gained, plus a
// tenth of that again): a switch that buys the time far dearer is skipped for the next one. An
// edited, non-optimal program (e.g. dp::enforce_min_regime's merges) is trimmed without it.
bool trim_to_time(const SectionEngine& engine, double target_time_s, double tolerance_s,
                  TimeSearchResult& result, double search_step_m = 0.0, bool from_optimum = true);
// The same for a run re-simulated at step_m (result.run.sim, a search's coarse run): trimmed on
// runs at that step towards the target moved by offset_s (the fine run's time minus the coarse
// one's, 0 if not known), each trimmed program checked by a fine run (resumed from fine_base, a
// fine run of a program that shares a prefix, when it has checkpoints), a miss correcting the
// offset by what that fine run measured. Only a fine run that meets the time is accepted and
// returned in result; false when none did.
bool trim_via_coarse_runs(const SectionEngine& engine, double target_time_s, double tolerance_s,
                          TimeSearchResult& result, double step_m, double offset_s,
                          physics::SimulationResult fine_base = {});

// Runs already computed on the search's lattice of prices (lambda_guess times powers of
// bracket_factor), shared by consecutive searches on one engine from one start, e.g. the points
// of a frontier. Every search brackets its time by walking that lattice from lambda_guess, so a
// frontier point and a stand-alone solve for the same time take the same path to the same run;
// with a memo, the frontier pays for each lattice price once. Thread-safe.
class LatticeRuns {
 public:
  bool find(double lambda, LambdaRun* run) const;
  void keep(const LambdaRun& run);

 private:
  mutable std::mutex mutex_;
  std::map<double, LambdaRun> runs_;
};

// Where a neighbouring solve put the price: log(lambda) and the slope of the running time in it
// (negative), e.g. the previous point of a frontier or the frontiers' price of a journey. Only a
// starting point: the search starts with Newton and secant steps from it instead of walking the
// lattice, which costs about one evaluation when the neighbour is close.
// From rest at the departure, or (start given) for the rest of the section from a mid-run state
// in the remaining running time target_time_s. InfeasibleTimeError below the flat-out time,
// LongTimeError above the slow limit; otherwise converged says whether the time was met by a
// run that arrives. Where the converged run's held cruises cost more than the grid's own at its
// price (held_excess_share above kGridCruisesCheckShare), the time is searched again on the
// grid's own cruises and the cheaper run returned (grid_cruises_searched, grid_cruises_kept).
TimeSearchResult solve_for_time(const SectionEngine& engine, double target_time_s,
                                const TimeSearchOptions& options, const StartState& start = {},
                                LatticeRuns* memo = nullptr);

}  // namespace ecorail::dp
