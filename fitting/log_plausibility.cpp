#include "fitting/log_plausibility.hpp"

#include <algorithm>
#include <cmath>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {

namespace {

std::string kmh_text(double v_ms) {
  if (!std::isfinite(units::ms_to_kmh(v_ms))) return data::format_number(v_ms) + " m/s";
  return data::format_number(std::round(units::ms_to_kmh(v_ms) * 100.0) / 100.0) + " km/h";
}

std::string accel_text(double a) {
  return data::format_number(std::round(a * 100.0) / 100.0) + " m/s^2";
}

double curve_term(double radius_m) {
  return radius_m > 0.0 ? 600.0 / radius_m : 0.0;
}

}  // namespace

AccelBounds accel_bounds(const physics::Train& t, double v_ms, double gradient_permille,
                         double curve_N_per_kN) {
  const double m_eff = t.effective_mass_kg();
  // Specific forces in N/kN turned into m/s^2 of the effective mass.
  const double per_N_per_kN = t.gravity_m_s2 / 1000.0 / (1.0 + t.rotating_mass_factor);
  const double resistance = t.davis_N_per_kN(v_ms) + curve_N_per_kN;
  AccelBounds b;
  // Motoring: the envelope or the acceleration limit, whichever allows more (a log of a train
  // without the limit is still plausible), plus a descent pulling the train.
  b.accel_m_s2 = std::max(t.max_accel_m_s2, t.traction.force_N(v_ms) / m_eff) +
                 std::max(-gradient_permille, 0.0) * per_N_per_kN;
  // Braking: the envelope or the deceleration limit, plus resistance and a climb.
  b.decel_m_s2 = std::max(t.max_decel_m_s2, t.braking.force_N(v_ms) / m_eff) +
                 (resistance + std::max(gradient_permille, 0.0)) * per_N_per_kN;
  return b;
}

void check_log_plausible(const Log& log, const physics::Train& train,
                         const PlausibilityOptions& o) {
  const double v_max = train.max_speed_ms + units::kmh_to_ms(o.speed_margin_kmh);
  const auto& rows = log.rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const LogRow& r = rows[i];
    if (!(r.speed_ms <= v_max)) {
      throw data::InputError(
          log.label, r.source_row, log.speed_column,
          "a speed the train can run: at most its maximum speed " + kmh_text(train.max_speed_ms) +
              " plus " + data::format_number(o.speed_margin_kmh) + " km/h (--train names the " +
              "train of the log); got " + kmh_text(r.speed_ms));
    }
    if (i == 0) continue;
    const LogRow& p = rows[i - 1];
    const double dt = r.time_s - p.time_s;
    const double a = (r.speed_ms - p.speed_ms) / dt;
    // The bound over the interval: the more permissive end (the envelopes fall with speed).
    AccelBounds b{0.0, 0.0};
    for (const LogRow* end : {&p, &r}) {
      const AccelBounds e = accel_bounds(train, end->speed_ms, end->gradient_permille,
                                         curve_term(end->curve_radius_m));
      b.accel_m_s2 = std::max(b.accel_m_s2, e.accel_m_s2);
      b.decel_m_s2 = std::max(b.decel_m_s2, e.decel_m_s2);
    }
    const double hi = b.accel_m_s2 + o.accel_margin_m_s2;
    const double lo = -(b.decel_m_s2 + o.accel_margin_m_s2);
    if (a > hi || a < lo) {
      throw data::InputError(
          log.label, r.source_row, log.speed_column,
          "a speed the train can reach from row " + std::to_string(p.source_row) + " (" +
              kmh_text(p.speed_ms) + ") in " + data::format_number(dt) +
              " s: an acceleration between " + accel_text(lo) + " and " + accel_text(hi) +
              " (its traction and braking envelopes plus " + accel_text(o.accel_margin_m_s2) +
              " for measurement error); got " + kmh_text(r.speed_ms) + ", " + accel_text(a));
    }
  }
}

void check_logs_plausible(const std::vector<Log>& logs, const physics::Train& train,
                          const PlausibilityOptions& options) {
  for (const auto& log : logs) check_log_plausible(log, train, options);
}

}  // namespace ecorail::fitting
