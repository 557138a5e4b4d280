#include "physics/train.hpp"

#include <algorithm>
#include <cmath>

#include "physics/units.hpp"

namespace ecorail::physics {

namespace {
// Index i and weight w of x in the ascending grid: x = (1 - w) grid[i] + w grid[i + 1], with w
// clamped to [0, 1] outside the grid.
void locate(const std::vector<double>& grid, double x, std::size_t* i, double* w) {
  const auto it = std::upper_bound(grid.begin() + 1, grid.end() - 1, x);
  *i = static_cast<std::size_t>(it - grid.begin()) - 1;
  const double span = grid[*i + 1] - grid[*i];
  *w = std::clamp((x - grid[*i]) / span, 0.0, 1.0);
}
}  // namespace

double EfficiencyMap::at(double v_ms, double force_N) const {
  std::size_t i = 0, j = 0;
  double wv = 0.0, wf = 0.0;
  locate(speeds_ms, v_ms, &i, &wv);
  locate(forces_N, std::abs(force_N), &j, &wf);
  const std::size_t n = forces_N.size();
  const double lo = (1.0 - wf) * values[i * n + j] + wf * values[i * n + j + 1];
  const double hi = (1.0 - wf) * values[(i + 1) * n + j] + wf * values[(i + 1) * n + j + 1];
  return (1.0 - wv) * lo + wv * hi;
}

double Train::davis_N_per_kN(double v_ms) const {
  const double v = units::ms_to_kmh(v_ms);
  return davis.A + v * (davis.B + v * davis.C);
}

double Train::max_traction_N(double v_ms, double resistance_N) const {
  const double limit = effective_mass_kg() * max_accel_m_s2 + resistance_N;
  return std::max(0.0, std::min(traction.force_N(v_ms), limit));
}

double Train::max_brake_N(double v_ms, double resistance_N) const {
  // dv/dt = (-b - W) / M_eff >= -max_decel  <=>  b <= M_eff max_decel - W
  const double limit = effective_mass_kg() * max_decel_m_s2 - resistance_N;
  return std::max(0.0, std::min(braking.force_N(v_ms) + pneumatic_brake_N, limit));
}

}  // namespace ecorail::physics
