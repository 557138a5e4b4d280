// ForceEnvelope: the maximum traction or braking force a train can apply as a function of speed.
// Two forms cover the sources we meet: piecewise polynomials in km/h giving kN (the contest
// train), and tables of (km/h, kN) points interpolated linearly (digitised manufacturer curves,
// TTOBench). Either form can carry a power cap, F <= P / v. Above the last piece the last piece
// is extrapolated; forces never go negative.
#pragma once

#include <string>
#include <utility>
#include <vector>

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

  // Maximum force in N at speed v (m/s), including the power cap.
  double force_N(double v_ms) const;
  // Same in the edge units, for reports and fitting.
  double force_kN_at_kmh(double v_kmh) const;

  bool is_table() const { return !points_.empty(); }
  const std::vector<PolynomialPiece>& pieces() const { return pieces_; }
  const std::vector<TablePoint>& points() const { return points_; }
  double power_cap_kW() const { return power_cap_kW_; }
  bool empty() const { return pieces_.empty() && points_.empty(); }

 private:
  double raw_kN(double v_kmh) const;

  std::vector<PolynomialPiece> pieces_;
  std::vector<TablePoint> points_;
  double power_cap_kW_ = 0.0;
};

}  // namespace ecorail::physics
