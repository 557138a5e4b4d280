// Motion: integrates the equation of motion of a Train on a Route over distance, with the
// specific kinetic energy e = v^2/2 as the state (de/ds = (u - W) / M_eff, smooth even at a
// standing start) and time accumulated per substep as 2 h / (v0 + v1), exact for constant
// acceleration. One substep never crosses a route change, so gradient, curve and limit are
// constant inside it (the events of the integrator). Whenever the commanded control would
// leave the speed envelope, the force is reduced (down to full braking) so the train lands on
// it: that is how limits and the final braking curve are followed. The DP transitions (coarse
// substeps, Heun) and the forward re-simulation (fine substeps, RK4) share this one kernel.
#pragma once

#include <cmath>
#include <limits>

#include "physics/control.hpp"
#include "physics/route.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/train.hpp"

namespace ecorail::physics {

struct StepSettings {
  double max_substep_m = 1.0;
  int rk_order = 2;  // 2 (Heun) or 4 (classic Runge-Kutta)
};

// Result of one substep of constant control on constant track.
struct Substep {
  double e_end = 0.0;
  double time_s = 0.0;
  double length_m = 0.0;  // shorter than requested if the train stopped
  double traction_work_J = 0.0;
  double brake_work_J = 0.0;
  // The part of brake_work_J the regenerative brake carries (all of it unless the train has a
  // pneumatic brake): regeneration first, the pneumatic brake only for the excess.
  double regen_brake_work_J = 0.0;
  // Energy drawn for the traction work and fed back from the regenerative braking work, by the
  // efficiency maps at the substep's mean speed and force; set only for a train with maps
  // (Train::has_efficiency_maps), 0 otherwise (the constants apply to the sums, as before).
  double traction_input_J = 0.0;
  double regen_J = 0.0;
  double mean_force_N = 0.0;  // work / length, signed (traction positive)
  Regime regime = Regime::Coast;
  bool stopped = false;       // speed reached zero inside the substep
  double overspeed_ms = 0.0;  // above the envelope at the end (could not brake enough)
};

// Result of advancing over a distance with one control (several substeps).
struct Advance {
  double e_end = 0.0;
  double time_s = 0.0;
  double traction_work_J = 0.0;
  double brake_work_J = 0.0;
  double regen_brake_work_J = 0.0;  // see Substep
  double traction_input_J = 0.0;    // see Substep (trains with efficiency maps only)
  double regen_J = 0.0;
  bool stalled = false;  // stopped before reaching the end position
};

class Motion {
 public:
  Motion(const Train& train, const Route& route, const SpeedEnvelope& envelope)
      : train_(&train), route_(&route), envelope_(&envelope) {}

  // One substep of length h from (s, e) on the segment holding s; h must not cross a segment end.
  // e_cap_end (J/kg) is a further limit on the end state besides the speed envelope, e.g. a
  // moving speed cap evaluated where and when the substep ends; it is supervised like the
  // envelope (the force is reduced, down to full braking, so the train lands on it).
  Substep substep(double s_m, double e, double h_m, Control c, int rk_order,
                  double e_cap_end = std::numeric_limits<double>::infinity()) const;
  // The same on a segment the caller has already found (route().segments()[i] holding s_m, as
  // a cursor along a run finds it): bit for bit substep()'s result without the look-up.
  Substep substep_on(const RouteSegment& seg, double s_m, double e, double h_m, Control c,
                     int rk_order,
                     double e_cap_end = std::numeric_limits<double>::infinity()) const;
  // Advances from s0 to s1 with control c, splitting at route changes and max_substep.
  Advance advance(double s0_m, double e0, double s1_m, Control c, const StepSettings& st) const;
  // The same advance with the speed envelope not supervised. Where the envelope never binds
  // (e_max <= the envelope at every substep end) the result is bit for bit advance()'s; the
  // DP's transition table uses this to integrate a transition once for every stage it fits.
  struct FreeAdvance {
    Advance advance;
    double e_max = 0.0;    // largest e at any substep end
    bool stopped = false;  // some substep came to rest (advance.stalled then needs s1)
    // Where it came to rest, short of s1 (0 when it did not stop): a stall by more than a
    // millimetre and a rounding is a stall wherever the same integration starts.
    double stop_short_of_end_m = 0.0;
  };
  FreeAdvance advance_unsupervised(double s0_m, double e0, double s1_m, Control c,
                                   const StepSettings& st) const;

  // Net specific force (u - W) / M_eff for control c at speed v on a segment, and the force u.
  double applied_force_N(Control c, double v_ms, const RouteSegment& seg) const;

  const Train& train() const { return *train_; }
  const Route& route() const { return *route_; }
  const SpeedEnvelope& envelope() const { return *envelope_; }
  // Total resistance in N at v on a segment: Davis, gradient, curve and tunnel drag.
  double resistance_N(double v_ms, const RouteSegment& seg) const {
    return resistance_N(v_ms, seg.track_N_per_kN(), seg.tunnel_drag_N_per_kN_kmh2);
  }

 private:
  // The same with the segment's track resistance and tunnel drag read once (a substep reads
  // them once and evaluates the force law up to four times).
  double resistance_N(double v_ms, double track_N_per_kN, double tunnel_drag) const {
    const double w = train_->resistance_N(v_ms, track_N_per_kN);
    if (tunnel_drag == 0.0) return w;  // the common case costs one compare
    const double v_kmh = 3.6 * v_ms;
    return w + train_->specific_to_N(tunnel_drag * v_kmh * v_kmh);
  }
  inline double force_for_N(Control c, double v_ms, double w) const;
  // de/ds at specific energy e whose speed v_ms = speed_from_e(e) the caller already has.
  inline double de_ds_at(Control c, double v_ms, double track_N_per_kN, double tunnel_drag,
                         double* force_N) const;
  inline double de_ds(Control c, double e, double track_N_per_kN, double tunnel_drag,
                      double* force_N) const;
  template <bool kSupervised>
  Substep substep_impl(const RouteSegment& seg, double s_m, double e, double h_m, Control c,
                       int rk_order, double e_cap_end) const;
  template <bool kSupervised>
  Advance advance_impl(double s0_m, double e0, double s1_m, Control c, const StepSettings& st,
                       double* e_max, bool* stopped, double* stop_short_m) const;

  const Train* train_;
  const Route* route_;
  const SpeedEnvelope* envelope_;
};

inline double speed_from_e(double e) {
  return e > 0.0 ? std::sqrt(2.0 * e) : 0.0;
}

}  // namespace ecorail::physics
