// NetworkBalance: the fleet on the traction power network (the network model), incremental.
// Every bin of the time grid is one instant of the DC load flow (power/load_flow.hpp) with the
// trains on the line at that bin; the balance keeps, per bin, the substations' energy, the line
// losses and the regenerated and traction energy curtailed, rounded to micro-joules, and their
// totals as integers. Moving one train re-solves only the bins it touches (its old and new
// runs), so any sequence of moves gives exactly the totals of a fresh placement. place_all
// solves every bin, spread over OpenMP threads; the integer totals do not depend on the thread
// count. The objective of the optimiser is the substation energy (substation()).
#pragma once

#include <memory>
#include <vector>

#include "power/load_flow.hpp"
#include "power/micro_joules.hpp"
#include "power/network_profile.hpp"

namespace ecorail::power {

struct NetworkBinEnergy {
  MicroJoules substation = 0, losses = 0, curtailed_regen = 0, curtailed_traction = 0;
};

class NetworkBalance {
 public:
  // trains share one profile; horizon_s: the clock time past which no train runs.
  NetworkBalance(const NetworkProfile& profile, const PowerSupply& supply,
                 double traction_efficiency, int trains, double horizon_s, int threads = 0);

  int trains() const { return static_cast<int>(departure_s_.size()); }
  int departure_s(int train) const { return departure_s_[train]; }
  // Lays every train at its departure (whole seconds >= 0) and solves every bin.
  void place_all(const std::vector<int>& departures_s);
  // Moves one placed train; returns the change of substation energy.
  MicroJoules move(int train, int departure_s);

  MicroJoules substation() const { return total_.substation; }
  const NetworkBinEnergy& total() const { return total_; }
  // Bins whose load flow was not CONVERGENCE (a failure is never counted as a solution).
  long unsolved_bins() const { return unsolved_; }
  // Totals recomputed from the bins (a check of the running totals).
  NetworkBinEnergy recount() const;

 private:
  NetworkBinEnergy solve_bin(long bin, LoadFlow& flow, LoadFlowResult& result,
                             std::vector<TrainLoad>& loads, std::vector<int>& ids,
                             bool* solved) const;
  void resort();
  void resolve(long from_bin, long to_bin);

  const NetworkProfile* profile_;
  PowerSupply supply_;
  double traction_efficiency_;
  int threads_;
  long bins_ = 0;
  std::vector<int> departure_s_;
  std::vector<long> sorted_base_;  // first bins of the trains, ascending
  std::vector<int> sorted_train_;
  std::vector<NetworkBinEnergy> bin_;
  std::vector<char> bin_unsolved_;
  NetworkBinEnergy total_;
  long unsolved_ = 0;
  // Workspace of the serial moves.
  std::unique_ptr<LoadFlow> flow_;
  LoadFlowResult result_;
  std::vector<TrainLoad> loads_;
  std::vector<int> ids_;
};

}  // namespace ecorail::power
