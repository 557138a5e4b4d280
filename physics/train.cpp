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

}  // namespace ecorail::physics
