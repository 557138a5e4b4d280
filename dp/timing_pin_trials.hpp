// What the two searches over pinned states of a timing-point journey share: the speed pins
// (dp/timing_speed_pins.hpp, a point's free time or speed by golden section) and the binding
// pins (dp/timing_binding_pins.hpp, the speeds where the label search's run binds a time, by a
// lattice along the chain of pieces between them). Both score a trial by solves of the stretch
// it changes, and then solve the whole journey at the cheapest trials' values in turn: a trial
// is solved on another grid or over a shorter stretch than the journey, and a value met there
// can be missed on the journey (a time at 1 813.9 m of seed 71's journey 27 at the default
// grid: the trials around it alternate between met and missed).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "dp/timing_journey.hpp"

namespace ecorail::dp::timing {

// A solved journey's energy cost by its objective; +inf when a window is missed or the solve
// is not usable.
double journey_cost_J(const TimingJourneySolution& s);

using JourneySolve = std::function<TimingJourneySolution(const std::vector<TimingWindow>&)>;
// Whether a journey is refused before any search (flat-out runs cannot meet a window).
using JourneyRefused = std::function<bool(const std::vector<TimingWindow>&)>;

// No pinned speed is searched below this (a crawl; the simulator's slowest runs are unreliable).
constexpr double kLowestPinned_ms = 0.5;
// At most this many of the cheapest trials are solved as whole journeys.
constexpr std::size_t kFinalTries = 3;

// The journey at one of the cheapest trials: `solution` solved from journey_of(index).
struct CheapestTrialJourney {
  std::optional<TimingJourneySolution> solution;  // empty when every solve was refused
  std::size_t index = 0;                          // the trial it was solved at
  bool met = false;                               // every window holds on it
};

// The first window of a stretch solved alone, made its departure at departure_s (the time the
// reference run leaves it): its earliest bound there, its latest no earlier.
void depart_at(TimingWindow& first, double departure_s);

// solution as it was before the pins were tried, its evaluations and wall time counting the
// trials' (they were spent): `evaluations` more, and the time since t0.
TimingJourneySolution after_trying(TimingJourneySolution solution, int evaluations,
                                   std::chrono::steady_clock::time_point t0);

// Solves journey_of(k) for the trials k = 0, 1, ... (cheapest first, `trials` of them), at
// most kFinalTries, until one meets every window (met). When none does, the first journey that
// was solved at all, unmet. A solve refused with a TimeRequestError counts as unmet. Adds each
// solve's evaluations to *evaluations.
CheapestTrialJourney solve_cheapest_in_turn(
    std::size_t trials, const std::function<std::vector<TimingWindow>(std::size_t)>& journey_of,
    const JourneySolve& solve, int* evaluations);

}  // namespace ecorail::dp::timing
