// A time-expanded search for one part of a timing-point journey (dp/timing_journey_part.hpp),
// the last resort when the part's price searches end with a window missed. Energy falls with
// running time, so the part's main search prices time; but windows that hold a run back and
// then ask it to be fast (an earliest bound just before a latest one, twice in one part) can
// leave every price the search tries on the wrong side of some window, although a run exists.
// This search carries what the windows need in its state: a forward DP over position stages (a
// stage ends at every passing point) whose labels are states (speed, time since the departure,
// energy so far) reached by integrating each control (full traction, hold, coast, full braking)
// over the stage with the engine's Motion kernel (coarse Heun substeps, the speed envelope
// supervised as the simulator supervises it). Per stage and (speed, time) bucket it keeps the
// cheapest label and the soonest, latest, fastest and slowest ones (a bucket holding only its
// cheapest label loses the run a later window needs). At a passing point a label outside the
// point's windows (kept a small margin inside their bounds) is dropped, or, within a repair band
// of them, kept at a penalty on its cost (the caller moves the run onto the window); a label
// that could not meet a later latest bound even at the line's top speed is dropped, and so is
// one slower than a crawl between the ends (at walking pace the coarse integration's time drifts
// from the fine re-simulation's by seconds). At the end the label of least cost that ends as the
// part asks becomes a control program, re-simulated at the engine's fine step. With buckets too
// fine to merge labels the DP is exact over its controls (tested against a brute force over
// every control sequence); with its buckets it is a heuristic in energy: a feasible run for the
// caller to move onto its windows (repair_passing_times) and descend on its switches.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/timing_journey_part.hpp"

namespace ecorail::dp::timing {

struct LabelSearchOptions {
  double stage_m = 10.0;  // longest stage (parts of more than max_stages stages stretch it)
  int max_stages = 800;
  double speed_bucket_ms = 0.5;   // one label per bucket of speed ...
  double time_bucket_s = 1.0;     // ... and of time
  double substep_m = 5.0;         // Heun substeps inside a stage
  double time_margin_s = 0.05;    // a window's bounds kept this far inside (when it is wider
  double speed_margin_ms = 0.05;  // than twice the margin; otherwise its middle half)
  // A label outside a window by less than these is kept at a penalty (the caller moves the run
  // onto the window on the simulator): a run the windows leave no room for (a bound at a
  // witness's own time) is found near them. Beyond them it is dropped.
  double repair_s = 0.5;
  double repair_ms = 0.25;
  double time_penalty_J_per_s = 1e8;
  double speed_penalty_J_per_ms = 1e8;
  double crawl_ms = 1.5;           // no label slower than this between the part's ends
  long max_advances = 60'000'000;  // integrations of one control over one stage, all stages
  bool IsValid() const {
    return stage_m > 0.0 && max_stages > 0 && speed_bucket_ms > 0.0 && time_bucket_s > 0.0 &&
           substep_m > 0.0 && substep_m <= stage_m && time_margin_s >= 0.0 &&
           speed_margin_ms >= 0.0 && repair_s >= 0.0 && repair_ms >= 0.0 &&
           time_penalty_J_per_s >= 0.0 && speed_penalty_J_per_ms >= 0.0 && crawl_ms >= 0.0 &&
           max_advances > 0;
  }
};

// A passing point as the label search checks it: position in the part, times relative to the
// part's departure, speeds (m/s); open bounds are infinite.
struct LabelWindow {
  double s_m = 0.0;
  double earliest_s = 0.0, latest_s = 0.0;
  double min_ms = 0.0, max_ms = 0.0;
};

struct LabelSearchResult {
  std::optional<LambdaRun> run;  // re-simulated at the engine's fine step
  double dp_cost_J = NAN;        // the run's cost in the search's own integration
  long labels = 0;               // kept over all stages
  long advances = 0;
  int stages = 0;
  bool out_of_budget = false;  // stopped at max_advances
};

// The part's least-energy run on the label grid from start, ending as end asks between
// earliest_arrival_s and latest_arrival_s after the departure, passing every window. progress
// (optional) is called every few stages ("label search", stage, stages).
LabelSearchResult label_search(const SectionEngine& engine, const StartState& start,
                               const EndCheck& end, double earliest_arrival_s,
                               double latest_arrival_s, const std::vector<LabelWindow>& windows,
                               const LabelSearchOptions& options, const ProgressFn& progress = {});

// Moves a run (the label search's) onto the passing times of `windows`, point by point from
// the first: a time outside its window (or off a zero-width one) is brought to the window's
// nearer bound (kRepairInside_s inside it; a zero-width time onto its value) by moving one
// switch between the point before it and it, bisected on the re-simulated passing time (the
// last switch there that brackets the bound). Switches before a point never move once it is
// met, so the points met stay met. Returns false when some point cannot be met that way (run
// then holds the points met so far); *simulations counts the re-simulations.
bool repair_passing_times(const SectionEngine& engine, const StartState& start, LambdaRun& run,
                          const std::vector<LabelWindow>& windows, int* simulations);

}  // namespace ecorail::dp::timing
