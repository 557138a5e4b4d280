#include "data/plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "physics/units.hpp"

namespace ecorail::data::plausible {

namespace {

std::string range(double lo, double hi, const char* unit) {
  return "a value in [" + format_number(lo) + ", " + format_number(hi) + "] " + unit;
}

void require_in(double value, double lo, double hi, const char* unit, const std::string& file,
                const std::string& field) {
  if (!(value >= lo && value <= hi)) {
    throw InputError(file, 0, field,
                     range(lo, hi, unit) + " (plausibility range); got " + format_number(value));
  }
}

// The envelope sampled every 0.5 km/h over [0, max speed] must be finite, non-negative and
// at most kMaxForcePerMass_m_s2 times the mass; returns the largest force found (N).
double check_envelope(const physics::ForceEnvelope& envelope, const physics::Train& train,
                      const std::string& file, const std::string& field) {
  const double vmax_kmh = units::ms_to_kmh(train.max_speed_ms);
  const double limit_N = kMaxForcePerMass_m_s2 * train.mass_kg;
  double largest_N = 0.0;
  const int samples = static_cast<int>(std::ceil(vmax_kmh / 0.5));
  for (int k = 0; k <= samples; ++k) {
    const double v_kmh = std::min(vmax_kmh, 0.5 * k);
    const double f_N = envelope.force_N(units::kmh_to_ms(v_kmh));
    if (!(std::isfinite(f_N) && f_N >= 0.0 && f_N <= limit_N)) {
      throw InputError(file, 0, field,
                       "a force of at most " + format_number(kMaxForcePerMass_m_s2) +
                           " m/s^2 times the mass (" + format_number(limit_N / 1000.0) +
                           " kN) at every speed up to max_speed_kmh (plausibility range); got " +
                           format_number(f_N / 1000.0) + " kN at " + format_number(v_kmh) +
                           " km/h");
    }
    largest_N = std::max(largest_N, f_N);
  }
  return largest_N;
}

}  // namespace

void check_train(const physics::Train& train, const std::string& file) {
  require_in(train.mass_kg / 1000.0, kMinMass_t, kMaxMass_t, "t", file, "mass_t");
  require_in(train.rotating_mass_factor, 0.0, kMaxRotatingMassFactor, "", file,
             "rotating_mass_factor");
  require_in(train.gravity_m_s2, kMinGravity_m_s2, kMaxGravity_m_s2, "m/s^2", file, "gravity_m_s2");
  require_in(units::ms_to_kmh(train.max_speed_ms), 1e-9, kMaxTrainSpeed_kmh, "km/h", file,
             "max_speed_kmh");
  // An absent comfort limit is no limit (infinity, as a TTOBench train without one reads); a
  // stated one must be plausible.
  if (train.max_accel_m_s2 != std::numeric_limits<double>::infinity()) {
    require_in(train.max_accel_m_s2, 1e-9, kMaxAccel_m_s2, "m/s^2", file, "max_accel_m_s2");
  }
  if (train.max_decel_m_s2 != std::numeric_limits<double>::infinity()) {
    require_in(train.max_decel_m_s2, 1e-9, kMaxAccel_m_s2, "m/s^2", file, "max_decel_m_s2");
  }
  // A negative coefficient makes resistance push the train: energy from nowhere.
  require_in(train.davis.A, 0.0, kMaxDavisA_N_per_kN, "N/kN", file, "davis.A");
  require_in(train.davis.B, 0.0, kMaxDavisB_N_per_kN_kmh, "N/kN per km/h", file, "davis.B");
  require_in(train.davis.C, 0.0, kMaxDavisC_N_per_kN_kmh2, "N/kN per (km/h)^2", file, "davis.C");
  check_envelope(train.traction, train, file, "traction");
  const double brake_N = check_envelope(train.braking, train, file, "braking");
  const double start_N = train.traction.force_N(0.0);
  const double level_start_N = train.resistance_N(0.0, 0.0);
  if (!(start_N > level_start_N)) {
    throw InputError(file, 0, "traction",
                     "a force at 0 km/h above the starting resistance on level track (" +
                         format_number(level_start_N / 1000.0) + " kN); got " +
                         format_number(start_N / 1000.0) + " kN");
  }
  require_in(train.auxiliary_power_W / 1000.0, 0.0, kMaxAuxiliaryPower_kW, "kW", file,
             "auxiliary_power_kW");
  if (!(brake_N + train.pneumatic_brake_N > 0.0)) {
    throw InputError(file, 0, "braking", "a braking force above 0 kN at some speed; got none");
  }
}

void check_can_start(const physics::Train& train, const physics::Route& route,
                     const std::string& train_file) {
  const auto& segments = route.segments();
  if (segments.empty()) return;
  const auto steepest = std::max_element(segments.begin(), segments.end(),
                                         [](const physics::RouteSegment& a, const auto& b) {
                                           return a.track_N_per_kN() < b.track_N_per_kN();
                                         });
  const double start_N = train.traction.force_N(0.0);
  const double resistance_N = train.resistance_N(0.0, steepest->track_N_per_kN());
  if (start_N > resistance_N) return;
  throw InputError(train_file, 0, "traction",
                   "a force at 0 km/h that starts the train on the steepest climb of " +
                       route.from_name() + " -> " + route.to_name() + " (" +
                       format_number(steepest->gradient_permille) + " per mille at " +
                       format_number(steepest->start_m) + " m needs more than " +
                       format_number(resistance_N / 1000.0) + " kN); got " +
                       format_number(start_N / 1000.0) + " kN");
}

}  // namespace ecorail::data::plausible
