// FleetEnergyModel: the one interface through which the fleet searches (fleet/) see an energy
// model. A model prices a fleet whose trains all run one trip (departing at whole seconds within
// FleetLimits): evaluate() gives the full account of one timetable; make_balance() an
// incremental balance that moves one train at a time and returns the exact change of the
// substation energy; lower_bound() a proven lower bound over every timetable within the limits;
// search_plan() how a heuristic search should spend its moves on it (a load flow per bin costs
// far more than a sum per bin). Optional capabilities answer "none" by default: an exact
// decomposition of the used energy over headways (the overlap models: the search then solves a
// DP instead of annealing), per-train trips in the balance, the substation energy without any
// reuse, the maximisers of a relaxation (starts for the search). Models are made by name in
// energy/model_registry.hpp; a new model implements this class in its own files and adds one line
// there.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "energy/fleet_energy.hpp"
#include "energy/model_options.hpp"
#include "physics/trip.hpp"
#include "power/micro_joules.hpp"
#include "power/network_evaluation.hpp"

namespace ecorail::energy {

using power::MicroJoules;
using power::to_joules;

struct FleetEvaluation {
  std::string model;            // the model's registered name
  std::string overlap_variant;  // overlap model: "ahead" or "either"; empty otherwise
  double time_step_s = 0.0;     // time-binned models; 0 for exact intervals (overlap)
  std::vector<int> departures_s;
  FleetEnergy total;
  std::vector<FleetEnergy> per_train;    // used energy attributed to the braking train
  std::vector<FleetEnergy> per_section;  // sections model (one entry for power-flow)
  // Network model: the full account; total.used_regen_J is then traction at the wheel less the
  // substation energy (so total.substation_J() is the substations' energy), the regenerated
  // energy that entered the line is network->used_regen_J.
  std::shared_ptr<const power::NetworkEvaluation> network;
  // The regenerated energy the fleet used: for the network model the energy that entered the
  // line.
  double used_regen_J() const { return network ? network->used_regen_J : total.used_regen_J; }
};

// An incremental balance of a fleet on one grid: trains placed and moved one at a time, totals
// kept as integers so that any sequence of moves gives exactly a fresh placement's totals.
class FleetBalance {
 public:
  virtual ~FleetBalance() = default;
  virtual int trains() const = 0;
  // Lays every train at its departure (whole seconds >= 0), replacing any earlier placement.
  virtual void place_all(const std::vector<int>& departures_s) = 0;
  // Moves one placed train; returns the change of the substation energy (< 0: better).
  virtual MicroJoules move(int train, int departure_s) = 0;
  virtual MicroJoules substation() const = 0;
  // The substation energy with `train` (placed at placed_at_s) at each of `departures_s`, the
  // rest as placed, into substation_J; the train is left at placed_at_s. Default: a move to
  // each and back; a model may price them without moving (the polish tries a window of
  // departures per train).
  virtual void substation_at(int train, int placed_at_s, const std::vector<int>& departures_s,
                             std::vector<MicroJoules>& substation_J);
  // The change of the substation energy that move(train, departure_s) would make, the train
  // left at placed_at_s (the annealing's proposals, most of them rejected). Default: the move
  // and its undo.
  virtual MicroJoules change_if_moved(int train, int placed_at_s, int departure_s);
  // Bins the model found no solution for (a balance with any is never taken as a result).
  virtual long unsolved_bins() const { return 0; }
  // Per-train trips (FleetEnergyModel::per_train_trips()): the change of the substation energy
  // that giving `train` its own trip (departing at 0, same grid) would make, without changing
  // anything (candidates may be priced in parallel); the change itself; the account.
  virtual MicroJoules substation_change_if(int train, const physics::Trip& trip) const;
  virtual void set_trip(int train, const physics::Trip& trip);
  virtual FleetEvaluation evaluation() const;
};

// A proven lower bound on the substation energy of every timetable within the model's limits,
// in the form the model proves it: exactly one of the two is finite.
struct FleetLowerBound {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // An upper bound on the regenerated energy any timetable uses (substation = traction - used;
  // the traction is the same for every timetable).
  double used_regen_J = kNone;
  // A lower bound on the substation energy (the network model: substation plus curtailed
  // traction, which its load flow may trade for each other).
  double substation_J = kNone;
  std::string name;  // e.g. "pair bound"
  bool exists() const { return used_regen_J == used_regen_J || substation_J == substation_J; }
};

// The best timetable of one part of the domain, proven by an exact search there
// (FleetEnergyModel::exact_part_optimum): no timetable of that part uses more regenerated energy.
// It says nothing of the rest of the domain.
struct ExactPartOptimum {
  bool proven = false;
  std::string why_not;  // when not proven
  std::string part;     // which timetables, e.g. "every headway in 522-660 s"
  // Better than the incumbent given; empty when the incumbent is the part's optimum.
  std::vector<int> headways_s;
  double used_regen_J = 0.0;     // the part's optimum
  double relaxed_bound_J = 0.0;  // the relaxation that pruned the search (above used_regen_J)
  double wall_s = 0.0;
};

// The used energy as a function of the headways alone, when the model has one:
// sum_k value(h_k) - sum_k penalty(h_k, h_k+1) (no penalty: separable).
struct HeadwayDecomposition {
  std::function<double(int)> value_J;
  std::function<double(int, int)> penalty_J;  // empty: separable
  std::string what;                           // e.g. "overlap, train ahead"
};

// How the heuristic headway search spends its moves on a model (fleet/headway_optimiser.hpp).
struct SearchPlan {
  std::uint64_t draw_salt = 0;   // counter-based draws of this plan (fleet/search_support.hpp)
  long draw_offset = 0;          // first move counter of the annealing's proposals
  int temperature_samples = 64;  // proposals priced to set the start temperature
  bool samples_within_move_window = false;
  long time_check_every = 1024;             // moves between clock reads (a power of two)
  double anneal_share_of_time_limit = 0.8;  // the rest is the polish's
  bool run_without_restarts = false;        // restarts 0: one run of no moves per start
  bool two_train_values_on_search_grid = false;
  bool price_starts = true;      // report the best start's used energy
  bool polish_every_run = true;  // else only the best annealed timetable
  struct Polish {
    // Grid: the larger of this step and the model's (0: the model's; < 0: the annealing's).
    double step_s = 0.0;
    int window_s = -1;  // +-departures tried; < 0: the options' window, else at most it
    int sweeps = 50;
    bool skip_on_search_grid = false;  // skipped when the grid is the annealing's
  };
  std::vector<Polish> polish;
  std::string method_note;  // said after "annealing and polish" in the summary's method
};

// Prices trips laid under every train at fixed departures (the pattern search).
class TripPricer {
 public:
  virtual ~TripPricer() = default;
  // The substation energy (J) with every train on `trip`, or nullopt when the model screens it
  // out (no better than the current trip on a coarse grid) or finds no solution.
  virtual std::optional<double> substation_J(const physics::Trip& trip) = 0;
  // The trip priced last becomes the current one.
  virtual void accept() = 0;
  // Candidates evaluated in full for the whole fleet (0 for incremental models).
  int full_evaluations() const { return full_evaluations_; }

 protected:
  int full_evaluations_ = 0;
};

class FleetEnergyModel {
 public:
  // trip departs at 0; std::invalid_argument when the options or limits are not valid.
  FleetEnergyModel(const physics::Trip& trip, const FleetLimits& limits,
                   const EnergyModelOptions& options);
  virtual ~FleetEnergyModel() = default;

  virtual std::string_view name() const = 0;
  const physics::Trip& trip() const { return trip_; }
  const FleetLimits& limits() const { return limits_; }
  const EnergyModelOptions& options() const { return options_; }
  // The clock time past which no train runs.
  double horizon_s() const { return limits_.span_s + trip_.arrival_s() + 10.0; }

  // The account of one timetable; departures must keep the limits (std::invalid_argument).
  virtual FleetEvaluation evaluate(const std::vector<int>& departures_s) const = 0;
  // The same model for another trip (a candidate pattern), fleet or options (a coarser grid).
  virtual std::unique_ptr<FleetEnergyModel> rebuilt(const physics::Trip& trip,
                                                    const FleetLimits& limits,
                                                    const EnergyModelOptions& options) const = 0;
  std::unique_ptr<FleetEnergyModel> with_trip(const physics::Trip& trip) const;
  // On the grid of max(step_s, the model's step).
  std::unique_ptr<FleetEnergyModel> on_grid(double step_s) const;

  // An empty incremental balance for every train (nullptr: the model has none).
  virtual std::unique_ptr<FleetBalance> make_balance(int threads = 0) const;
  // Whether its balances take a trip per train (FleetBalance::set_trip).
  virtual bool per_train_trips() const { return false; }
  virtual std::optional<HeadwayDecomposition> headway_decomposition() const;
  // Value of two trains h apart alone, for h = lo_s..hi_s: the larger the better (used energy,
  // or minus the substation energy); the search's two-train approximation.
  virtual std::vector<double> two_train_values_J(int lo_s, int hi_s, int threads) const;
  // `stop` (may be empty; asked from any thread) cuts a costly bound short: the model then
  // returns the best bound it has by then, valid still and named so (a time limit keeps). The
  // search may run it on a thread of its own while it calls the model's other const members
  // (fleet/headway_optimiser.cpp, without a time limit), so it must not change the model.
  virtual FleetLowerBound lower_bound(const std::function<bool()>& stop = {}) const;
  // A cheaper model of the same trip and fleet whose good timetables are near this one's: the
  // search builds its structured starts on it when it does not price starts on this model
  // (SearchPlan::price_starts false). None by default; the network model: the power-flow model.
  virtual std::unique_ptr<FleetEnergyModel> start_proxy() const { return nullptr; }
  // Headway sequences that maximise a relaxation of the problem (one per multiplier tried; their
  // sums miss the span): starts for a search (fleet/relaxed_start.hpp). None by default; costs
  // a DP, so the search asks only when it builds that start. `stop` as for lower_bound (the
  // maximisers found by then).
  virtual std::vector<std::vector<int>> relaxation_maximisers_s(
      const std::function<bool()>& /*stop*/ = {}) const {
    return {};
  }
  // A sequence of the same span that uses more regenerated energy than `headways_s`, found near
  // it by an exact search the model can run on part of its domain (the power-flow model: the
  // window terms' DP, energy/window_refine.hpp); empty when it has none, does not apply or finds
  // nothing better. time_limit_s (0: none) bounds it between its passes.
  virtual std::vector<int> refined_headways_s(const std::vector<int>& headways_s, int threads,
                                              double time_limit_s) const;
  // The optimum of the part of the domain where the model has an exact search (the power-flow
  // model with one supply section: every headway in the core, energy/window_span_optimum.hpp),
  // the incumbent's headways pruning it. Not proven by default, when it does not apply or when
  // time_limit_s (0: none) stops it.
  virtual ExactPartOptimum exact_part_optimum(const std::vector<int>& incumbent_s, int threads,
                                              double time_limit_s) const;
  // (bound - result) / result's substation energy, in the bound's own form.
  double gap_fraction(const FleetEvaluation& result, const FleetLowerBound& bound) const;
  // What no bound built on pairs of trains can come below for this timetable (0: not known).
  virtual double pair_sum_J(const std::vector<int>& departures_s) const;
  // The substation energy of the same timetable with no regenerated energy used (nullopt when
  // the model does not report it).
  virtual std::optional<double> substation_without_reuse_J(
      const std::vector<int>& departures_s) const;
  virtual SearchPlan search_plan() const;
  // Prices candidate trips for every train at these departures, screening on the grid of
  // screen_step_s first when the model is costly (default: a fresh evaluation of each).
  virtual std::unique_ptr<TripPricer> make_trip_pricer(const std::vector<int>& departures_s,
                                                       double screen_step_s, int threads) const;

 protected:
  // std::invalid_argument unless the departures keep the limits.
  void check_departures(const std::vector<int>& departures_s) const;
  // Bins of the time grid from the first departure to the horizon, and of one trip.
  double horizon_bins() const;
  double trip_bins() const;
  // dp::ResourceLimitError, before anything is allocated, when `bytes` exceed a quarter of the
  // memory this process can have (dp/resource_estimate.hpp): a finer --step than the machine holds.
  void check_memory(double bytes, const std::string& what) const;

 private:
  physics::Trip trip_;
  FleetLimits limits_;
  EnergyModelOptions options_;
};

}  // namespace ecorail::energy
