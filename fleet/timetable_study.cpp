#include "fleet/timetable_study.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "data/route_builder.hpp"
#include "energy/network_model.hpp"
#include "energy/power_flow_model.hpp"

namespace ecorail::fleet {

std::string run_problem(const energy::EnergyModelOptions& o, double length_m, double line_length_m,
                        std::string* field) {
  auto m = [](double x) { return std::to_string(static_cast<long long>(std::llround(x))); };
  for (double b : o.section_boundaries_m) {
    if (b >= length_m) {
      if (field) *field = "section_boundaries_m";
      return "supply-section boundaries inside the run (0 to " + m(length_m) + " m); got " + m(b) +
             " m";
    }
  }
  if (o.power_supply) {
    for (const power::Substation& s : o.power_supply->substations) {
      if (s.position_m < 0.0 || s.position_m > line_length_m) {
        if (field) *field = "power_supply";
        return "substation '" + s.name + "' at " + m(s.position_m) +
               " m: expected a position on the line (0 to " + m(line_length_m) + " m)";
      }
    }
    for (const power::ConductorSegment& c : o.power_supply->conductors) {
      if (c.from_m < 0.0 || c.from_m >= line_length_m) {
        if (field) *field = "power_supply";
        return "conductor segment from " + m(c.from_m) + " m: expected a start on the line (0 to " +
               m(line_length_m) + " m)";
      }
    }
  }
  return "";
}

bool StudyOptimiseOptions::IsValid(std::string* error) const {
  return headways.IsValid(error);
}

TimetableStudy::TimetableStudy(const TimetableStudySetup& setup)
    : problem_(setup.problem), line_(setup.line), model_options_(setup.model), stops_(setup.stops) {
  std::string why;
  if (!problem_.IsValid(&why)) throw std::invalid_argument(why);
  if (stops_.size() < 2) throw std::invalid_argument("stops: expected at least two");
  model_options_.traction_efficiency = setup.train.traction_efficiency;
  dp::SectionLibraryOptions lib_options;
  lib_options.engine = setup.engine;
  library_ = std::make_shared<dp::SectionLibrary>(
      setup.train, data::build_routes(setup.line, stops_, setup.train), lib_options);
  double pos = 0.0;
  positions_m_.push_back(0.0);
  for (std::size_t i = 0; i < library_->size(); ++i)
    positions_m_.push_back(pos += library_->route(i).length_m());
  std::string field;
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < setup.line.stations.size(); ++i) {
    const double k = setup.line.stations[i].km_post_m;
    lo = i == 0 ? k : std::min(lo, k);
    hi = i == 0 ? k : std::max(hi, k);
  }
  why = run_problem(model_options_, run_length_m(), hi - lo, &field);
  if (!why.empty()) throw std::invalid_argument(field + ": " + why);
  dwell_s_ = setup.dwell_s;
  journey_.engine = lib_options.engine;
  journey_.measure_marginals = false;
  make_pattern_and_model(nullptr);
}

void TimetableStudy::make_pattern_and_model(const TimetableStudy* start) {
  if (start != nullptr && start->problem_.trip_time_s == problem_.trip_time_s) {
    initial_pattern_ = start->initial_pattern_;
  } else {
    const std::vector<double> dwells(stops_.size() - 2, dwell_s_);
    initial_pattern_ = optimal_split_pattern(*library_, dwells, problem_.trip_time_s, journey_);
  }
  pattern_ = initial_pattern_;
  model_ = make_model(pattern_.trip, problem_, model_options_);
}

std::unique_ptr<TimetableStudy> TimetableStudy::with_problem(const FleetProblem& problem) const {
  std::string why;
  if (!problem.IsValid(&why)) throw std::invalid_argument(why);
  std::unique_ptr<TimetableStudy> s(new TimetableStudy());
  s->problem_ = problem;
  s->line_ = line_;
  s->model_options_ = model_options_;
  s->stops_ = stops_;
  s->positions_m_ = positions_m_;
  s->library_ = library_;
  s->dwell_s_ = dwell_s_;
  s->journey_ = journey_;
  s->make_pattern_and_model(this);
  return s;
}

StudyEvaluation TimetableStudy::evaluate(const std::vector<int>& departures_s) const {
  const std::string why = departures_problem(problem_, departures_s);
  if (!why.empty()) throw std::invalid_argument(why);
  StudyEvaluation out;
  out.evaluation = model_->evaluate(departures_s);
  if (out.evaluation.network && out.evaluation.network->unsolved_instants > 0)
    throw std::runtime_error("the load flow found no solution at " +
                             std::to_string(out.evaluation.network->unsolved_instants) +
                             " instants; nothing written");
  // The same day with every train burning its regenerated energy: what reuse saves.
  out.substation_without_reuse_J = model_->substation_without_reuse_J(departures_s);
  return out;
}

StudyOptimisation TimetableStudy::optimise(const StudyOptimiseOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  StudyOptimisation out;
  if (!options.pattern && !options.per_train_patterns) {
    out.result = optimise_headways(*model_, problem_, options.headways);
  } else {
    PatternSearchOptions po;
    po.headways = options.headways;
    po.per_train_patterns = options.per_train_patterns;
    po.progress = options.pattern_progress;
    PatternSearchResult r = optimise_pattern(*library_, problem_, model_options_, pattern_, po);
    if (!r.per_train.empty()) {
      per_train_patterns_ = r.per_train;
      per_train_trips_ = r.per_train_trips;
    }
    pattern_ = r.pattern;
    model_ = model_->with_trip(pattern_.trip);
    out.result = r.timetable;
    out.pattern_search = std::move(r);
  }
  return out;
}

bool TimetableStudy::has_power_trace() const {
  return dynamic_cast<const energy::PowerFlowModel*>(model_.get()) != nullptr;
}

bool TimetableStudy::has_network() const {
  return dynamic_cast<const energy::NetworkModel*>(model_.get()) != nullptr;
}

energy::PowerBalance::Trace TimetableStudy::power_trace(const std::vector<int>& departures_s,
                                                        double from_s, double to_s) const {
  const auto* flow = dynamic_cast<const energy::PowerFlowModel*>(model_.get());
  if (!flow)
    throw std::invalid_argument("the " + std::string(model_->name()) +
                                " model has no power-flow trace");
  // Per-train patterns: each train's own profile (kept alive here while the trace is made).
  std::vector<std::unique_ptr<energy::PowerProfile>> own;
  std::vector<const energy::PowerProfile*> profiles;
  for (const physics::Trip& trip : per_train_trips_) {
    own.push_back(energy::make_profile(trip, model_options_));
    profiles.push_back(own.back().get());
  }
  auto balance = profiles.empty() ? flow->make_power_balance() : flow->make_power_balance(profiles);
  balance->place_all(departures_s);
  return balance->trace(from_s, to_s);
}

power::SubstationTrace TimetableStudy::substation_trace(const std::vector<int>& departures_s,
                                                        double from_s, double to_s) const {
  const auto* net = dynamic_cast<const energy::NetworkModel*>(model_.get());
  if (!net) throw std::invalid_argument("only the network model has substations");
  return power::substation_trace(net->network_setup(), departures_s, from_s, to_s);
}

power::LoadFlowResult TimetableStudy::load_flow_at(const std::vector<int>& departures_s, double t_s,
                                                   std::vector<int>* trains) const {
  const auto* net = dynamic_cast<const energy::NetworkModel*>(model_.get());
  if (!net) throw std::invalid_argument("only the network model has line voltages");
  return power::load_flow_at(net->network_setup(), departures_s, t_s, trains);
}

}  // namespace ecorail::fleet
