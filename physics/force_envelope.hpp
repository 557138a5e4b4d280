// ForceEnvelope: the maximum traction or braking force a train can apply as a function of speed.
// Two forms cover the sources we meet: piecewise polynomials in km/h giving kN (the contest
// train), and tables of (km/h, kN) points interpolated linearly (digitised manufacturer curves,
// TTOBench). Either form can carry a power cap, F <= P / v. Above the last piece the last piece
// is extrapolated; forces never go negative.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "physics/units.hpp"

namespace ecorail::physics {

struct PolynomialPiece {
  double from_kmh = 0.0;
  double to_kmh = 0.0;
  std::vector<double> coeffs_kN;  // ascending powers of v in km/h
};

struct TablePoint {
  double speed_kmh = 0.0;
  double force_kN = 0.0;
};

class ForceEnvelope {
 public:
  ForceEnvelope() = default;
  static ForceEnvelope piecewise(std::vector<PolynomialPiece> pieces, double power_cap_kW = 0.0);
  static ForceEnvelope table(std::vector<TablePoint> points, double power_cap_kW = 0.0);

  // Maximum force in N at speed v (m/s), including the power cap. Inline: the forward
  // re-simulation evaluates it several times per 5 cm step.
  double force_N(double v_ms) const {
    return units::kN_to_N(force_kN_at_kmh(units::ms_to_kmh(v_ms)));
  }
  // Same in the edge units, for reports and fitting.
  double force_kN_at_kmh(double v_kmh) const {
    double f = std::max(0.0, raw_kN(v_kmh));
    if (power_cap_kW_ > 0.0 && v_kmh > 0.0) {
      f = std::min(f, power_cap_kW_ / units::kmh_to_ms(v_kmh));  // kW / (m/s) = kN
    }
    return f;
  }

  bool is_table() const { return !points_.empty(); }
  const std::vector<PolynomialPiece>& pieces() const { return pieces_; }
  const std::vector<TablePoint>& points() const { return points_; }
  double power_cap_kW() const { return power_cap_kW_; }
  bool empty() const { return pieces_.empty() && points_.empty(); }

 private:
  double raw_kN(double v_kmh) const {
    if (!points_.empty()) return table_kN(v_kmh);
    // The piece whose [from, to) holds v; beyond the last piece its polynomial is extrapolated.
    // Pieces are sorted by from_kmh: the last one starting at or below v is the first one
    // followed by a start above v.
    const PolynomialPiece* piece = &pieces_.front();
    for (const auto& p : pieces_) {
      if (!(v_kmh >= p.from_kmh)) break;
      piece = &p;
    }
    double f = 0.0;
    for (auto c = piece->coeffs_kN.rbegin(); c != piece->coeffs_kN.rend(); ++c) f = f * v_kmh + *c;
    return f;
  }
  double table_kN(double v_kmh) const;

  std::vector<PolynomialPiece> pieces_;
  std::vector<TablePoint> points_;
  double power_cap_kW_ = 0.0;
};

}  // namespace ecorail::physics
