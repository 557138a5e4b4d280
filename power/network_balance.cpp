#include "power/network_balance.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace ecorail::power {

namespace {

void add(NetworkBinEnergy& a, const NetworkBinEnergy& b, int sign) {
  a.substation += sign * b.substation;
  a.losses += sign * b.losses;
  a.curtailed_regen += sign * b.curtailed_regen;
  a.curtailed_traction += sign * b.curtailed_traction;
}

}  // namespace

NetworkBalance::NetworkBalance(const NetworkProfile& profile, const PowerSupply& supply,
                               double traction_efficiency, int trains, double horizon_s,
                               int threads)
    : profile_(&profile),
      supply_(supply),
      traction_efficiency_(traction_efficiency),
      threads_(threads > 0 ? threads : omp_get_max_threads()),
      departure_s_(trains, -1) {
  if (trains < 1) throw std::invalid_argument("a network balance needs at least one train");
  if (!(traction_efficiency > 0.0 && traction_efficiency <= 1.0))
    throw std::invalid_argument("traction efficiency must be in (0, 1]");
  bins_ = static_cast<long>(std::ceil(horizon_s * profile.ticks_per_second())) + 1;
  bin_.assign(bins_, {});
  bin_unsolved_.assign(bins_, 0);
  flow_ = std::make_unique<LoadFlow>(supply_);
}

NetworkBinEnergy NetworkBalance::solve_bin(long bin, LoadFlow& flow, LoadFlowResult& r,
                                           std::vector<TrainLoad>& loads, std::vector<int>& ids,
                                           bool* solved) const {
  loads.clear();
  ids.clear();
  profile_->loads_at(bin, sorted_base_.data(), sorted_train_.data(), trains(), traction_efficiency_,
                     supply_.auxiliary_power_W, loads, ids);
  flow.solve(loads.data(), static_cast<int>(loads.size()), &r);
  *solved = r.summary.termination == Termination::CONVERGENCE;
  const double to_uJ = profile_->step_s() * kMicroJoulesPerJoule;
  return {std::llround(r.substation_W * to_uJ), std::llround(r.line_losses_W * to_uJ),
          std::llround(r.curtailed_regen_W * to_uJ), std::llround(r.curtailed_traction_W * to_uJ)};
}

void NetworkBalance::resort() {
  std::vector<int> order(trains());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return departure_s_[a] < departure_s_[b]; });
  sorted_base_.resize(order.size());
  sorted_train_ = order;
  for (std::size_t i = 0; i < order.size(); ++i)
    sorted_base_[i] = static_cast<long>(departure_s_[order[i]]) * profile_->ticks_per_second();
}

void NetworkBalance::place_all(const std::vector<int>& departures_s) {
  if (static_cast<int>(departures_s.size()) != trains())
    throw std::invalid_argument("one departure per train expected");
  const long span = profile_->span_bins();
  for (int d : departures_s) {
    if (d < 0 || static_cast<long>(d) * profile_->ticks_per_second() + span > bins_)
      throw std::out_of_range("a departure outside the network balance's horizon");
  }
  departure_s_ = departures_s;
  resort();
  NetworkBinEnergy total;
  long unsolved = 0;
  const long bins = bins_;
#pragma omp parallel num_threads(threads_)
  {
    LoadFlow flow(supply_);
    LoadFlowResult r;
    std::vector<TrainLoad> loads;
    std::vector<int> ids;
    NetworkBinEnergy mine;
    long my_unsolved = 0;
#pragma omp for schedule(static, 4096)
    for (long b = 0; b < bins; ++b) {
      bool solved = true;
      bin_[b] = solve_bin(b, flow, r, loads, ids, &solved);
      bin_unsolved_[b] = solved ? 0 : 1;
      my_unsolved += solved ? 0 : 1;
      add(mine, bin_[b], +1);
    }
#pragma omp critical
    {
      add(total, mine, +1);  // integers: the order of the threads does not matter
      unsolved += my_unsolved;
    }
  }
  total_ = total;
  unsolved_ = unsolved;
}

void NetworkBalance::resolve(long from_bin, long to_bin) {
  for (long b = std::max(0L, from_bin); b < std::min(bins_, to_bin); ++b) {
    add(total_, bin_[b], -1);
    unsolved_ -= bin_unsolved_[b];
    bool solved = true;
    bin_[b] = solve_bin(b, *flow_, result_, loads_, ids_, &solved);
    bin_unsolved_[b] = solved ? 0 : 1;
    unsolved_ += bin_unsolved_[b];
    add(total_, bin_[b], +1);
  }
}

MicroJoules NetworkBalance::move(int train, int departure_s) {
  const long tps = profile_->ticks_per_second(), span = profile_->span_bins();
  if (departure_s < 0 || static_cast<long>(departure_s) * tps + span > bins_)
    throw std::out_of_range("a departure outside the network balance's horizon");
  const MicroJoules before = total_.substation;
  const long old_base = static_cast<long>(departure_s_[train]) * tps;
  const long new_base = static_cast<long>(departure_s) * tps;
  departure_s_[train] = departure_s;
  resort();
  if (std::abs(new_base - old_base) < span) {
    resolve(std::min(old_base, new_base), std::max(old_base, new_base) + span);
  } else {
    resolve(old_base, old_base + span);
    resolve(new_base, new_base + span);
  }
  return total_.substation - before;
}

NetworkBinEnergy NetworkBalance::recount() const {
  NetworkBinEnergy t;
  for (const auto& b : bin_) add(t, b, +1);
  return t;
}

}  // namespace ecorail::power
