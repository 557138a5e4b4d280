#include "power/load_flow.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::power {

namespace {

// A Newton iterate outside this band has left every physical operating point: the demand has
// no solution at these voltages and a curtailment must be imposed.
constexpr double kDivergedAbove = 20.0;  // x max train voltage
constexpr double kDivergedBelow = 1e-3;  // x min train voltage
// Nodes closer than this loop resistance (about 0.4 m of the example's 23 mOhm/km) are one bus:
// a train 1 mm from a substation would otherwise make the equations needlessly ill-conditioned
// (a branch conductance of 10^7 S next to the substation's 67 S).
constexpr double kMergeResistance_ohm = 1e-5;
// Holds are released only on a clear sign, so rounding cannot make the active set cycle.
constexpr double kReleaseTolerance_W = 1e-6;

}  // namespace

bool LoadFlowOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(std::isfinite(voltage_tolerance_V) && voltage_tolerance_V > 0.0))
    return fail("voltage_tolerance_V: expected a tolerance > 0 V");
  if (max_newton_iterations < 1) return fail("max_newton_iterations: expected at least 1");
  if (max_active_set_iterations < 1) return fail("max_active_set_iterations: expected at least 1");
  return true;
}

std::string LoadFlowSummary::BriefReport() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%s: %d Newton solves, %d iterations, regen curtailed at %d buses, traction at %d",
                std::string(dp::termination_name(termination)).c_str(), active_set_iterations,
                newton_iterations, regen_curtailed_buses, traction_curtailed_buses);
  return buf;
}

std::string LoadFlowSummary::FullReport() const {
  std::string out = BriefReport() + "\n";
  out += std::string("  no solution at full demand: ") +
         (no_solution_at_full_demand ? "yes" : "no") + "\n";
  out += std::string("  voltage limit violated: ") + (voltage_limit_violated ? "yes" : "no") + "\n";
  if (!message.empty()) out += "  " + message + "\n";
  return out;
}

LoadFlow::LoadFlow(const PowerSupply& supply, const LoadFlowOptions& options)
    : supply_(supply), options_(options) {
  std::string why;
  if (!supply_.IsValid(&why)) throw std::invalid_argument("power supply: " + why);
  if (!options_.IsValid(&why)) throw std::invalid_argument("load flow options: " + why);
  for (const Substation& s : supply_.substations) {
    sub_r_ohm_.push_back(supply_.loop_resistance_to_ohm(s.position_m));
    sub_g_S_.push_back(1.0 / s.internal_resistance_ohm);
  }
}

double LoadFlow::bus_power_W(const Bus& b) const {
  switch (b.mode) {
    case Mode::NoRegen:
      return b.traction_W + b.auxiliary_W;
    case Mode::NoTraction:
      return b.auxiliary_W - b.regen_W;
    default:
      return b.traction_W + b.auxiliary_W - b.regen_W;
  }
}

double LoadFlow::substation_current_A(int s, double v) const {
  // The diode's state is fixed during a Newton solve (the active set decides it), so the
  // equations Newton sees are smooth.
  const Substation& sub = supply_.substations[s];
  const double i = sub_g_S_[s] * (sub.no_load_voltage_V - v);
  if (semismooth_) return (sub.reversible || i > 0.0) ? i : 0.0;
  return conducting_[s] ? i : 0.0;
}

double LoadFlow::bus_net_current_A(int i) const {
  const Bus& b = buses_[i];
  const double v = b.voltage_V;
  double out = 0.0;
  if (i > 0) out += g_[i - 1] * (v - buses_[i - 1].voltage_V);
  if (i + 1 < static_cast<int>(buses_.size())) out += g_[i] * (v - buses_[i + 1].voltage_V);
  for (int s = b.sub_begin; s < b.sub_end; ++s) out -= substation_current_A(s, v);
  return out;
}

double LoadFlow::residual_A(int i) const {
  const Bus& b = buses_[i];
  return bus_net_current_A(i) + bus_power_W(b) / b.voltage_V;
}

// Damped Newton on the buses not held; held buses keep their voltage. Returns false when the
// iterate leaves every physical operating point or does not settle.
bool LoadFlow::newton(int* iterations) {
  const int n = static_cast<int>(buses_.size());
  f_.resize(n), diag_.resize(n), lower_.resize(n), upper_.resize(n), step_.resize(n);
  trial_.resize(n), cprime_.resize(n);
  auto held = [&](int i) {
    return buses_[i].mode == Mode::HoldHigh || buses_[i].mode == Mode::HoldLow;
  };
  auto max_residual = [&]() {
    double m = 0.0;
    for (int i = 0; i < n; ++i)
      if (!held(i)) m = std::max(m, std::fabs(residual_A(i)));
    return m;
  };
  const double v_hi = kDivergedAbove * supply_.max_train_voltage_V;
  const double v_lo = kDivergedBelow * supply_.min_train_voltage_V;
  double norm = max_residual();
  for (int it = 0; it < options_.max_newton_iterations; ++it) {
    ++*iterations;
    // Jacobian rows and the Newton step by the Thomas algorithm.
    for (int i = 0; i < n; ++i) {
      const Bus& b = buses_[i];
      if (held(i)) {
        diag_[i] = 1.0, lower_[i] = 0.0, upper_[i] = 0.0, f_[i] = 0.0;
        continue;
      }
      const double v = b.voltage_V;
      double d = -bus_power_W(b) / (v * v);
      lower_[i] = upper_[i] = 0.0;
      if (i > 0) d += g_[i - 1], lower_[i] = -g_[i - 1];
      if (i + 1 < n) d += g_[i], upper_[i] = -g_[i];
      for (int s = b.sub_begin; s < b.sub_end; ++s)
        // Semismooth: at the kink (v == U0) the conducting branch, so that from the no-load
        // start the first step sees the substation that will feed the load.
        if (semismooth_ ? (supply_.substations[s].reversible ||
                           v <= supply_.substations[s].no_load_voltage_V)
                        : conducting_[s] != 0)
          d += sub_g_S_[s];
      diag_[i] = d;
      f_[i] = -residual_A(i);
    }
    for (int i = 0; i < n; ++i) {
      const double denom = diag_[i] - (i > 0 ? lower_[i] * cprime_[i - 1] : 0.0);
      if (denom == 0.0 || !std::isfinite(denom)) return false;
      cprime_[i] = upper_[i] / denom;
      step_[i] = (f_[i] - (i > 0 ? lower_[i] * step_[i - 1] : 0.0)) / denom;
    }
    for (int i = n - 2; i >= 0; --i) step_[i] -= cprime_[i] * step_[i + 1];
    double full_step = 0.0;
    for (int i = 0; i < n; ++i) full_step = std::max(full_step, std::fabs(step_[i]));
    // Backtracking on the largest residual keeps the iterate from jumping across the nose of
    // a heavily loaded bus.
    for (int i = 0; i < n; ++i) trial_[i] = buses_[i].voltage_V;
    double alpha = 1.0, new_norm = norm;
    bool descended = false;
    for (int k = 0; k < 40 && !descended; ++k, alpha *= 0.5) {
      bool inside = true;
      for (int i = 0; i < n; ++i) {
        double v = trial_[i] + alpha * step_[i];
        // A released hold keeps its iterate on the side of the limit its release came from:
        // its solution lies there, and the unprojected step can run away past the limit.
        const Bus& b = buses_[i];
        if (b.released && b.mode == Mode::Free) {
          if (b.regen_W > 0.0) v = std::min(v, supply_.max_train_voltage_V);
          if (b.traction_W > 0.0) v = std::max(v, supply_.min_train_voltage_V);
        }
        inside = inside && v > v_lo && v < v_hi;
        buses_[i].voltage_V = v;
      }
      if (!inside) continue;
      new_norm = max_residual();
      descended =
          new_norm <= (1.0 - 1e-4 * alpha) * norm || full_step <= options_.voltage_tolerance_V;
    }
    if (!descended) {
      // No step reduces the residual: a stationary point that is not a solution, unless the
      // residual is already at rounding level.
      for (int i = 0; i < n; ++i) buses_[i].voltage_V = trial_[i];
      return norm <= 1e-9;
    }
    norm = new_norm;
    // A braking bus pushed above the maximum (an accelerating one below the minimum) is held
    // there at once: the free iterate of a line that cannot take all the regenerated power
    // runs away instead of converging. The outer active set releases a hold that needs a
    // negative curtailment.
    bool switched = false;
    for (Bus& b : buses_) {
      if (b.mode != Mode::Free || b.released) continue;
      if (b.regen_W > 0.0 && b.voltage_V > supply_.max_train_voltage_V)
        b.mode = Mode::HoldHigh, b.voltage_V = supply_.max_train_voltage_V, switched = true;
      else if (b.traction_W > 0.0 && b.voltage_V < supply_.min_train_voltage_V)
        b.mode = Mode::HoldLow, b.voltage_V = supply_.min_train_voltage_V, switched = true;
    }
    if (switched) {
      norm = max_residual();
      continue;
    }
    if (full_step <= options_.voltage_tolerance_V) return true;
  }
  return false;
}

void LoadFlow::solve(const TrainLoad* trains, int count, LoadFlowResult* r, bool with_nodes) {
  const int n_sub = static_cast<int>(supply_.substations.size());
  conducting_.assign(n_sub, 1);  // every rectifier conducts until the active set says not
  order_.resize(count);
  for (int k = 0; k < count; ++k) order_[k] = k;
  std::sort(order_.begin(), order_.end(), [&](int a, int b) {
    return trains[a].position_m < trains[b].position_m ||
           (trains[a].position_m == trains[b].position_m && a < b);
  });
  // Buses: substations and trains merged by position; a new bus wherever the loop resistance
  // from the previous node is not (nearly) zero.
  buses_.clear();
  g_.clear();
  int s = 0, t = 0;
  double v0 = 0.0;
  for (const Substation& sub : supply_.substations) v0 = std::max(v0, sub.no_load_voltage_V);
  while (s < n_sub || t < count) {
    const bool take_sub = t >= count || (s < n_sub && supply_.substations[s].position_m <=
                                                          trains[order_[t]].position_m);
    const double r_ohm =
        take_sub ? sub_r_ohm_[s] : supply_.loop_resistance_to_ohm(trains[order_[t]].position_m);
    if (buses_.empty() || r_ohm - buses_.back().r_ohm > kMergeResistance_ohm) {
      if (!buses_.empty()) g_.push_back(1.0 / (r_ohm - buses_.back().r_ohm));
      Bus b;
      b.r_ohm = r_ohm;
      b.sub_begin = b.sub_end = s;
      b.train_begin = b.train_end = t;
      b.voltage_V = v0;
      buses_.push_back(b);
    }
    Bus& b = buses_.back();
    if (take_sub) {
      b.sub_end = ++s;
    } else {
      const TrainLoad& load = trains[order_[t]];
      b.traction_W += load.traction_W;
      b.auxiliary_W += load.auxiliary_W;
      b.regen_W += load.regen_W;
      b.train_end = ++t;
    }
  }
  const int n = static_cast<int>(buses_.size());
  const double v_max = supply_.max_train_voltage_V, v_min = supply_.min_train_voltage_V;
  LoadFlowSummary& sm = r->summary;
  sm = LoadFlowSummary{};
  auto required_power_W = [&](int i) { return -buses_[i].voltage_V * bus_net_current_A(i); };

  // Two strategies for the diodes: semismooth Newton (the diode's max inside the equations),
  // and, when that does not settle, the diodes' states as part of the active set (smooth
  // equations in each Newton solve). Each fails on rare instants; rarely on the same one.
  bool settled = false, failed = false;
  for (int strategy = 0; strategy < 2 && !settled; ++strategy) {
    semismooth_ = strategy == 0;
    settled = failed = false;
    conducting_.assign(n_sub, 1);
    for (Bus& b : buses_) b.mode = Mode::Free, b.released = false, b.voltage_V = v0;
    for (int pass = 0; pass < options_.max_active_set_iterations && !settled; ++pass) {
      ++sm.active_set_iterations;
      const bool newton_ok = newton(&sm.newton_iterations);
      if (!newton_ok) {
        // No operating point with the demand as it stands: curtail where the iterate points
        // and retry.
        sm.no_solution_at_full_demand = true;
        int hi = -1, lo = -1;
        for (int i = 0; i < n; ++i) {
          const Bus& b = buses_[i];
          if (b.mode != Mode::Free) continue;
          if (b.regen_W > 0.0 && (hi < 0 || b.voltage_V > buses_[hi].voltage_V)) hi = i;
          if (b.traction_W > 0.0 && (lo < 0 || b.voltage_V < buses_[lo].voltage_V)) lo = i;
        }
        // Above every no-load voltage the substations do not feed the line: the surplus of
        // regeneration has nowhere to go and the highest braking bus must burn it; otherwise the
        // demand is too high and the lowest accelerating bus must give way.
        double u0_min = supply_.substations.front().no_load_voltage_V;
        for (const Substation& sub : supply_.substations)
          u0_min = std::min(u0_min, sub.no_load_voltage_V);
        if (hi >= 0 && (buses_[hi].voltage_V > u0_min || lo < 0)) {
          buses_[hi].mode = Mode::HoldHigh, buses_[hi].voltage_V = v_max;
        } else if (lo >= 0) {
          buses_[lo].mode = Mode::HoldLow, buses_[lo].voltage_V = v_min;
        } else {
          failed = true;
          sm.message = "Newton's method found no operating point and no train can be curtailed";
          break;
        }
        continue;
      }
      settled = true;
      // Diodes: a unidirectional rectifier whose terminals rise above its no-load voltage stops
      // conducting; a blocked one whose terminals fall below it conducts again.
      for (int i = 0; i < n && !semismooth_; ++i) {
        const double v = buses_[i].voltage_V;
        for (int k = buses_[i].sub_begin; k < buses_[i].sub_end; ++k) {
          const Substation& sub = supply_.substations[k];
          if (sub.reversible) continue;
          if (conducting_[k] && v > sub.no_load_voltage_V + options_.voltage_tolerance_V)
            conducting_[k] = 0, settled = false;
          else if (!conducting_[k] && v < sub.no_load_voltage_V - options_.voltage_tolerance_V)
            conducting_[k] = 1, settled = false;
        }
      }
      for (int i = 0; i < n; ++i) {
        Bus& b = buses_[i];
        const double full = b.traction_W + b.auxiliary_W - b.regen_W;
        switch (b.mode) {
          case Mode::Free:
            if (b.regen_W > 0.0 && b.voltage_V > v_max + options_.voltage_tolerance_V) {
              b.mode = Mode::HoldHigh, b.voltage_V = v_max, settled = false;
            } else if (b.traction_W > 0.0 && b.voltage_V < v_min - options_.voltage_tolerance_V) {
              b.mode = Mode::HoldLow, b.voltage_V = v_min, settled = false;
            }
            break;
          case Mode::HoldHigh: {
            const double curtailed = required_power_W(i) - full;
            if (curtailed < -kReleaseTolerance_W)
              b.mode = Mode::Free, b.released = true, settled = false;
            if (curtailed > b.regen_W + kReleaseTolerance_W)
              b.mode = Mode::NoRegen, settled = false;
            break;
          }
          case Mode::HoldLow: {
            const double curtailed = full - required_power_W(i);
            if (curtailed < -kReleaseTolerance_W)
              b.mode = Mode::Free, b.released = true, settled = false;
            if (curtailed > b.traction_W + kReleaseTolerance_W)
              b.mode = Mode::NoTraction, settled = false;
            break;
          }
          default:
            break;
        }
      }
    }
  }
  sm.termination = failed    ? Termination::FAILURE
                   : settled ? Termination::CONVERGENCE
                             : Termination::NO_CONVERGENCE;
  if (sm.termination == Termination::NO_CONVERGENCE)
    sm.message = "the voltage-limit active set did not settle";

  // Results.
  r->substation_power_W.assign(n_sub, 0.0);
  r->substation_current_A.assign(n_sub, 0.0);
  r->substation_voltage_V.assign(n_sub, 0.0);
  r->train_voltage_V.assign(count, 0.0);
  r->train_curtailed_regen_W.assign(count, 0.0);
  r->train_curtailed_traction_W.assign(count, 0.0);
  r->substation_W = r->line_losses_W = r->traction_W = r->auxiliary_W = r->regen_W = 0.0;
  r->curtailed_regen_W = r->curtailed_traction_W = 0.0;
  r->min_train_voltage_V = r->max_train_voltage_V = 0.0;
  bool any_train = false;
  for (int i = 0; i < n; ++i) {
    const Bus& b = buses_[i];
    const double v = b.voltage_V;
    for (int k = b.sub_begin; k < b.sub_end; ++k) {
      const double current = substation_current_A(k, v);
      r->substation_current_A[k] = current;
      r->substation_voltage_V[k] = v;
      r->substation_power_W[k] = v * current;
      r->substation_W += v * current;
    }
    if (i + 1 < n) {
      const double dv = v - buses_[i + 1].voltage_V;
      r->line_losses_W += g_[i] * dv * dv;
    }
    if (b.train_begin == b.train_end) continue;
    const double full = b.traction_W + b.auxiliary_W - b.regen_W;
    double cut_regen = 0.0, cut_traction = 0.0;
    if (b.mode == Mode::HoldHigh)
      cut_regen = std::clamp(required_power_W(i) - full, 0.0, b.regen_W);
    if (b.mode == Mode::NoRegen) cut_regen = b.regen_W;
    if (b.mode == Mode::HoldLow)
      cut_traction = std::clamp(full - required_power_W(i), 0.0, b.traction_W);
    if (b.mode == Mode::NoTraction) cut_traction = b.traction_W;
    if (cut_regen > 0.0) ++sm.regen_curtailed_buses;
    if (cut_traction > 0.0) ++sm.traction_curtailed_buses;
    if (v > v_max * (1.0 + 1e-9) || (b.traction_W > 0.0 && v < v_min * (1.0 - 1e-9)))
      sm.voltage_limit_violated = true;
    r->traction_W += b.traction_W - cut_traction;
    r->auxiliary_W += b.auxiliary_W;
    r->regen_W += b.regen_W;
    r->curtailed_regen_W += cut_regen;
    r->curtailed_traction_W += cut_traction;
    for (int k = b.train_begin; k < b.train_end; ++k) {
      const int j = order_[k];
      r->train_voltage_V[j] = v;
      if (cut_regen > 0.0)
        r->train_curtailed_regen_W[j] = cut_regen * trains[j].regen_W / b.regen_W;
      if (cut_traction > 0.0)
        r->train_curtailed_traction_W[j] = cut_traction * trains[j].traction_W / b.traction_W;
    }
    r->min_train_voltage_V = any_train ? std::min(r->min_train_voltage_V, v) : v;
    r->max_train_voltage_V = any_train ? std::max(r->max_train_voltage_V, v) : v;
    any_train = true;
  }
  r->used_regen_W = r->regen_W - r->curtailed_regen_W;
  if (sm.voltage_limit_violated && sm.message.empty())
    sm.message = "a train is outside its voltage limits with nothing left to curtail";
  r->nodes.clear();
  if (with_nodes) {
    for (int i = 0; i < n; ++i) {
      const Bus& b = buses_[i];
      for (int k = b.sub_begin; k < b.sub_end; ++k)
        r->nodes.push_back({supply_.substations[k].position_m, b.voltage_V, k, -1});
      for (int k = b.train_begin; k < b.train_end; ++k)
        r->nodes.push_back({trains[order_[k]].position_m, b.voltage_V, -1, order_[k]});
    }
    std::stable_sort(
        r->nodes.begin(), r->nodes.end(),
        [](const LoadFlowNode& a, const LoadFlowNode& b) { return a.position_m < b.position_m; });
  }
}

}  // namespace ecorail::power
