// Train: a single-mass-point model of one train. It carries the traction and braking envelopes,
// the Davis resistance (N/kN with v in km/h, the convention of the contest and of most metro
// literature), the rotating-mass factor, acceleration limits on the net acceleration, and the
// traction and regeneration efficiencies. The equation of motion is
//   M (1 + rho) dv/dt = u - W(v, s),   -B(v) <= u <= F(v),   a_min <= dv/dt <= a_max,
// with W = (w0(v) + w_track(s)) * M g / 1000. Resistance uses the static mass M; inertia uses
// the effective mass M (1 + rho).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "physics/force_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail::physics {

struct DavisCoefficients {
  double A = 0.0;  // N/kN
  double B = 0.0;  // N/kN per km/h
  double C = 0.0;  // N/kN per (km/h)^2
};

// Extra Davis C coefficient inside a tunnel of a given cross-section (TTOBench's 'tunnel
// resistance'): the train's drag grows with speed squared more in a narrow tunnel.
struct TunnelDrag {
  double cross_section_m2 = 0.0;
  double C_kN_per_kmh2 = 0.0;  // added to the train's quadratic resistance, in kN / (km/h)^2
};

// An efficiency as a table over speed and the magnitude of the force at the wheel (traction
// or regenerative braking): bilinear between the table's points, held at its edges outside.
// Empty: the train's constant efficiency applies. Energy drawn (or fed back) is then measured
// substep by substep at the substep's mean speed and force, and the DP minimises that.
struct EfficiencyMap {
  std::vector<double> speeds_ms;  // ascending, at least 2
  std::vector<double> forces_N;   // ascending, from 0 up, at least 2
  std::vector<double> values;     // speeds_ms.size() x forces_N.size(), row by speed, in (0, 1]
  bool empty() const { return values.empty(); }
  double at(double v_ms, double force_N) const;
};

struct Train {
  std::string name;
  double mass_kg = 0.0;
  double rotating_mass_factor = 0.0;
  double gravity_m_s2 = 9.8;
  double max_speed_ms = 0.0;
  double max_accel_m_s2 = 1.0;  // limit on dv/dt while motoring
  double max_decel_m_s2 = 1.0;  // limit on -dv/dt while braking
  double traction_efficiency = 1.0;
  double regen_efficiency = 0.95;
  DavisCoefficients davis;
  ForceEnvelope traction;
  ForceEnvelope braking;  // the regenerative brake: it regenerates (regen_efficiency)
  // A constant braking force beyond the regenerative envelope (pneumatic/friction brake): it
  // brakes but regenerates nothing. 0 (the reference train): all braking is regenerative.
  double pneumatic_brake_N = 0.0;
  // Length (m); 0 = a point mass. The route builder then holds a limit until the tail has
  // passed it and averages gradient, curve and tunnel forces over the train.
  double length_m = 0.0;
  std::vector<TunnelDrag> tunnel_drag;  // by cross-section, ascending; empty = no data
  // Auxiliary power (lighting, air conditioning, compressors), drawn at all times, dwells
  // included. At a fixed running time it adds the same energy to every way of driving, so it
  // changes no optimum; it is reported (auxiliary_energy_kJ) and counted by the power network.
  double auxiliary_power_W = 0.0;
  // Efficiencies over speed and force where the data give them (empty: the constants above).
  EfficiencyMap traction_efficiency_map;
  EfficiencyMap regen_efficiency_map;

  bool has_efficiency_maps() const {
    return !traction_efficiency_map.empty() || !regen_efficiency_map.empty();
  }
  double traction_efficiency_at(double v_ms, double force_N) const {
    return traction_efficiency_map.empty() ? traction_efficiency
                                           : traction_efficiency_map.at(v_ms, force_N);
  }
  double regen_efficiency_at(double v_ms, double force_N) const {
    return regen_efficiency_map.empty() ? regen_efficiency : regen_efficiency_map.at(v_ms, force_N);
  }

  double effective_mass_kg() const { return mass_kg * (1.0 + rotating_mass_factor); }
  // Converts a specific resistance in N/kN into a force in N for this train's weight.
  double specific_to_N(double w_N_per_kN) const {
    return w_N_per_kN * mass_kg * gravity_m_s2 / 1000.0;
  }
  // Davis specific resistance w0 in N/kN at v (m/s). This and the force limits below are
  // inline: the forward re-simulation evaluates them several times per 5 cm step.
  double davis_N_per_kN(double v_ms) const {
    const double v = units::ms_to_kmh(v_ms);
    return davis.A + v * (davis.B + v * davis.C);
  }
  // Total resistance in N at speed v for a track term (gradient + curve) in N/kN.
  double resistance_N(double v_ms, double track_N_per_kN) const {
    return specific_to_N(davis_N_per_kN(v_ms) + track_N_per_kN);
  }
  // Largest traction force applicable at v against resistance W: the envelope, reduced where the
  // net acceleration would exceed max_accel.
  double max_traction_N(double v_ms, double resistance_N) const {
    const double limit = effective_mass_kg() * max_accel_m_s2 + resistance_N;
    return std::max(0.0, std::min(traction.force_N(v_ms), limit));
  }
  // Largest braking force (a positive number) applicable at v against resistance W: the
  // regenerative envelope plus the pneumatic brake, reduced to keep within max_decel.
  double max_brake_N(double v_ms, double resistance_N) const {
    // dv/dt = (-b - W) / M_eff >= -max_decel  <=>  b <= M_eff max_decel - W
    const double limit = effective_mass_kg() * max_decel_m_s2 - resistance_N;
    return std::max(0.0, std::min(braking.force_N(v_ms) + pneumatic_brake_N, limit));
  }
};

}  // namespace ecorail::physics
