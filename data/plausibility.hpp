// Physical plausibility ranges for loaded lines and trains. The readers check syntax and sign
// (a number, a positive limit); these ranges refuse inputs that parse but describe no railway
// the model is meant for (a gradient of 1e308 per mille, a curve of 1 cm radius, a negative
// Davis coefficient that turns resistance into propulsion, a train that cannot move itself).
// Each is one InputError naming the file, row and field and the range (docs/formats.md,
// "Plausibility ranges"). The ranges are wide on purpose: every real adhesion railway, metro, tram
// and freight train fits.
#pragma once

#include <string>

#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::data::plausible {

// Line tables.
inline constexpr double kMaxGradient_permille = 100.0;  // |gradient|; adhesion lines stay < 90
inline constexpr double kMinCurveRadius_m = 10.0;       // 0 = straight; tram curves are >= 15 m
inline constexpr double kMaxSpeedLimit_kmh = 600.0;
inline constexpr double kMaxKmPost_m = 1e7;  // |km post|: 10 000 km

// Trains.
inline constexpr double kMinMass_t = 1.0;
inline constexpr double kMaxMass_t = 50000.0;
inline constexpr double kMaxRotatingMassFactor = 1.0;
inline constexpr double kMinGravity_m_s2 = 9.7;  // g on the Earth's surface is 9.76 to 9.84
inline constexpr double kMaxGravity_m_s2 = 9.9;
inline constexpr double kMaxTrainSpeed_kmh = 600.0;
inline constexpr double kMaxAccel_m_s2 = 5.0;  // limits on dv/dt; metros use about 1.3
inline constexpr double kMaxDavisA_N_per_kN = 100.0;
inline constexpr double kMaxDavisB_N_per_kN_kmh = 10.0;
inline constexpr double kMaxDavisC_N_per_kN_kmh2 = 1.0;
inline constexpr double kMaxAuxiliaryPower_kW = 10000.0;  // a long EMU draws about 500 kW
inline constexpr double kMaxForcePerMass_m_s2 = 20.0;     // envelope force / mass at any speed
inline constexpr double kMaxForce_kN = kMaxForcePerMass_m_s2 * kMaxMass_t;  // fit points, logs

// Checks a loaded train against the ranges above (field names as in the train TOML): mass,
// gravity, limits, non-negative Davis coefficients, envelopes finite and within
// kMaxForcePerMass_m_s2 over [0, max speed], traction at standstill above the level-track
// starting resistance, a braking force somewhere. Throws InputError(file, 0, field, ...).
void check_train(const physics::Train& train, const std::string& file);

// The train must be able to start from rest on the steepest climb of the route it runs
// (gradient plus curve resistance): otherwise no run exists and a solver would only report
// nonsense. Throws InputError naming train_file, field 'traction' and the climb.
void check_can_start(const physics::Train& train, const physics::Route& route,
                     const std::string& train_file);

}  // namespace ecorail::data::plausible
