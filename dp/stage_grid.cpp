#include "dp/stage_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/units.hpp"

namespace ecorail::dp {

StageGrid::StageGrid(const physics::SpeedEnvelope& envelope, double length_m, const GridSpec& spec)
    : dv_(units::kmh_to_ms(spec.dv_kmh)) {
  if (!(spec.ds_m > 0.0) || !(spec.dv_kmh > 0.0)) {
    throw std::invalid_argument("grid steps ds and dv must be positive");
  }
  const int steps = std::max(1, static_cast<int>(std::ceil(length_m / spec.ds_m - 1e-9)));
  s_.resize(steps + 1);
  for (int i = 0; i <= steps; ++i) s_[i] = std::min(length_m, i * spec.ds_m);
  s_.back() = length_m;
  offset_.assign(1, 0);
  for (double s : s_) {
    const double top = envelope.v_at(s);
    top_.push_back(top);
    // Uniform nodes strictly below the top node (a node within 1e-9 of the top is the top).
    const int uniform = top > 0.0 ? static_cast<int>(std::ceil(top / dv_ - 1e-9)) : 0;
    uniform_.push_back(uniform);
    offset_.push_back(offset_.back() + uniform + 1);
  }
}

double StageGrid::speed(int i, int j) const {
  return j < uniform_[i] ? j * dv_ : top_[i];
}

int StageGrid::next_stage_after(double s_m) const {
  auto it = std::upper_bound(s_.begin(), s_.end(), s_m + 1e-9);
  return it == s_.end() ? stage_count() - 1 : static_cast<int>(it - s_.begin());
}

void StageGrid::locate(int i, double v, int* lower, double* weight) const {
  const int u = uniform_[i];
  const double top = top_[i];
  if (v >= top || u == 0) {
    *lower = offset_[i] + u;  // the top node
    *weight = 0.0;
    return;
  }
  const double last_uniform = (u - 1) * dv_;
  if (v >= last_uniform) {
    *lower = offset_[i] + u - 1;
    *weight = (v - last_uniform) / (top - last_uniform);
    return;
  }
  int k;
  double w;
  uniform_position(v, &k, &w);
  if (k <= u - 2) {
    *lower = offset_[i] + k;
    *weight = w;
    return;
  }
  // Rounding put v / dv on the last uniform node: the interval below it, at its far end.
  const double x = std::max(0.0, v) / dv_;
  *lower = offset_[i] + u - 2;
  *weight = x - (u - 2);
}

void StageGrid::uniform_position(double v, int* lower, double* weight) const {
  const double x = std::max(0.0, v) / dv_;
  *lower = static_cast<int>(x);
  *weight = x - *lower;
}

bool StageGrid::locates_uniformly(int i, double v) const {
  const int u = uniform_[i];
  if (u == 0 || !(v < top_[i]) || !(v < (u - 1) * dv_)) return false;
  int k;
  double w;
  uniform_position(v, &k, &w);
  return k <= u - 2;
}

}  // namespace ecorail::dp
