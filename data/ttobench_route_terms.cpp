#include "data/ttobench_route_terms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/ttobench_units.hpp"
#include "physics/units.hpp"

namespace ecorail::data {

namespace {

// A function of the position x along the route (travel direction, 0 at the departure stop),
// piecewise linear in a parameter p: f = p for plain profiles, f = curve resistance of |p| for
// curvature profiles. Beyond its pieces it continues its end values.
struct Piece {
  double x0 = 0.0, x1 = 0.0;
  double p0 = 0.0, p1 = 0.0;
};

class Profile {
 public:
  Profile(std::vector<Piece> pieces, bool curvature, CurveFormula formula)
      : pieces_(std::move(pieces)), curvature_(curvature), formula_(formula) {
    std::sort(pieces_.begin(), pieces_.end(),
              [](const Piece& a, const Piece& b) { return a.x0 < b.x0; });
    // Gaps continue the previous piece's end value, so the pieces cover their whole extent.
    std::vector<Piece> filled;
    for (const auto& p : pieces_) {
      if (!filled.empty() && p.x0 > filled.back().x1) {
        filled.push_back({filled.back().x1, p.x0, filled.back().p1, filled.back().p1});
      }
      if (!filled.empty() && p.x0 < filled.back().x1) continue;  // overlaps: first wins
      filled.push_back(p);
    }
    pieces_ = std::move(filled);
  }

  double f_of(double p) const {
    return curvature_ ? curve_resistance_N_per_kN(std::abs(p), formula_) : p;
  }
  double param_at(double x) const {
    if (pieces_.empty()) return 0.0;
    if (x <= pieces_.front().x0) return pieces_.front().p0;
    if (x >= pieces_.back().x1) return pieces_.back().p1;
    const Piece& p = pieces_[locate(x)];
    return p.p0 + (p.p1 - p.p0) * (x - p.x0) / (p.x1 - p.x0);
  }
  double value_at(double x) const { return f_of(param_at(x)); }
  bool varies_on(double a, double b) const {
    for (const auto& p : pieces_) {
      if (p.x1 > a && p.x0 < b && p.p0 != p.p1) return true;
    }
    return false;
  }
  // Integral of f over [a, b].
  double integral(double a, double b) const {
    if (pieces_.empty() || !(b > a)) return 0.0;
    double sum = 0.0;
    const double lo = pieces_.front().x0;
    const double hi = pieces_.back().x1;
    if (a < lo) {
      sum += f_of(pieces_.front().p0) * (std::min(b, lo) - a);
      a = lo;
    }
    if (b > hi) {
      sum += f_of(pieces_.back().p1) * (b - std::max(a, hi));
      b = hi;
    }
    if (!(b > a)) return sum;
    for (std::size_t i = locate(a); i < pieces_.size() && pieces_[i].x0 < b; ++i) {
      sum += piece_integral(pieces_[i], std::max(a, pieces_[i].x0), std::min(b, pieces_[i].x1));
    }
    return sum;
  }
  std::vector<double> breakpoints() const {
    std::vector<double> out;
    for (const auto& p : pieces_) {
      out.push_back(p.x0);
      out.push_back(p.x1);
    }
    return out;
  }

 private:
  std::size_t locate(double x) const {
    auto it = std::upper_bound(pieces_.begin(), pieces_.end(), x,
                               [](double v, const Piece& p) { return v < p.x0; });
    return it == pieces_.begin() ? 0 : static_cast<std::size_t>(it - pieces_.begin()) - 1;
  }
  double piece_integral(const Piece& p, double a, double b) const {
    if (!(b > a)) return 0.0;
    const auto param = [&](double x) { return p.p0 + (p.p1 - p.p0) * (x - p.x0) / (p.x1 - p.x0); };
    if (!curvature_ || p.p0 == p.p1) return f_of(param(0.5 * (a + b))) * (b - a);
    // Split where f has a kink or a jump (the parameter crossing 0 or Roeckl's 300 m), then
    // Simpson on smooth pieces (exact for 600/R, which is linear in |k|).
    std::vector<double> cuts{a, b};
    for (const double k : {0.0, 1.0 / 300.0, -1.0 / 300.0}) {
      const double w = (k - p.p0) / (p.p1 - p.p0);
      const double x = p.x0 + w * (p.x1 - p.x0);
      if (x > a && x < b) cuts.push_back(x);
    }
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    constexpr int kPanels = 16;
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double h = (cuts[c + 1] - cuts[c]) / kPanels;
      double s = f_of(param(cuts[c])) + f_of(param(cuts[c + 1]));
      for (int i = 1; i < kPanels; ++i) s += (i % 2 ? 4.0 : 2.0) * f_of(param(cuts[c] + i * h));
      sum += s * h / 3.0;
    }
    return sum;
  }

  std::vector<Piece> pieces_;
  bool curvature_;
  CurveFormula formula_;
};

// Travel coordinate of a km post.
struct Frame {
  double p0;
  int dir;
  double x(double km) const { return dir * (km - p0); }
  // A km-post interval with values at its start and end as a piece in travel coordinates.
  Piece piece(double km_a, double km_b, double v_a, double v_b) const {
    return dir > 0 ? Piece{x(km_a), x(km_b), v_a, v_b} : Piece{x(km_b), x(km_a), v_b, v_a};
  }
};

Profile table_profile(const std::vector<IntervalRow>& rows, const Frame& f, double sign) {
  std::vector<Piece> pieces;
  for (const auto& r : rows) {
    const double v = sign * r.value + 0.0;
    pieces.push_back(f.piece(r.start_km_post_m, r.end_km_post_m, v, v));
  }
  return Profile(std::move(pieces), false, CurveFormula::Inverse600);
}

Profile curve_profile(const Line& line, const Frame& f) {
  std::vector<Piece> pieces;
  if (!line.curvatures.empty()) {
    for (const auto& c : line.curvatures) {
      pieces.push_back(f.piece(c.start_km_post_m, c.end_km_post_m, c.curvature_start_per_m,
                               c.curvature_end_per_m));
    }
  } else {
    for (const auto& r : line.curves) {
      const double k = r.value > 0.0 ? 1.0 / r.value : 0.0;
      pieces.push_back(f.piece(r.start_km_post_m, r.end_km_post_m, k, k));
    }
  }
  return Profile(std::move(pieces), true, line.curve_formula);
}

void check_roeckl(const Line& line) {
  if (line.curve_formula != CurveFormula::Roeckl) return;
  const auto bad = [](double k) { return k != 0.0 && std::abs(1.0 / k) <= 55.0; };
  for (const auto& c : line.curvatures) {
    if (bad(c.curvature_start_per_m) || bad(c.curvature_end_per_m)) {
      throw InputError(line.curves_file, c.source_row, "curvatures radius",
                       "a radius above 55 m for Roeckl's 650 / (R - 55); got " +
                           format_number(1.0 / std::max(std::abs(c.curvature_start_per_m),
                                                        std::abs(c.curvature_end_per_m))));
    }
  }
  if (line.curvatures.empty()) {
    for (const auto& r : line.curves) {
      if (r.value > 0.0 && r.value <= 55.0) {
        throw InputError(
            line.curves_file, r.source_row, "radius_m",
            "a radius above 55 m for Roeckl's 650 / (R - 55); got " + format_number(r.value));
      }
    }
  }
}

// The train's added Davis C (N/kN per (km/h)^2) in a tunnel of cross-section A: its table's
// value, interpolated linearly between listed cross-sections.
double tunnel_C(const Line& line, const TunnelRow& t, const physics::Train& train) {
  const auto& table = train.tunnel_drag;
  if (table.empty()) {
    throw InputError(line.tunnels_file, t.source_row, "tunnels",
                     "a train with tunnel drag data ('tunnel resistance'): the line has tunnels "
                     "and train '" +
                         train.name + "' gives none, refused rather than ignored");
  }
  const double A = t.cross_section_m2;
  const double lo = table.front().cross_section_m2;
  const double hi = table.back().cross_section_m2;
  if (A < lo - 1e-9 || A > hi + 1e-9) {
    throw InputError(line.tunnels_file, t.source_row, "tunnels cross section",
                     "a cross-section within the train's tunnel table (" + format_number(lo) +
                         " to " + format_number(hi) + " m^2); got " + format_number(A));
  }
  double C_kN = table.back().C_kN_per_kmh2;
  for (std::size_t i = 0; i + 1 < table.size(); ++i) {
    if (A <= table[i + 1].cross_section_m2) {
      const double w = std::clamp((A - table[i].cross_section_m2) /
                                      (table[i + 1].cross_section_m2 - table[i].cross_section_m2),
                                  0.0, 1.0);
      C_kN = table[i].C_kN_per_kmh2 + w * (table[i + 1].C_kN_per_kmh2 - table[i].C_kN_per_kmh2);
      break;
    }
  }
  if (table.size() == 1 || std::abs(A - lo) <= 1e-9) C_kN = table.front().C_kN_per_kmh2;
  return ttobench::force_to_specific(C_kN * 1000.0, train);
}

Profile tunnel_profile(const Line& line, const Frame& f, const physics::Train& train) {
  std::vector<Piece> pieces;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const auto* rows : {&line.gradients, &line.limits}) {
    for (const auto& r : *rows) {
      lo = std::min(lo, r.start_km_post_m);
      hi = std::max(hi, r.end_km_post_m);
    }
  }
  std::vector<TunnelRow> tunnels = line.tunnels;
  std::sort(tunnels.begin(), tunnels.end(), [](const TunnelRow& a, const TunnelRow& b) {
    return a.start_km_post_m < b.start_km_post_m;
  });
  double at = lo;
  for (const auto& t : tunnels) {
    if (t.start_km_post_m > at) pieces.push_back(f.piece(at, t.start_km_post_m, 0.0, 0.0));
    const double c = tunnel_C(line, t, train);
    pieces.push_back(f.piece(t.start_km_post_m, t.end_km_post_m, c, c));
    at = t.end_km_post_m;
  }
  if (hi > at) pieces.push_back(f.piece(at, hi, 0.0, 0.0));
  return Profile(std::move(pieces), false, CurveFormula::Inverse600);
}

// Mean over [a, b] of the force a train of length L feels with its head at s: the mean of f
// over [s - L, s] (f itself when L = 0). Simpson in s is exact where that mean is quadratic
// in s, which it is between the cut points for piecewise constant f.
double mean_felt(const Profile& p, double a, double b, double L) {
  if (L <= 0.0) {
    return p.varies_on(a, b) ? p.integral(a, b) / (b - a) : p.value_at(0.5 * (a + b));
  }
  const auto felt = [&](double s) { return p.integral(s - L, s) / L; };
  return (felt(a) + 4.0 * felt(0.5 * (a + b)) + felt(b)) / 6.0;
}

}  // namespace

bool needs_route_terms(const Line& line, const physics::Train& train) {
  return !line.curvatures.empty() || !line.tunnels.empty() ||
         line.curve_formula != CurveFormula::Inverse600 || train.length_m > 0.0;
}

double curve_resistance_N_per_kN(double k, CurveFormula formula) {
  if (k <= 0.0) return 0.0;
  if (formula == CurveFormula::Inverse600) return 600.0 * k;
  // Roeckl in terms of k = 1/R, finite as R -> infinity: 500 / (R - 30) = 500 k / (1 - 30 k).
  return k <= 1.0 / 300.0 ? 500.0 * k / (1.0 - 30.0 * k) : 650.0 * k / (1.0 - 55.0 * k);
}

std::vector<physics::RouteSegment> route_term_segments(const Line& line, double p0_m, int dir,
                                                       double length_m,
                                                       const physics::Train& train) {
  check_roeckl(line);
  const Frame frame{p0_m, dir};
  const double L = std::max(0.0, train.length_m);
  const Profile gradient = table_profile(line.gradients, frame, dir);
  const Profile limit = table_profile(line.limits, frame, 1.0);
  const Profile curve = curve_profile(line, frame);
  const Profile tunnel = tunnel_profile(line, frame, train);

  // Cuts: every change of any profile, and the same L further on (where it leaves the train).
  std::vector<double> force_changes;
  for (const Profile* p : {&gradient, &curve, &tunnel}) {
    for (const double b : p->breakpoints()) force_changes.push_back(b);
  }
  std::vector<double> cuts{0.0, length_m};
  for (const Profile* p : {&gradient, &curve, &tunnel, &limit}) {
    for (const double b : p->breakpoints()) {
      for (const double c : {b, b + L}) {
        if (c > 1e-6 && c < length_m - 1e-6) cuts.push_back(c);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> points;
  for (const double c : cuts) {
    if (points.empty() || c - points.back() > 1e-6) points.push_back(c);
  }
  if (length_m - points.back() <= 1e-6) points.back() = length_m;
  std::sort(force_changes.begin(), force_changes.end());

  const double vmax_kmh = units::ms_to_kmh(train.max_speed_ms);
  std::vector<physics::RouteSegment> segments;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double a = points[i];
    const double b = points[i + 1];
    // The felt force varies on [a, b] if a change lies under the train somewhere on it, or a
    // clothoid does: then pieces of at most kMaxPiece_m.
    bool varies = gradient.varies_on(a - L, b) || curve.varies_on(a - L, b);
    if (!varies && L > 0.0) {
      const auto it = std::upper_bound(force_changes.begin(), force_changes.end(), a - L + 1e-9);
      varies = it != force_changes.end() && *it < b - 1e-9;
    }
    const int n = varies ? std::max(1, static_cast<int>(std::ceil((b - a) / kMaxPiece_m))) : 1;
    // The limit on [a, b]: the strictest under the train anywhere (constant between the cuts).
    const double mid = 0.5 * (a + b);
    double v_kmh = limit.value_at(mid);
    if (L > 0.0) {
      for (const double bp : limit.breakpoints()) {
        if (bp > mid - L && bp < mid) v_kmh = std::min(v_kmh, limit.value_at(bp + 1e-9));
      }
      v_kmh = std::min(v_kmh, limit.value_at(mid - L));
    }
    if (line.cap_limits_at_train_speed) v_kmh = std::min(v_kmh, vmax_kmh);
    for (int k = 0; k < n; ++k) {
      const double s0 = a + (b - a) * k / n;
      const double s1 = k + 1 == n ? b : a + (b - a) * (k + 1) / n;
      physics::RouteSegment seg;
      seg.start_m = s0;
      seg.end_m = s1;
      seg.gradient_permille = mean_felt(gradient, s0, s1, L) + 0.0;
      seg.curve_N_per_kN = std::max(0.0, mean_felt(curve, s0, s1, L));
      const double k_head = std::abs(curve.param_at(0.5 * (s0 + s1)));
      seg.curve_radius_m = k_head > 0.0 ? 1.0 / k_head : 0.0;  // for reports only
      seg.tunnel_drag_N_per_kN_kmh2 = std::max(0.0, mean_felt(tunnel, s0, s1, L));
      seg.speed_limit_ms = units::kmh_to_ms(v_kmh);
      if (!segments.empty()) {
        physics::RouteSegment& last = segments.back();
        if (last.gradient_permille == seg.gradient_permille &&
            last.curve_N_per_kN == seg.curve_N_per_kN &&
            last.curve_radius_m == seg.curve_radius_m &&
            last.tunnel_drag_N_per_kN_kmh2 == seg.tunnel_drag_N_per_kN_kmh2 &&
            last.speed_limit_ms == seg.speed_limit_ms) {
          last.end_m = seg.end_m;
          continue;
        }
      }
      segments.push_back(seg);
    }
  }
  return segments;
}

}  // namespace ecorail::data
