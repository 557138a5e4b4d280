#include "fitting/log_prep.hpp"

#include <algorithm>
#include <cmath>

#include "physics/units.hpp"

namespace ecorail::fitting {

std::string_view interval_status_name(IntervalStatus s) {
  switch (s) {
    case IntervalStatus::Used:
      return "used";
    case IntervalStatus::Gap:
      return "gap in time";
    case IntervalStatus::Standing:
      return "standing at one end";
    case IntervalStatus::UnknownForce:
      return "force unknown";
    case IntervalStatus::Switch:
      return "regime switch";
    case IntervalStatus::ForceStep:
      return "force step";
  }
  return "?";
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Largest deceleration a coasting train of the base model could show at v on this track,
// whether or not it feels the gradient.
double coasting_decel(const physics::Train& t, double v_ms, double grade, double curve) {
  const double w = t.davis_N_per_kN(v_ms) + std::max(grade, 0.0) + curve;
  return t.gravity_m_s2 * w / 1000.0 / (1.0 + t.rotating_mass_factor);
}

void classify_forces(const Log& log, int index, const physics::Train& base, const PrepOptions& opt,
                     PreparedLog& out, int& inferred_braking) {
  const double zero_N = units::kN_to_N(opt.zero_force_kN);
  const auto& rows = log.rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const LogRow& r = rows[i];
    PreparedRow p;
    p.log_index = index;
    p.source_row = r.source_row;
    p.time_s = r.time_s;
    p.speed_ms = r.speed_ms;
    p.gradient_permille = r.gradient_permille;
    p.curve_N_per_kN = r.curve_radius_m > 0.0 ? 600.0 / r.curve_radius_m : 0.0;
    p.position_m = r.position_m;

    double trac = log.has_traction ? r.traction_force_N : kUnknown;
    double brake = log.has_braking ? r.braking_force_N : kUnknown;
    if (std::isnan(trac) && std::isfinite(r.notch)) {
      trac = r.notch > 0.0 ? r.notch * base.traction.force_N(r.speed_ms) : 0.0;
    }
    if (std::isnan(brake) && std::isfinite(r.notch)) {
      brake = r.notch < 0.0 ? -r.notch * base.braking.force_N(r.speed_ms) : 0.0;
    }
    if (std::isnan(brake) && std::isfinite(trac)) {
      if (trac > zero_N) {
        brake = 0.0;  // a train does not motor and brake at once
      } else {
        // Coasting, or braking with a force the log does not give: braking shows as a
        // deceleration on both sides of the row well beyond what coasting could produce.
        const double limit =
            coasting_decel(base, r.speed_ms, r.gradient_permille, p.curve_N_per_kN) +
            opt.brake_detect_margin_m_s2;
        bool braking = true;
        bool any = false;
        if (i > 0) {
          const double a = (r.speed_ms - rows[i - 1].speed_ms) / (r.time_s - rows[i - 1].time_s);
          braking = braking && -a > limit;
          any = true;
        }
        if (i + 1 < rows.size()) {
          const double a = (rows[i + 1].speed_ms - r.speed_ms) / (rows[i + 1].time_s - r.time_s);
          braking = braking && -a > limit;
          any = true;
        }
        if (any && braking) {
          ++inferred_braking;
        } else {
          brake = 0.0;
        }
      }
    }
    if (std::isnan(trac) && std::isfinite(brake) && brake > zero_N) trac = 0.0;

    if (std::isnan(trac) || std::isnan(brake)) {
      p.regime = Regime::Unknown;
    } else {
      p.traction_N = trac;
      p.braking_N = brake;
      const bool t = trac > zero_N;
      const bool b = brake > zero_N;
      p.regime = t && b ? Regime::Unknown
                 : t    ? Regime::Traction
                 : b    ? Regime::Braking
                        : Regime::Coast;
      if (!t) p.traction_N = 0.0;
      if (!b) p.braking_N = 0.0;
    }
    out.rows.push_back(p);
  }
}

IntervalStatus interval_status(const PreparedRow& a, const PreparedRow& b, const PrepOptions& opt) {
  const double standing = units::kmh_to_ms(opt.standing_speed_kmh);
  if (b.time_s - a.time_s > opt.max_gap_s) return IntervalStatus::Gap;
  if (a.speed_ms < standing || b.speed_ms < standing) return IntervalStatus::Standing;
  if (a.regime == Regime::Unknown || b.regime == Regime::Unknown) {
    return IntervalStatus::UnknownForce;
  }
  if (a.regime != b.regime) return IntervalStatus::Switch;
  const double ua = a.traction_N - a.braking_N;
  const double ub = b.traction_N - b.braking_N;
  const double step = std::abs(ub - ua);
  if (step > units::kN_to_N(opt.force_step_min_kN) &&
      step > opt.force_step_fraction * std::max(std::abs(ua), std::abs(ub))) {
    return IntervalStatus::ForceStep;
  }
  return IntervalStatus::Used;
}

// Positions against speeds: the distance between two rows should be what the speeds cover.
void check_positions(const PreparedLog& log, int index, const PrepOptions& opt,
                     std::vector<PositionInconsistency>& out) {
  const auto& rows = log.rows;
  std::vector<double> err(rows.size() > 0 ? rows.size() - 1 : 0, 0.0);
  std::vector<bool> valid(err.size(), false);
  std::vector<double> abs_err;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const auto& a = rows[i];
    const auto& b = rows[i + 1];
    if (std::isnan(a.position_m) || std::isnan(b.position_m)) continue;
    const double dt = b.time_s - a.time_s;
    if (dt > opt.max_gap_s) continue;
    err[i] = (b.position_m - a.position_m) - 0.5 * (a.speed_ms + b.speed_ms) * dt;
    valid[i] = true;
    abs_err.push_back(std::abs(err[i]));
  }
  if (abs_err.empty()) return;
  const double sigma = std::max(1.4826 * median(abs_err), 0.05);
  const double limit = std::max(6.0 * sigma, 0.5);
  auto bad = [&](std::size_t i) { return valid[i] && std::abs(err[i]) > limit; };
  for (std::size_t i = 0; i < err.size(); ++i) {
    if (!bad(i)) continue;
    PositionInconsistency p;
    p.log_index = index;
    p.row_from = rows[i].source_row;
    p.row_to = rows[i + 1].source_row;
    p.expected_m =
        0.5 * (rows[i].speed_ms + rows[i + 1].speed_ms) * (rows[i + 1].time_s - rows[i].time_s);
    p.logged_m = rows[i + 1].position_m - rows[i].position_m;
    // One wrong position shows as two errors of opposite sign and similar size around it.
    auto pairs = [&](std::size_t j) {  // intervals j and j+1 around row j+1
      if (j + 1 >= err.size() || !bad(j) || !bad(j + 1)) return false;
      const double r = -err[j + 1] / err[j];
      return r > 0.5 && r < 2.0;
    };
    if (pairs(i)) {
      p.suspect_row = rows[i + 1].source_row;
    } else if (i > 0 && pairs(i - 1)) {
      p.suspect_row = rows[i].source_row;
    }
    out.push_back(p);
  }
}

}  // namespace

PreparedData prepare_logs(const std::vector<Log>& logs, const physics::Train& base,
                          const PrepOptions& opt) {
  PreparedData data;
  bool first_used = true;
  for (std::size_t li = 0; li < logs.size(); ++li) {
    PreparedLog p;
    p.label = logs[li].label;
    classify_forces(logs[li], static_cast<int>(li), base, opt, p, data.inferred_braking_rows);
    data.rows += static_cast<int>(p.rows.size());
    for (std::size_t i = 0; i + 1 < p.rows.size(); ++i) {
      const auto& a = p.rows[i];
      const auto& b = p.rows[i + 1];
      const IntervalStatus s = interval_status(a, b, opt);
      p.intervals.push_back(s);
      ++data.status_counts[static_cast<int>(s)];
      if (s != IntervalStatus::Used) continue;
      ++data.used_intervals;
      const double vlo = units::ms_to_kmh(std::min(a.speed_ms, b.speed_ms));
      const double vhi = units::ms_to_kmh(std::max(a.speed_ms, b.speed_ms));
      const double glo = std::min(a.gradient_permille, b.gradient_permille);
      const double ghi = std::max(a.gradient_permille, b.gradient_permille);
      if (first_used) {
        data.min_speed_kmh = vlo;
        data.max_speed_kmh = vhi;
        data.min_gradient_permille = glo;
        data.max_gradient_permille = ghi;
        first_used = false;
      }
      data.min_speed_kmh = std::min(data.min_speed_kmh, vlo);
      data.max_speed_kmh = std::max(data.max_speed_kmh, vhi);
      data.min_gradient_permille = std::min(data.min_gradient_permille, glo);
      data.max_gradient_permille = std::max(data.max_gradient_permille, ghi);
      if (std::max(std::abs(a.gradient_permille), std::abs(b.gradient_permille)) >= 0.5) {
        ++data.gradient_intervals;
      }
      if (a.regime != Regime::Coast) ++data.force_intervals;
      if (a.regime == Regime::Braking) ++data.braking_intervals;
    }
    if (logs[li].has_position) check_positions(p, static_cast<int>(li), opt, data.position_issues);
    data.logs.push_back(std::move(p));
  }
  return data;
}

}  // namespace ecorail::fitting
