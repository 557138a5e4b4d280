#include "power/network_evaluation.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "power/micro_joules.hpp"

namespace ecorail::power {

namespace {

// The departures sorted, as loads_at needs them.
struct Placement {
  std::vector<long> base;
  std::vector<int> train;
};

Placement place(const NetworkSetup& s, const std::vector<int>& departures_s) {
  if (s.profile == nullptr || s.supply == nullptr)
    throw std::invalid_argument("a network setup needs a profile and a supply");
  Placement p;
  p.train.resize(departures_s.size());
  std::iota(p.train.begin(), p.train.end(), 0);
  std::stable_sort(p.train.begin(), p.train.end(),
                   [&](int a, int b) { return departures_s[a] < departures_s[b]; });
  for (int k : p.train) {
    if (departures_s[k] < 0) throw std::out_of_range("a departure before 0 s");
    p.base.push_back(static_cast<long>(departures_s[k]) * s.profile->ticks_per_second());
  }
  return p;
}

long bins_of(const NetworkSetup& s) {
  return static_cast<long>(std::ceil(s.horizon_s * s.profile->ticks_per_second())) + 1;
}

struct Accumulator {
  std::vector<MicroJoules> sub, train_regen, train_traction;
  std::vector<double> peak_W, peak_A;
  MicroJoules substation = 0, losses = 0, traction = 0, aux = 0, regen = 0, cut_regen = 0,
              cut_traction = 0;
  double v_min = 0.0, v_max = 0.0;
  bool any_train = false;
  long instants = 0, regen_cut = 0, traction_cut = 0, no_solution = 0, unsolved = 0;
  double worst = 0.0;
  Accumulator(std::size_t subs, std::size_t trains)
      : sub(subs, 0),
        train_regen(trains, 0),
        train_traction(trains, 0),
        peak_W(subs, 0.0),
        peak_A(subs, 0.0) {}
  void merge(const Accumulator& o) {
    for (std::size_t i = 0; i < sub.size(); ++i) {
      sub[i] += o.sub[i];
      peak_W[i] = std::max(peak_W[i], o.peak_W[i]);
      peak_A[i] = std::max(peak_A[i], o.peak_A[i]);
    }
    for (std::size_t k = 0; k < train_regen.size(); ++k) {
      train_regen[k] += o.train_regen[k];
      train_traction[k] += o.train_traction[k];
    }
    substation += o.substation, losses += o.losses, traction += o.traction, aux += o.aux;
    regen += o.regen, cut_regen += o.cut_regen, cut_traction += o.cut_traction;
    if (o.any_train) {
      v_min = any_train ? std::min(v_min, o.v_min) : o.v_min;
      v_max = any_train ? std::max(v_max, o.v_max) : o.v_max;
      any_train = true;
    }
    instants += o.instants, regen_cut += o.regen_cut, traction_cut += o.traction_cut;
    no_solution += o.no_solution, unsolved += o.unsolved;
    worst = std::max(worst, o.worst);
  }
};

}  // namespace

NetworkEvaluation evaluate_network(const NetworkSetup& s, const std::vector<int>& departures_s,
                                   bool regeneration) {
  const Placement p = place(s, departures_s);
  const long bins = bins_of(s);
  const std::size_t n_sub = s.supply->substations.size();
  const int n = static_cast<int>(departures_s.size());
  const double step = s.profile->step_s();
  const double to_uJ = step * kMicroJoulesPerJoule;
  auto uJ = [&](double w) { return std::llround(w * to_uJ); };
  Accumulator total(n_sub, departures_s.size());
  const int threads = s.threads > 0 ? s.threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads)
  {
    LoadFlow flow(*s.supply);
    LoadFlowResult r;
    std::vector<TrainLoad> loads;
    std::vector<int> ids;
    Accumulator mine(n_sub, departures_s.size());
#pragma omp for schedule(static, 4096)
    for (long b = 0; b < bins; ++b) {
      loads.clear();
      ids.clear();
      s.profile->loads_at(b, p.base.data(), p.train.data(), n, s.traction_efficiency,
                          s.supply->auxiliary_power_W, loads, ids);
      if (!regeneration)
        for (auto& l : loads) l.regen_W = 0.0;
      flow.solve(loads.data(), static_cast<int>(loads.size()), &r);
      ++mine.instants;
      if (r.summary.termination != Termination::CONVERGENCE) ++mine.unsolved;
      if (r.summary.no_solution_at_full_demand) ++mine.no_solution;
      if (r.curtailed_regen_W > 0.0) ++mine.regen_cut;
      if (r.curtailed_traction_W > 0.0) ++mine.traction_cut;
      for (std::size_t i = 0; i < n_sub; ++i) {
        mine.sub[i] += uJ(r.substation_power_W[i]);
        mine.peak_W[i] = std::max(mine.peak_W[i], r.substation_power_W[i]);
        mine.peak_A[i] = std::max(mine.peak_A[i], r.substation_current_A[i]);
      }
      for (std::size_t j = 0; j < ids.size(); ++j) {
        mine.train_regen[ids[j]] += uJ(r.train_curtailed_regen_W[j]);
        mine.train_traction[ids[j]] += uJ(r.train_curtailed_traction_W[j]);
      }
      mine.substation += uJ(r.substation_W);
      mine.losses += uJ(r.line_losses_W);
      mine.traction += uJ(r.traction_W);
      mine.aux += uJ(r.auxiliary_W);
      mine.regen += uJ(r.regen_W);
      mine.cut_regen += uJ(r.curtailed_regen_W);
      mine.cut_traction += uJ(r.curtailed_traction_W);
      if (!ids.empty()) {
        mine.v_min =
            mine.any_train ? std::min(mine.v_min, r.min_train_voltage_V) : r.min_train_voltage_V;
        mine.v_max =
            mine.any_train ? std::max(mine.v_max, r.max_train_voltage_V) : r.max_train_voltage_V;
        mine.any_train = true;
        const double scale = r.traction_W + r.auxiliary_W + r.regen_W;
        if (scale > 0.0)
          mine.worst = std::max(mine.worst, std::fabs(r.balance_residual_W()) / scale);
      }
    }
#pragma omp critical
    total.merge(mine);  // sums of integers, maxima and minima: independent of the order
  }
  NetworkEvaluation e;
  e.time_step_s = step;
  for (std::size_t i = 0; i < n_sub; ++i) {
    const auto& sub = s.supply->substations[i];
    e.substations.push_back(
        {sub.name, sub.position_m, to_joules(total.sub[i]), total.peak_W[i], total.peak_A[i]});
  }
  e.substation_J = to_joules(total.substation);
  e.line_losses_J = to_joules(total.losses);
  e.traction_wheel_J = s.profile->traction_total_J() * n;
  e.traction_input_J = to_joules(total.traction);
  e.auxiliary_J = to_joules(total.aux);
  e.regen_J = to_joules(total.regen);
  e.curtailed_regen_J = to_joules(total.cut_regen);
  e.used_regen_J = e.regen_J - e.curtailed_regen_J;
  e.curtailed_traction_J = to_joules(total.cut_traction);
  e.min_train_voltage_V = total.v_min;
  e.max_train_voltage_V = total.v_max;
  e.instants = total.instants;
  e.regen_curtailed_instants = total.regen_cut;
  e.traction_curtailed_instants = total.traction_cut;
  e.no_solution_instants = total.no_solution;
  e.unsolved_instants = total.unsolved;
  e.max_balance_error_fraction = total.worst;
  for (int k = 0; k < n; ++k) {
    e.train_curtailed_regen_J.push_back(to_joules(total.train_regen[k]));
    e.train_curtailed_traction_J.push_back(to_joules(total.train_traction[k]));
  }
  return e;
}

SubstationTrace substation_trace(const NetworkSetup& s, const std::vector<int>& departures_s,
                                 double from_s, double to_s) {
  const Placement p = place(s, departures_s);
  const int tps = s.profile->ticks_per_second();
  const long bins = bins_of(s);
  const long b0 = std::clamp(static_cast<long>(std::floor(from_s * tps)), 0L, bins);
  const long b1 = std::clamp(static_cast<long>(std::ceil(to_s * tps)), b0, bins);
  SubstationTrace t;
  t.start_s = static_cast<double>(b0) / tps;
  t.step_s = s.profile->step_s();
  for (const auto& sub : s.supply->substations) t.names.push_back(sub.name);
  t.power_W.assign(t.names.size(), std::vector<double>(b1 - b0, 0.0));
  LoadFlow flow(*s.supply);
  LoadFlowResult r;
  std::vector<TrainLoad> loads;
  std::vector<int> ids;
  for (long b = b0; b < b1; ++b) {
    loads.clear();
    ids.clear();
    s.profile->loads_at(b, p.base.data(), p.train.data(), static_cast<int>(p.base.size()),
                        s.traction_efficiency, s.supply->auxiliary_power_W, loads, ids);
    flow.solve(loads.data(), static_cast<int>(loads.size()), &r);
    for (std::size_t i = 0; i < t.names.size(); ++i) t.power_W[i][b - b0] = r.substation_power_W[i];
  }
  return t;
}

LoadFlowResult load_flow_at(const NetworkSetup& s, const std::vector<int>& departures_s, double t_s,
                            std::vector<int>* trains) {
  const Placement p = place(s, departures_s);
  const long b = static_cast<long>(std::floor(t_s * s.profile->ticks_per_second()));
  LoadFlow flow(*s.supply);
  LoadFlowResult r;
  std::vector<TrainLoad> loads;
  std::vector<int> ids;
  s.profile->loads_at(b, p.base.data(), p.train.data(), static_cast<int>(p.base.size()),
                      s.traction_efficiency, s.supply->auxiliary_power_W, loads, ids);
  flow.solve(loads.data(), static_cast<int>(loads.size()), &r, true);
  if (trains) *trains = ids;
  return r;
}

}  // namespace ecorail::power
