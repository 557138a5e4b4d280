// TimetableStudy: what the `timetable evaluate|optimise` commands compute, as one object a
// program or a binding can drive. Built from a line, a train, the stops of the run, a dwell for
// every intermediate stop, the fleet problem and the energy model's options: it solves the
// section library of the run, the pattern (the optimal split of the trip's running time over
// the sections) and builds the named energy model (energy/model_registry.hpp). evaluate() gives
// a timetable's account (and, when the model reports it, the substation energy of the same day
// without any reuse); optimise() runs the headway or the pattern search and keeps the pattern it
// found. Plots' data (the power-flow trace, the substations' power, the load flow at an instant)
// come from the model when it has them. with_problem() gives the study of another fleet problem
// on the same run, sharing the section library (its solves and frontiers are not made again).
// optimise() returns its search's summary whatever the termination: a FAILURE (no timetable the
// model found a solution for) is flagged there, IsSolutionUsable() false, and is never a result
// to write.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "data/line.hpp"
#include "dp/journey.hpp"
#include "dp/section_engine.hpp"
#include "dp/section_library.hpp"
#include "energy/fleet_energy_model.hpp"
#include "energy/power_flow_balance.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/headway_optimiser.hpp"
#include "fleet/pattern_search.hpp"
#include "physics/train.hpp"
#include "power/load_flow.hpp"
#include "power/network_evaluation.hpp"

namespace ecorail::fleet {

struct TimetableStudySetup {
  data::Line line;
  physics::Train train;
  std::vector<std::string> stops;  // the run's stops in the order of travel (at least two)
  dp::EngineOptions engine;
  double dwell_s = 30.0;  // at every intermediate stop
  FleetProblem problem;
  // The train's traction efficiency is the network model's.
  energy::EnergyModelOptions model;
};

struct StudyEvaluation {
  FleetEvaluation evaluation;
  std::optional<double> substation_without_reuse_J;  // when the model reports it
};

struct StudyOptimiseOptions {
  HeadwayOptimiserOptions headways;
  bool pattern = false;             // dwells and running times too (pattern search)
  bool per_train_patterns = false;  // implies pattern
  std::function<void(const PatternProgress&)> pattern_progress;
  bool IsValid(std::string* error) const;
};

struct StudyOptimisation {
  HeadwayOptimiserResult result;
  // Pattern search only (its timetable is `result`).
  std::optional<PatternSearchResult> pattern_search;
};

class TimetableStudy {
 public:
  // dp::InfeasibleTimeError when the trip time leaves less than the flat-out runs after the
  // dwells; std::invalid_argument for options that do not fit the run (RunProblem).
  explicit TimetableStudy(const TimetableStudySetup& setup);
  // The study of problem on the same line, train, stops, dwell and model options: the section
  // library is shared, the pattern is the optimal split for problem's trip time (the one this
  // study started from when the trip time is the same; a pattern or per-train patterns found by
  // optimise() are not carried over), the model is built for problem. Errors as the
  // constructor's.
  std::unique_ptr<TimetableStudy> with_problem(const FleetProblem& problem) const;

  const FleetProblem& problem() const { return problem_; }
  const energy::EnergyModelOptions& model_options() const { return model_options_; }
  const energy::FleetEnergyModel& model() const { return *model_; }
  const std::vector<std::string>& stops() const { return stops_; }
  const data::Line& line() const { return line_; }  // its stations locate the GTFS stops
  const std::vector<double>& positions_m() const { return positions_m_; }  // along the run
  double run_length_m() const { return positions_m_.back(); }
  const dp::SectionLibrary& library() const { return *library_; }
  const PatternTrip& pattern() const { return pattern_; }
  // After an optimisation with per-train patterns: train k's pattern and trip; else empty.
  const std::vector<FleetPattern>& per_train_patterns() const { return per_train_patterns_; }
  const std::vector<physics::Trip>& per_train_trips() const { return per_train_trips_; }

  StudyEvaluation evaluate(const std::vector<int>& departures_s) const;
  // Keeps the pattern (and per-train patterns) the search found for the outputs. The result's
  // summary says how the search ended (std::invalid_argument only for options that are not
  // valid).
  StudyOptimisation optimise(const StudyOptimiseOptions& options);

  // Plots' data over [from_s, to_s) of the clock. The power-flow trace needs a model with a
  // power balance (power-flow, sections), the others the network model.
  bool has_power_trace() const;
  bool has_network() const;
  energy::PowerBalance::Trace power_trace(const std::vector<int>& departures_s, double from_s,
                                          double to_s) const;
  power::SubstationTrace substation_trace(const std::vector<int>& departures_s, double from_s,
                                          double to_s) const;
  // The load flow at clock time t_s; trains receives each load's train number.
  power::LoadFlowResult load_flow_at(const std::vector<int>& departures_s, double t_s,
                                     std::vector<int>* trains) const;

 private:
  TimetableStudy() = default;
  // The pattern for problem_'s trip time (reused from start when it has that trip time) and the
  // model for problem_.
  void make_pattern_and_model(const TimetableStudy* start);

  FleetProblem problem_;
  data::Line line_;
  energy::EnergyModelOptions model_options_;
  std::vector<std::string> stops_;
  std::vector<double> positions_m_;
  std::shared_ptr<dp::SectionLibrary> library_;  // shared with the studies of with_problem
  double dwell_s_ = 30.0;
  dp::JourneyOptions journey_;   // of the pattern's optimal split
  PatternTrip initial_pattern_;  // the optimal split the study started from
  PatternTrip pattern_;
  std::vector<FleetPattern> per_train_patterns_;
  std::vector<physics::Trip> per_train_trips_;
  std::unique_ptr<energy::FleetEnergyModel> model_;
};

// Why the model options do not fit a run of run_length_m on a line of line_length_m ("" when
// they do): a supply-section boundary at or beyond the run's end, a substation or the start of
// a conductor segment beyond the line's end (supply positions are along the run from its first
// station; the supply may extend past the run, not past the line). *field names the option:
// "section_boundaries_m" or "power_supply".
std::string run_problem(const energy::EnergyModelOptions& options, double run_length_m,
                        double line_length_m, std::string* field);

}  // namespace ecorail::fleet
