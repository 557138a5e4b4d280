#include "energy/overlap_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecorail::energy {

OverlapModel::OverlapModel(const physics::Trip& trip) {
  if (trip.empty() || trip.departure_s() != 0.0)
    throw std::invalid_argument("an overlap model is built from a trip departing at 0");
  const auto& smp = trip.samples();
  const double eff = trip.regen_efficiency();
  // Steps of one sign joined into stretches; a step's regime is its sign of force.
  int current = 0;  // +1 traction, -1 braking, 0 neither
  for (std::size_t k = 1; k < smp.size(); ++k) {
    const auto& a = smp[k - 1];
    const auto& b = smp[k];
    const double work = b.force_N * (b.s_m - a.s_m);
    const int sign = b.dwelling || work == 0.0 ? 0 : (work > 0.0 ? 1 : -1);
    if (sign > 0) {
      if (current != 1) traction_.push_back({a.t_s, a.t_s});
      traction_.back().end_s = b.t_s;
      traction_J_ += work;
    } else if (sign < 0) {
      if (current != -1) braking_.push_back({{a.t_s, a.t_s}, 0.0});
      braking_.back().time.end_s = b.t_s;
      braking_.back().regen_J += -work * eff;
      regen_J_ += -work * eff;
    }
    current = sign;
  }
}

double OverlapModel::traction_overlap(double a, double b, double shift) const {
  // Traction intervals shifted by `shift` that meet [a, b): the first one ending after a.
  auto it = std::upper_bound(traction_.begin(), traction_.end(), a - shift,
                             [](double t, const Interval& iv) { return t < iv.end_s; });
  double total = 0.0;
  for (; it != traction_.end() && it->begin_s + shift < b; ++it)
    total += std::max(0.0, std::min(b, it->end_s + shift) - std::max(a, it->begin_s + shift));
  return total;
}

double OverlapModel::traction_overlap2(double a, double b, double s1, double s2) const {
  auto it = std::upper_bound(traction_.begin(), traction_.end(), a - s1,
                             [](double t, const Interval& iv) { return t < iv.end_s; });
  double total = 0.0;
  for (; it != traction_.end() && it->begin_s + s1 < b; ++it) {
    const double lo = std::max(a, it->begin_s + s1), hi = std::min(b, it->end_s + s1);
    if (hi > lo) total += traction_overlap(lo, hi, s2);
  }
  return total;
}

double OverlapModel::used_with_traction_shift(double shift_s) const {
  double used = 0.0;
  for (const auto& p : braking_) {
    const double len = p.time.end_s - p.time.begin_s;
    if (len > 0.0)
      used += p.regen_J * traction_overlap(p.time.begin_s, p.time.end_s, shift_s) / len;
  }
  return used;
}

// The train ahead departed ahead_s earlier: on the braking train's clock its traction is shifted
// back; the train behind's is shifted forward.
double OverlapModel::used_from_ahead_J(double ahead_s) const {
  return used_with_traction_shift(-ahead_s);
}

double OverlapModel::used_from_behind_J(double behind_s) const {
  return used_with_traction_shift(behind_s);
}

double OverlapModel::double_count_J(double ahead_s, double behind_s) const {
  double used = 0.0;
  for (const auto& p : braking_) {
    const double len = p.time.end_s - p.time.begin_s;
    if (len > 0.0)
      used += p.regen_J * traction_overlap2(p.time.begin_s, p.time.end_s, -ahead_s, behind_s) / len;
  }
  return used;
}

double OverlapModel::used_from_either_J(double ahead_s, double behind_s) const {
  return used_from_ahead_J(ahead_s) + used_from_behind_J(behind_s) -
         double_count_J(ahead_s, behind_s);
}

double OverlapModel::train_used_J(const std::vector<int>& t, std::size_t k,
                                  OverlapVariant variant) const {
  const bool ahead = k > 0, behind = k + 1 < t.size() && variant == OverlapVariant::Either;
  if (ahead && behind) return used_from_either_J(t[k] - t[k - 1], t[k + 1] - t[k]);
  if (ahead) return used_from_ahead_J(t[k] - t[k - 1]);
  if (behind) return used_from_behind_J(t[k + 1] - t[k]);
  return 0.0;
}

FleetEnergy OverlapModel::evaluate(const std::vector<int>& t, OverlapVariant variant) const {
  FleetEnergy e;
  const auto n = t.size();
  e.traction_J = traction_J_ * static_cast<double>(n);
  e.regen_J = regen_J_ * static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) e.used_regen_J += train_used_J(t, k, variant);
  return e;
}

}  // namespace ecorail::energy
