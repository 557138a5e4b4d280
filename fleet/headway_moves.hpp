// The moves of the heuristic headway search (fleet/headway_optimiser.hpp) on an incremental
// balance: simulated annealing of the departures of trains 1..N-2 (one train moved by up to
// 30 s, or a block of 2-5 consecutive trains shifted together, every headway's clock class
// checked; counter-based draws keyed by seed, run and move, so a run does not depend on the
// thread that makes it), and the polish (every train tried at every departure within a window
// until a sweep changes nothing). Both keep to a time limit counted from t0.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/search_support.hpp"

namespace ecorail::fleet {

// The departure range of train k (0 < k < N-1) given its neighbours (with peak windows: the
// range of any class; allowed() then checks the classes of both headways).
std::pair<int, int> feasible_range(const FleetProblem& p, const std::vector<int>& t, int k);
bool allowed(const FleetProblem& p, const std::vector<int>& t, int k, int d);
// Whether a limit (0: none) has passed since t0.
bool past(SearchClock::time_point t0, double limit_s);

struct RunResult {
  std::vector<int> departures;  // the best seen on the balance's grid
  energy::MicroJoules substation = 0;
  long moves = 0;
  bool stopped = false;  // by the time limit
};

// Simulated annealing from t, minimising the substation energy; the start temperature is
// temperature_scale times the mean size of a few proposals' changes, cooled 1000x over `moves`.
RunResult anneal(energy::FleetBalance& balance, const FleetProblem& p,
                 const energy::SearchPlan& plan, std::vector<int> t, std::uint64_t seed,
                 std::uint64_t run, long moves, SearchClock::time_point t0, double limit_s,
                 bool block_moves, double temperature_scale = 1.0);

// Tries every departure within +-window for every train in turn, keeping the best, until a sweep
// changes nothing (at most `sweeps`); the time limit stops it between trains (*stopped set; the
// timetable so far is kept). Returns the moves priced.
long polish(energy::FleetBalance& balance, const FleetProblem& p, std::vector<int>& t, int window,
            int sweeps, SearchClock::time_point t0, double limit_s, bool* stopped);

}  // namespace ecorail::fleet
