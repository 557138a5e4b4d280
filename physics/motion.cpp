#include "physics/motion.hpp"

#include <algorithm>

namespace ecorail::physics {

inline double Motion::force_for_N(Control c, double v_ms, double w) const {
  switch (c) {
    case Control::MaxTraction:
      return train_->max_traction_N(v_ms, w);
    case Control::Hold:
      return std::clamp(w, -train_->max_brake_N(v_ms, w), train_->max_traction_N(v_ms, w));
    case Control::Coast:
      return 0.0;
    case Control::MaxBrake:
      return -train_->max_brake_N(v_ms, w);
  }
  return 0.0;
}

double Motion::applied_force_N(Control c, double v_ms, const RouteSegment& seg) const {
  return force_for_N(c, v_ms, resistance_N(v_ms, seg));
}

inline double Motion::de_ds_at(Control c, double v, double track, double tunnel,
                               double* force_N) const {
  const double w = resistance_N(v, track, tunnel);
  *force_N = force_for_N(c, v, w);
  return (*force_N - w) / train_->effective_mass_kg();
}

inline double Motion::de_ds(Control c, double e, double track, double tunnel,
                            double* force_N) const {
  return de_ds_at(c, speed_from_e(e), track, tunnel, force_N);
}

namespace {

// Where the last look-up of this thread landed: substeps move forward along a run, so the
// segment is nearly always the same one or the next (Route::index_at with a hint).
thread_local std::size_t segment_hint = 0;

const RouteSegment& segment_at(const Route& route, double s_m) {
  segment_hint = route.index_at(s_m, segment_hint);
  return route.segments()[segment_hint];
}

Regime classify(double u, double max_traction, double max_brake) {
  constexpr double kFull = 0.99;   // within 1 % of the envelope counts as full
  constexpr double kZero_N = 1.0;  // below 1 N the train is coasting
  if (u > kZero_N)
    return u >= kFull * max_traction ? Regime::FullTraction : Regime::PartialTraction;
  if (u < -kZero_N) return -u >= kFull * max_brake ? Regime::FullBrake : Regime::PartialBrake;
  return Regime::Coast;
}

}  // namespace

Substep Motion::substep(double s_m, double e0, double h, Control c, int rk_order,
                        double e_cap_end) const {
  return substep_impl<true>(segment_at(*route_, s_m), s_m, e0, h, c, rk_order, e_cap_end);
}

Substep Motion::substep_on(const RouteSegment& seg, double s_m, double e0, double h, Control c,
                           int rk_order, double e_cap_end) const {
  return substep_impl<true>(seg, s_m, e0, h, c, rk_order, e_cap_end);
}

template <bool kSupervised>
Substep Motion::substep_impl(const RouteSegment& seg, double s_m, double e0, double h, Control c,
                             int rk_order, double e_cap_end) const {
  const double track = seg.track_N_per_kN();
  const double tunnel = seg.tunnel_drag_N_per_kN_kmh2;
  Substep out;
  double u1, u2, u3, u4;
  double e1;
  double work;
  const double v0 = speed_from_e(e0);
  const double k1 = de_ds_at(c, v0, track, tunnel, &u1);
  if (rk_order >= 4) {
    const double k2 = de_ds(c, e0 + 0.5 * h * k1, track, tunnel, &u2);
    const double k3 = de_ds(c, e0 + 0.5 * h * k2, track, tunnel, &u3);
    const double k4 = de_ds(c, e0 + h * k3, track, tunnel, &u4);
    e1 = e0 + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    work = h / 6.0 * (u1 + 2.0 * u2 + 2.0 * u3 + u4);
  } else {
    const double k2 = de_ds(c, e0 + h * k1, track, tunnel, &u2);
    e1 = e0 + 0.5 * h * (k1 + k2);
    work = 0.5 * h * (u1 + u2);
  }
  out.length_m = h;

  if (e1 <= 0.0) {
    // Stopped inside the substep: e falls nearly linearly, so locate the stop by proportion.
    const double frac = e0 > 0.0 ? e0 / (e0 - e1) : 0.0;
    out.stopped = true;
    out.length_m = h * frac;
    out.e_end = 0.0;
    out.time_s = v0 > 0.0 ? 2.0 * out.length_m / v0 : 0.0;
    work *= frac;
  } else {
    const double e_env = kSupervised ? std::min(envelope_->e_at(s_m + h), e_cap_end)
                                     : std::numeric_limits<double>::infinity();
    if (kSupervised && e1 > e_env) {
      // Leaving the envelope: apply the constant force that lands on it, but no more braking
      // than the train has.
      const double e_mid = 0.5 * (e0 + e_env);
      const double v_mid = speed_from_e(e_mid);
      const double w = resistance_N(v_mid, track, tunnel);
      const double m = train_->effective_mass_kg();
      double u = m * (e_env - e0) / h + w;
      const double u_min = -train_->max_brake_N(v_mid, w);
      e1 = e_env;
      if (u < u_min) {
        u = u_min;
        e1 = e0 + h * (u - w) / m;
        out.overspeed_ms = speed_from_e(e1) - speed_from_e(e_env);
      }
      work = u * h;
      out.regime = classify(u, train_->max_traction_N(v_mid, w), train_->max_brake_N(v_mid, w));
    } else {
      switch (c) {
        case Control::MaxTraction:
          out.regime = Regime::FullTraction;
          break;
        case Control::Coast:
          out.regime = Regime::Coast;
          break;
        case Control::MaxBrake:
          out.regime = Regime::FullBrake;
          break;
        case Control::Hold: {
          const double w = resistance_N(v0, track, tunnel);
          out.regime = classify(u1, train_->max_traction_N(v0, w), train_->max_brake_N(v0, w));
          break;
        }
      }
    }
    out.e_end = e1;
    const double v1 = speed_from_e(e1);
    if (v0 + v1 <= 0.0) {
      out.stopped = true;  // standing still and not moving off
      out.length_m = 0.0;
      work = 0.0;
    } else {
      out.time_s = 2.0 * h / (v0 + v1);
    }
  }
  if (work > 0.0) {
    out.traction_work_J = work;
  } else {
    out.brake_work_J = -work;
    out.regen_brake_work_J = out.brake_work_J;
    if (train_->pneumatic_brake_N > 0.0 && out.length_m > 0.0) {
      // Regeneration carries what it can (its envelope at the mean speed), the pneumatic brake
      // the rest: every joule the regenerative brake takes is partly recovered, every joule the
      // pneumatic one takes is lost, and both brake alike, so regeneration first is optimal.
      const double v_mid = speed_from_e(0.5 * (e0 + out.e_end));
      out.regen_brake_work_J =
          std::min(out.brake_work_J, train_->braking.force_N(v_mid) * out.length_m);
    }
  }
  out.mean_force_N = out.length_m > 0.0 ? work / out.length_m : u1;
  if (train_->has_efficiency_maps() && out.length_m > 0.0) {
    const double v_mid = speed_from_e(0.5 * (e0 + out.e_end));
    out.traction_input_J =
        out.traction_work_J / train_->traction_efficiency_at(v_mid, out.mean_force_N);
    out.regen_J = out.regen_brake_work_J *
                  train_->regen_efficiency_at(v_mid, out.regen_brake_work_J / out.length_m);
  }
  return out;
}

Advance Motion::advance(double s0, double e0, double s1, Control c, const StepSettings& st) const {
  return advance_impl<true>(s0, e0, s1, c, st, nullptr, nullptr, nullptr);
}

Motion::FreeAdvance Motion::advance_unsupervised(double s0, double e0, double s1, Control c,
                                                 const StepSettings& st) const {
  FreeAdvance out;
  out.advance =
      advance_impl<false>(s0, e0, s1, c, st, &out.e_max, &out.stopped, &out.stop_short_of_end_m);
  return out;
}

template <bool kSupervised>
Advance Motion::advance_impl(double s0, double e0, double s1, Control c, const StepSettings& st,
                             double* e_max, bool* stopped, double* stop_short_m) const {
  Advance out;
  double s = s0;
  double e = e0;
  while (s < s1 - 1e-9) {
    const RouteSegment& seg = segment_at(*route_, s);
    const double next = std::min({s1, seg.end_m, s + st.max_substep_m});
    const Substep sub = substep_impl<kSupervised>(seg, s, e, next - s, c, st.rk_order,
                                                  std::numeric_limits<double>::infinity());
    if (e_max) *e_max = std::max(*e_max, sub.e_end);
    if (stopped) *stopped = *stopped || sub.stopped;
    out.time_s += sub.time_s;
    out.traction_work_J += sub.traction_work_J;
    out.brake_work_J += sub.brake_work_J;
    out.regen_brake_work_J += sub.regen_brake_work_J;
    out.traction_input_J += sub.traction_input_J;
    out.regen_J += sub.regen_J;
    e = sub.e_end;
    if (sub.stopped) {
      // A stop that lands on the end position (within a millimetre) is an arrival, not a stall.
      out.stalled = s + sub.length_m < s1 - 1e-3;
      if (stop_short_m) *stop_short_m = s1 - (s + sub.length_m);
      break;
    }
    s = next;
  }
  out.e_end = e;
  return out;
}

}  // namespace ecorail::physics
