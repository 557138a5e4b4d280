// The structure of a timing-point journey and the proof that its windows can be met: where its
// parts (stop to stop) begin and end, the checks of its layout, and the earliest time each
// timing point can be reached (flat-out runs), which refuses a window no run can meet before
// any search, naming the first such window. Internal to the journey solver
// (dp/timing_journey*.cpp).
#pragma once

#include <memory>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/timing_journey.hpp"
#include "physics/motion.hpp"
#include "physics/speed_envelope.hpp"

namespace ecorail::dp::timing {

// Where the parts start and end: indices of the points that bound them.
struct PartBounds {
  int first = 0, last = 0;
};

// A passing point whose windows fix its whole state: one time and one speed above 0 (zero-width
// windows). The run before it and the run after it do not interact (principle of optimality),
// so such a point ends one part (moving, at that speed) and starts the next.
bool pins_the_state(const TimingWindow& w);

// A stop (speed window [0, 0]), a point that pins the state, or the last point ends a part;
// two points at one position are the arrival at and the departure from a stop.
std::vector<PartBounds> split_into_parts(const std::vector<TimingWindow>& w);

// WindowInfeasibleError for a journey the solver does not take: fewer than two points, a point
// off the track, bounds the wrong way round, positions out of order, an open last arrival.
void check_structure(const std::vector<TimingWindow>& w, double track_length_m);

// The route whose speed envelope a part that ends moving uses (a run-off past its end).
physics::Route runoff_route(const physics::Train& train, const physics::Route& part, double top_ms,
                            double resolution_m);

// What the proof needs of a part: its speed envelope and its flat-out runs, without the grid
// and the transition table a SectionEngine builds (a refused journey pays for no table). The
// flat-out run is bit for bit SectionEngine::min_time_run's over the same route and options.
class FlatOutModel {
 public:
  FlatOutModel(const physics::Train& train, const physics::Route& route,
               const physics::Route& envelope_route, const EngineOptions& options);
  FlatOutModel(const FlatOutModel&) = delete;
  FlatOutModel& operator=(const FlatOutModel&) = delete;
  const physics::SpeedEnvelope& envelope() const { return envelope_; }
  physics::SimulationResult min_time_run(const StartState& start) const;

 private:
  physics::Train train_;
  physics::Route route_;
  physics::SpeedEnvelope envelope_;
  physics::Motion motion_;
  double step_m_;
};

// The earliest time each point can be reached (departure at departure0_s), from flat-out runs
// over each part from its start state; WindowInfeasibleError naming the first window whose
// latest time (or lowest speed) no run can meet.
std::vector<double> earliest_times(const std::vector<TimingWindow>& windows,
                                   const std::vector<PartBounds>& bounds,
                                   const std::vector<std::unique_ptr<FlatOutModel>>& engines,
                                   const std::vector<StartState>& starts, double departure0_s,
                                   double tol_t, double tol_v);

}  // namespace ecorail::dp::timing
