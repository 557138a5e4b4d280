// Running-time search: finds the time price lambda whose optimal run, re-simulated, takes the
// requested running time. Running time falls as lambda grows; the search brackets lambda by
// expansion in log space and closes the bracket by regula falsi (Illinois variant) on the
// re-simulated time, so the time it reports is the measured one.
//
// On a grid, T(lambda) is slightly ragged (a few hundredths of a second), while every run lies
// on the same energy-time frontier. So the lambda search stops within a coarse tolerance and the
// last hundredths are closed by trimming one switch point out of full traction: at an optimum
// the marginal energy per second of moving any switch point equals lambda, so the trim moves
// along the frontier and costs only a second-order error.
#pragma once

#include <stdexcept>
#include <string>

#include "dp/section_engine.hpp"

namespace ecorail::dp {

// The requested running time is shorter than the flat-out run.
class InfeasibleTimeError : public std::invalid_argument {
 public:
  InfeasibleTimeError(double requested_s, double minimum_s);
  double minimum_s() const { return minimum_s_; }

 private:
  double minimum_s_;
};

struct TimeSearchOptions {
  double tolerance_s = 0.001;        // final, after the trim
  double lambda_tolerance_s = 0.05;  // lambda search alone
  bool trim = true;
  int max_iterations = 60;
  double lambda_guess = 3e5;    // J/s; only a starting point
  double bracket_factor = 4.0;  // lambda is multiplied or divided by this while bracketing
};

struct TimeSearchResult {
  LambdaRun run;
  int iterations = 0;       // lambda evaluations (sweep + extraction + re-simulation)
  int trim_iterations = 0;  // re-simulations of the trim
  double trim_shift_m = 0.0;
  bool converged = false;
};

// Moves one switch point out of full traction so the re-simulated time matches the target.
// Returns false if no switch point can reach it.
bool trim_to_time(const SectionEngine& engine, double target_time_s, double tolerance_s,
                  TimeSearchResult& result);

// From rest at the departure, or (start given) for the rest of the section from a mid-run state
// in the remaining running time target_time_s.
TimeSearchResult solve_for_time(const SectionEngine& engine, double target_time_s,
                                const TimeSearchOptions& options, const StartState& start = {});

}  // namespace ecorail::dp
