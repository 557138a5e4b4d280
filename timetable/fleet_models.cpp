#include "timetable/fleet_models.hpp"

#include <stdexcept>

namespace ecorail::timetable {

FleetModels::FleetModels(const physics::Trip& trip, const FleetProblem& problem,
                         const EnergyModelOptions& options)
    : trip_(trip), problem_(problem), options_(options), overlap_(trip) {
  std::string why;
  if (!problem_.IsValid(&why) || !options_.IsValid(&why)) throw std::invalid_argument(why);
  if (options_.model != EnergyModel::Overlap) {
    const std::vector<double> none;
    profile_ = std::make_unique<PowerProfile>(
        trip_, options_.ticks_per_second(),
        options_.model == EnergyModel::Sections ? options_.section_boundaries_m : none);
  }
}

std::unique_ptr<PowerBalance> FleetModels::make_balance() const {
  if (!profile_) throw std::logic_error("the overlap model has no power balance");
  std::vector<const PowerProfile*> profiles(problem_.trains, profile_.get());
  return std::make_unique<PowerBalance>(profiles, problem_.span_s + trip_.arrival_s() + 2.0);
}

FleetEvaluation FleetModels::evaluate(const std::vector<int>& departures_s) const {
  const std::string why = departures_problem(problem_, departures_s);
  if (!why.empty()) throw std::invalid_argument(why);
  FleetEvaluation out;
  out.model = options_.model;
  out.overlap = options_.overlap;
  out.departures_s = departures_s;
  if (options_.model == EnergyModel::Overlap) {
    out.total = overlap_.evaluate(departures_s, options_.overlap);
    for (std::size_t k = 0; k < departures_s.size(); ++k) {
      out.per_train.push_back({overlap_.trip_traction_J(), overlap_.trip_regen_J(),
                               overlap_.train_used_J(departures_s, k, options_.overlap)});
    }
    return out;
  }
  out.time_step_s = options_.time_step_s;
  auto balance = make_balance();
  balance->place_all(departures_s);
  out.total = balance->energy();
  out.per_train = balance->train_energy();
  out.per_section = balance->section_energy();
  return out;
}

}  // namespace ecorail::timetable
