#include "physics/force_envelope.hpp"

#include <algorithm>
#include <stdexcept>

#include "physics/units.hpp"

namespace ecorail::physics {

ForceEnvelope ForceEnvelope::piecewise(std::vector<PolynomialPiece> pieces, double power_cap_kW) {
  if (pieces.empty()) throw std::invalid_argument("force envelope needs at least one piece");
  std::sort(pieces.begin(), pieces.end(),
            [](const auto& a, const auto& b) { return a.from_kmh < b.from_kmh; });
  ForceEnvelope e;
  e.pieces_ = std::move(pieces);
  e.power_cap_kW_ = power_cap_kW;
  return e;
}

ForceEnvelope ForceEnvelope::table(std::vector<TablePoint> points, double power_cap_kW) {
  if (points.empty()) throw std::invalid_argument("force table needs at least one point");
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.speed_kmh < b.speed_kmh; });
  ForceEnvelope e;
  e.points_ = std::move(points);
  e.power_cap_kW_ = power_cap_kW;
  return e;
}

double ForceEnvelope::table_kN(double v_kmh) const {
  if (v_kmh <= points_.front().speed_kmh) return points_.front().force_kN;
  if (v_kmh >= points_.back().speed_kmh) return points_.back().force_kN;
  auto it = std::upper_bound(points_.begin(), points_.end(), v_kmh,
                             [](double v, const TablePoint& p) { return v < p.speed_kmh; });
  const TablePoint& hi = *it;
  const TablePoint& lo = *(it - 1);
  const double w = (v_kmh - lo.speed_kmh) / (hi.speed_kmh - lo.speed_kmh);
  return lo.force_kN + w * (hi.force_kN - lo.force_kN);
}

}  // namespace ecorail::physics
