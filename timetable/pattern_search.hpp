// Pattern optimisation: dwells and section running times chosen jointly with the headways. With
// no timetable coupling every dwell goes to its minimum (dp/journey.hpp, free dwells); with
// regenerated energy shared between trains a longer dwell or a re-timed section can move a
// braking phase onto another train's acceleration. The search alternates: headways optimised
// for the pattern (optimise_headways), then the pattern improved for those headways by moves
// that keep the trip time (a dwell longer by delta and the section before or after it shorter by
// delta, or the reverse; deltas 4, 2, 1 s), each section re-solved energy-optimally for its new
// running time on the section library (solves are cached), the first improving move taken, until
// no move improves; then the headways once more. Every pattern the search keeps is feasible
// (dwells in range, each running time above its section's flat-out run), and the result is never
// worse than the headways alone (the search only accepts improvements). Same pattern for every
// train.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dp/section_library.hpp"
#include "timetable/fleet_pattern.hpp"
#include "timetable/headway_optimiser.hpp"

namespace ecorail::timetable {

struct PatternSearchOptions {
  HeadwayOptimiserOptions headways;
  std::vector<double> deltas_s = {4.0, 2.0, 1.0};
  int max_moves = 200;  // accepted pattern moves at most
  bool IsValid(std::string* error) const;
};

struct PatternSearchResult {
  PatternTrip pattern;               // the pattern found and its trip
  HeadwayOptimiserResult timetable;  // headways for it (final)
  FleetEvaluation headways_only;     // the start: default pattern, its optimal headways
  int moves_accepted = 0;
  int patterns_evaluated = 0;
  std::string BriefReport() const;
};

PatternSearchResult optimise_pattern(const dp::SectionLibrary& library, const FleetProblem& problem,
                                     const EnergyModelOptions& model, const PatternTrip& start,
                                     const PatternSearchOptions& options);

}  // namespace ecorail::timetable
