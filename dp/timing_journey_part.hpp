// One part of a timing-point journey (dp/timing_journey.hpp): the stretch from a stop (or a
// moving start) to the next stop (or a moving end), with the passing points inside it. Its
// optimum for a departure and a latest arrival is searched with one time price per stretch
// between binding timing points (dp/stage_prices.hpp); what solve_part returns is the run,
// whether every window of the part holds, and the prices. Internal to the journey solver
// (dp/timing_journey*.cpp); docs/ttobench.md ("Journeys with timing points") says how.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "dp/timing_journey.hpp"

namespace ecorail::dp::timing {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// A window of zero width (earliest = latest, or min speed = max speed) is met exactly: within
// these of its bound on the re-simulation, whatever the options' tolerances.
inline constexpr double kZeroWidthTime_s = 0.001;
inline constexpr double kZeroWidthSpeed_ms = 0.01 / 3.6;

inline bool finite(double x) {
  return std::isfinite(x);
}

// Time and speed of a run where it passes s (linear between trace points); nullopt-like
// (t = NaN) when the trace does not reach s.
struct Passing {
  double t_s = NAN, v_ms = NAN;
};
Passing passing_at(const BigVector<physics::TracePoint>& trace, double s);

// "timing point 3 (1500.0 m)" (i is 0-based).
std::string point_name(int i, const TimingWindow& w);

// Whether a run reaches the end of its part as the part asks: at rest at the stop
// (run_arrives), or, for a part that ends moving, at the end of the stretch without coming to
// rest before it, with its end speed inside the last point's speed window (within tol_ms).
struct EndCheck {
  bool moving = false;
  double min_ms = 0.0, max_ms = 0.0, tol_ms = 0.0;
  bool reaches_end(const physics::SimulationResult& sim) const;
  bool operator()(const physics::SimulationResult& sim) const;
};

// A passing point inside a part, as the part's engine sees it.
struct PartPoint {
  int index = 0;                            // into the journey's windows
  double s_m = 0.0;                         // position in the part
  int stage = 0;                            // grid stage of the price change and of the speed band
  double earliest_s = 0.0, latest_s = 0.0;  // relative to the part's departure
};

// What one part's search gives.
struct PartOutcome {
  LambdaRun run;
  bool met = false;    // the part's windows and its arrival hold (as far as its search knows)
  bool holds = false;  // every window of the part and its arrival hold on the run's re-simulation
  int evaluations = 0;
  std::vector<PartPoint> points;
  std::vector<std::string> notes;
  // Price of each stretch between consecutive timing points of the part (J/s), first to last.
  std::vector<double> stretch_lambda_J_per_s;
  // Per passing point: +1 its latest bound binds, -1 its earliest, 0 it does not bind.
  std::vector<int> binding_sign;
  // How far inside its bound a binding passing point may pass.
  double binding_slack_s = 0.0;
};

// The part's least-energy run from start (target_s after the departure at the latest; not
// before earliest_arrival_s) meeting the windows of points. arrival_free: the part's latest
// arrival lies beyond target_s (the slowest run the grid solves reliably), so a run that
// arrives earlier is inside its window: where no price meets target_s, the latest early run
// is taken. Throws TimeRequestError (e.g. LongTimeError) when the plain search for the arrival
// does. by_labels: the part is searched by its time-expanded label search instead
// (dp/timing_label_search.hpp, the last resort where the price searches missed a window), its
// run moved onto its windows and descended on its switches.
PartOutcome solve_part(const SectionEngine& engine, const StartState& start, const EndCheck& end,
                       double target_s, double earliest_arrival_s, std::vector<PartPoint> points,
                       const std::vector<TimingWindow>& windows,
                       const TimingJourneyOptions& options, bool arrival_free = false,
                       bool by_labels = false);

}  // namespace ecorail::dp::timing
