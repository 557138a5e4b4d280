#include "energy/power_flow_model.hpp"

#include <algorithm>
#include <stdexcept>

#include "energy/pair_bound.hpp"
#include "energy/window_bound.hpp"
#include "energy/window_refine.hpp"
#include "energy/window_span_optimum.hpp"

namespace ecorail::energy {

std::unique_ptr<PowerProfile> make_profile(const physics::Trip& trip,
                                           const EnergyModelOptions& options) {
  const std::vector<double> none;
  return std::make_unique<PowerProfile>(
      trip, options.ticks_per_second(),
      options.model == "sections" ? options.section_boundaries_m : none);
}

namespace {

// The power balance behind the FleetBalance interface: the objective is the substation energy,
// traction (fixed under moves) less the used energy, so a move changes it by minus the change of
// the used energy, exactly.
class PowerFlowBalance : public FleetBalance {
 public:
  explicit PowerFlowBalance(const PowerFlowModel& model)
      : model_(model), balance_(model.make_power_balance()), own_(model.limits().trains) {}
  int trains() const override { return balance_->trains(); }
  void place_all(const std::vector<int>& departures_s) override {
    balance_->place_all(departures_s);
  }
  MicroJoules move(int train, int departure_s) override {
    return -balance_->move(train, departure_s);
  }
  MicroJoules substation() const override { return balance_->traction() - balance_->used(); }
  MicroJoules change_if_moved(int train, int, int departure_s) override {
    return -balance_->used_change_if_moved(train, departure_s);
  }
  void substation_at(int train, int, const std::vector<int>& departures_s,
                     std::vector<MicroJoules>& substation_J) override {
    balance_->used_at(train, departures_s, substation_J);
    for (MicroJoules& s : substation_J) s = balance_->traction() - s;
  }
  MicroJoules substation_change_if(int train, const physics::Trip& trip) const override {
    return balance_->substation_change_if(train, *make_profile(trip, model_.options()));
  }
  void set_trip(int train, const physics::Trip& trip) override {
    std::unique_ptr<PowerProfile> profile = make_profile(trip, model_.options());
    balance_->set_profile(train, profile.get());
    own_[train] = std::move(profile);
  }
  FleetEvaluation evaluation() const override { return model_.evaluation_of(*balance_); }

 private:
  const PowerFlowModel& model_;
  std::unique_ptr<PowerBalance> balance_;
  std::vector<std::unique_ptr<PowerProfile>> own_;  // trains with a trip of their own
};

// One power balance for the whole pattern search: a candidate trip is a new profile laid under
// every train, not a new balance (a day's balance is about 100 MB).
class PowerFlowPricer : public TripPricer {
 public:
  PowerFlowPricer(const PowerFlowModel& model, const std::vector<int>& departures_s)
      : model_(model), current_(make_profile(model.trip(), model.options())) {
    balance_ = model.make_power_balance(
        std::vector<const PowerProfile*>(model.limits().trains, current_.get()));
    balance_->place_all(departures_s);
  }
  std::optional<double> substation_J(const physics::Trip& trip) override {
    // The balance lets go of the previous candidate before it is freed.
    std::unique_ptr<PowerProfile> next = make_profile(trip, model_.options());
    lay(next.get());
    candidate_ = std::move(next);
    return balance_->energy().substation_J();
  }
  void accept() override { current_ = std::move(candidate_); }

 private:
  void lay(const PowerProfile* profile) { balance_->set_profile_all(profile); }
  const PowerFlowModel& model_;
  std::unique_ptr<PowerProfile> current_, candidate_;
  std::unique_ptr<PowerBalance> balance_;
};

}  // namespace

PowerFlowModel::PowerFlowModel(const physics::Trip& trip, const FleetLimits& limits,
                               const EnergyModelOptions& options)
    : FleetEnergyModel(trip, limits, options) {
  // The profile's bins (at most one per bin of the trip) and the balance's traction and regen
  // per section and bin of the day.
  const double sections = static_cast<double>(options.section_boundaries_m.size()) + 1.0;
  check_memory(trip_bins() * sizeof(PowerBin) + 2.0 * sections * horizon_bins() * 8.0,
               "the power balance of " + std::to_string(limits.trains) + " trains");
  profile_ = make_profile(trip, options);
}

std::unique_ptr<PowerBalance> PowerFlowModel::make_power_balance() const {
  return make_power_balance(std::vector<const PowerProfile*>(limits().trains, profile_.get()));
}

std::unique_ptr<PowerBalance> PowerFlowModel::make_power_balance(
    std::vector<const PowerProfile*> profiles) const {
  if (profiles.size() != static_cast<std::size_t>(limits().trains))
    throw std::invalid_argument("one power profile per train expected");
  // Every pattern keeps the trip time, so the pattern's arrival bounds every train's.
  return std::make_unique<PowerBalance>(std::move(profiles), horizon_s());
}

FleetEvaluation PowerFlowModel::evaluation_of(const PowerBalance& balance) const {
  FleetEvaluation out;
  out.model = name();
  out.time_step_s = options().time_step_s;
  for (int k = 0; k < balance.trains(); ++k) out.departures_s.push_back(balance.departure_s(k));
  out.total = balance.energy();
  out.per_train = balance.train_energy();
  out.per_section = balance.section_energy();
  return out;
}

FleetEvaluation PowerFlowModel::evaluate(const std::vector<int>& departures_s) const {
  check_departures(departures_s);
  auto balance = make_power_balance();
  balance->place_all(departures_s);
  return evaluation_of(*balance);
}

std::unique_ptr<FleetEnergyModel> PowerFlowModel::rebuilt(const physics::Trip& trip,
                                                          const FleetLimits& limits,
                                                          const EnergyModelOptions& options) const {
  return std::make_unique<PowerFlowModel>(trip, limits, options);
}

std::unique_ptr<FleetBalance> PowerFlowModel::make_balance(int) const {
  return std::make_unique<PowerFlowBalance>(*this);
}

std::vector<double> PowerFlowModel::two_train_values_J(int lo_s, int hi_s, int) const {
  PowerBalance two({profile_.get(), profile_.get()}, hi_s + trip().arrival_s() + 2.0);
  std::vector<double> out;
  for (int h = lo_s; h <= hi_s; ++h) {
    two.place_all({0, h});
    out.push_back(to_joules(two.used()));
  }
  return out;
}

FleetLowerBound PowerFlowModel::lower_bound(const std::function<bool()>& stop) const {
  // No timetable uses more than is regenerated, nor more than is drawn.
  const PairBound pair = used_regen_bound(*profile_, limits());
  const MicroJoules trains = limits().trains;
  FleetLowerBound b;
  b.name = "pair bound";
  b.used_regen_J = std::min({pair.bound_used_J, to_joules(trains * profile_->regen_total()),
                             to_joules(trains * profile_->traction_total())});
  // One supply section and one headway class: the window bound, far tighter where it applies.
  WindowBoundOptions o;
  o.stop = stop;
  const WindowBound window = window_used_regen_bound(*profile_, limits(), o);
  if (window.applicable && window.bound_used_J < b.used_regen_J) {
    b.used_regen_J = window.bound_used_J;
    b.name = "window bound";
  }
  if (window.stopped) b.name += ", " + window_cut_short(window);
  return b;
}

std::vector<std::vector<int>> PowerFlowModel::relaxation_maximisers_s(
    const std::function<bool()>& stop) const {
  WindowBoundOptions o;
  o.stop = stop;
  return window_core_maximisers(*profile_, limits(), o);
}

std::vector<int> PowerFlowModel::refined_headways_s(const std::vector<int>& headways_s, int threads,
                                                    double time_limit_s) const {
  WindowRefineOptions o;
  o.threads = threads;
  o.time_limit_s = time_limit_s;
  const WindowRefineSummary r = window_refine(*profile_, limits(), headways_s, o);
  if (!r.applicable || r.headways_s == headways_s) return {};
  return r.headways_s;
}

ExactPartOptimum PowerFlowModel::exact_part_optimum(const std::vector<int>& incumbent_s,
                                                    int threads, double time_limit_s) const {
  WindowSpanOptions o;
  o.threads = threads;
  o.time_limit_s = time_limit_s;
  const WindowSpanSummary r = window_span_optimum(*profile_, limits(), incumbent_s, o);
  ExactPartOptimum out;
  out.wall_s = r.wall_s;
  if (!r.complete()) {
    out.why_not = r.why_not;
    return out;
  }
  out.proven = true;
  out.part = "every headway in " + std::to_string(r.lowest_headway_s) + "-" +
             std::to_string(r.highest_headway_s) + " s";
  if (r.improved) out.headways_s = r.headways_s;
  out.used_regen_J = r.used_J;
  out.relaxed_bound_J = r.dual_bound_J;
  return out;
}

double PowerFlowModel::pair_sum_J(const std::vector<int>& departures_s) const {
  return energy::pair_sum_J(*profile_, departures_s);
}

std::unique_ptr<TripPricer> PowerFlowModel::make_trip_pricer(const std::vector<int>& departures_s,
                                                             double, int) const {
  return std::make_unique<PowerFlowPricer>(*this, departures_s);
}

}  // namespace ecorail::energy
