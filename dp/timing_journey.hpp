// Journeys with timing points (TTOBench journeys): least energy subject to a time window and a
// speed window at each timing point. A stop (speed window [0, 0]) splits the journey into parts
// that couple only through time; each part is one section engine over its stretch of track.
// Every part departs at its earliest allowed time and arrives at its latest (energy falls with
// running time); inside a part, passing points are met with one time price per stretch between
// binding timing points (dp/stage_prices.hpp): a second spent before a binding latest bound is
// worth more than one after it, before a binding earliest bound less. The prices are searched on
// the re-simulated times; which windows bind is reported, and every window is checked on the
// final re-simulation. Windows that no run can meet are refused before any search with
// WindowInfeasibleError, naming the window and the least time needed (flat-out runs, a proof).
// See docs/ttobench.md ("Journeys with timing points").
#pragma once

#include <string>
#include <vector>

#include "dp/journey.hpp"
#include "dp/progress_callback.hpp"
#include "dp/section_engine.hpp"
#include "dp/termination.hpp"
#include "dp/time_target.hpp"
#include "physics/timing_window.hpp"

namespace ecorail::dp {

// One timing point (physics/timing_window.hpp).
using TimingWindow = physics::TimingWindow;

struct TimingJourneyOptions {
  EngineOptions engine;
  // A window holds in the re-simulation when the time is within time_tolerance_s and the speed
  // within speed_tolerance_kmh of its bounds.
  double time_tolerance_s = 0.05;
  double speed_tolerance_kmh = 0.1;
  // Price evaluations (sweep, extraction, re-simulation) allowed per part.
  int max_evaluations = 400;
  // A part that ends at one speed or at a stop has its run descended on its switches
  // (dp/timing_switch_descent.hpp); off for the speed pins' trial solves, which only compare
  // times.
  bool descend_on_switches = true;
  // A part still missing a window after its price searches is searched by the time-expanded
  // label search (dp/timing_label_search.hpp); off for the speed pins' trial solves, whose
  // comparisons a run found that way (feasible, its energy a heuristic's) would mislead.
  bool label_search_last_resort = true;
  // Called after each price evaluation of a part ("price evaluation", the part's count, 0; a part
  // without binding windows searches one price: "lambda evaluation"): a long journey shows its
  // progress, and a caller may stop it by throwing from here.
  ProgressFn progress;
  bool IsValid(std::string* error) const;
};

// A window no run can meet (found by flat-out runs before any search), or a journey the solver
// does not take (point names the timing point, 0-based). what() is the whole sentence.
class WindowInfeasibleError : public TimeRequestError {
 public:
  WindowInfeasibleError(int point, const std::string& message)
      : TimeRequestError(message), point_(point) {}
  int point() const { return point_; }

 private:
  int point_;
};

struct WindowResult {
  TimingWindow window;
  double time_s = 0.0;             // re-simulated (departure time for a departure point)
  double speed_ms = 0.0;           // re-simulated
  std::vector<std::string> binds;  // "earliest", "latest", "min_speed", "max_speed"
  bool met = false;
};

// One part (stop to stop, or from/to a moving end): its stretch, times and prices.
struct TimingPart {
  int first_point = 0, last_point = 0;  // indices into the journey's windows
  double start_m = 0.0, end_m = 0.0;
  double departure_s = 0.0, arrival_target_s = 0.0;
  // Price of each stretch between consecutive timing points of the part (J/s), first to last.
  std::vector<double> stretch_lambda_J_per_s;
  int evaluations = 0;
  // Its run is the label search's (dp/timing_label_search.hpp, the last resort where the price
  // searches missed a window): feasible, its energy a heuristic's.
  bool by_label_search = false;
};

struct TimingJourneySummary {
  std::string id;
  int parts = 0;
  double distance_m = 0.0;
  GridSpec grid;
  Objective objective = Objective::Traction;
  int evaluations = 0;
  bool windows_met = false;
  Termination termination = Termination::FAILURE;
  double total_wall_s = 0.0;
  double running_time_s = 0.0;
  double trip_time_s = 0.0;
  double traction_energy_kJ = 0.0;
  double regen_energy_kJ = 0.0;
  double net_energy_kJ = 0.0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  // Usable only when every part arrives and every window holds.
  bool IsSolutionUsable() const { return is_usable(termination); }
};

struct TimingJourneySolution {
  std::vector<physics::Route> routes;  // one per part
  std::vector<TimingPart> parts;
  // The parts as a journey's sections (dwell after each part: the time at its stop), so the
  // journey outputs (timeline, trip, JSON) apply unchanged. Its lambda is NaN (several prices).
  JourneySolution journey;
  std::vector<WindowResult> windows;
  bool windows_met = false;
  TimingJourneySummary summary;
};

// The journey over `track` (positions of the windows are track positions). WindowInfeasibleError
// for windows no run can meet and for journeys outside what is supported (see the doc);
// std::invalid_argument for invalid options. A solution whose windows are not all met is
// returned flagged (termination not CONVERGENCE), never as a result.
TimingJourneySolution solve_timing_journey(const physics::Train& train, const physics::Route& track,
                                           const std::vector<TimingWindow>& windows,
                                           const TimingJourneyOptions& options,
                                           const std::string& id = "");

// The stretch [from_m, to_m] of a route as a route of its own: physics/route.hpp.
using physics::slice_route;

}  // namespace ecorail::dp
