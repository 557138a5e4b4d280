#include "dp/timing_pin_trials.hpp"

#include <algorithm>
#include <utility>

#include "dp/timing_journey_part.hpp"

namespace ecorail::dp::timing {

double journey_cost_J(const TimingJourneySolution& s) {
  if (!s.windows_met || !s.summary.IsSolutionUsable()) return kInf;
  double cost = 0.0;
  for (const JourneySection& section : s.journey.sections) cost += section.run.cost_J;
  return cost;
}

void depart_at(TimingWindow& first, double departure_s) {
  first.earliest_s = departure_s;
  first.latest_s = std::max(first.latest_s, departure_s);
}

TimingJourneySolution after_trying(TimingJourneySolution solution, int evaluations,
                                   std::chrono::steady_clock::time_point t0) {
  solution.summary.evaluations += evaluations;
  solution.summary.total_wall_s +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  solution.journey.total_wall_s = solution.summary.total_wall_s;
  return solution;
}

CheapestTrialJourney solve_cheapest_in_turn(
    std::size_t trials, const std::function<std::vector<TimingWindow>(std::size_t)>& journey_of,
    const JourneySolve& solve, int* evaluations) {
  CheapestTrialJourney out;
  for (std::size_t k = 0; k < trials && k < kFinalTries && !out.met; ++k) {
    try {
      TimingJourneySolution s = solve(journey_of(k));
      *evaluations += s.summary.evaluations;
      const bool met = finite(journey_cost_J(s));
      if (met || !out.solution) {
        out.solution = std::move(s);
        out.index = k;
        out.met = met;
      }
    } catch (const TimeRequestError&) {  // a state no run reaches (or too slow)
    }
  }
  return out;
}

}  // namespace ecorail::dp::timing
