// Physical plausibility of a driving log against the train it is calibrated from, checked before
// any fit. A robust loss only discounts an outlier; it does not stop it from pulling the
// estimate (one tenfold speed typo, 615 km/h for an 80 km/h train, moves the Davis
// coefficients although the row is flagged). So a row that no train of this model could have
// produced is refused up front with one clear error instead: a speed above the train's maximum
// speed, or a speed change from the previous row that needs an acceleration beyond the train's
// traction or braking envelope (and its acceleration limits, the gradient and the resistance).
// Both bounds carry a stated allowance for measurement error, wide enough for the gross errors
// the robust loss is there for (a few km/h on one row).
#pragma once

#include <vector>

#include "fitting/log_reader.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting {

struct PlausibilityOptions {
  // Allowance above the train's maximum speed (noise, overspeed within the protection margin).
  double speed_margin_kmh = 5.0;
  // Allowance beyond the acceleration the envelopes allow between two rows: 3 m/s^2 is a
  // speed error of about 11 km/h on a one-second row, above the gross errors the robust loss
  // discounts and far below what a mistyped digit gives.
  double accel_margin_m_s2 = 3.0;
};

// Largest acceleration (m/s^2, positive) and largest deceleration (m/s^2, positive) the train
// can show at speed v on a track of gradient (per mille, + uphill) and curve term (N/kN).
struct AccelBounds {
  double accel_m_s2 = 0.0;
  double decel_m_s2 = 0.0;
};
AccelBounds accel_bounds(const physics::Train& train, double v_ms, double gradient_permille,
                         double curve_N_per_kN);

// Throws data::InputError(file, row, speed column, what was expected and found) for the first
// implausible row of log.
void check_log_plausible(const Log& log, const physics::Train& train,
                         const PlausibilityOptions& options = {});
void check_logs_plausible(const std::vector<Log>& logs, const physics::Train& train,
                          const PlausibilityOptions& options = {});

}  // namespace ecorail::fitting
