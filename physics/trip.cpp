#include "physics/trip.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecorail::physics {

struct Trip::Data {
  std::vector<Sample> samples;
  std::vector<Route> routes;
  std::vector<double> section_start_m;
  std::vector<TripStop> stops;  // relative to the departure
  EnergyLedger ledger;
  double running_time_s = 0.0;
  double regen_efficiency = 0.0;
};

namespace {

// Position travelled into a step after tau seconds, at constant acceleration; exact at both
// ends so that energies over sub-intervals telescope to the step's work.
double distance_into(const Trip::Sample& a, const Trip::Sample& b, double tau) {
  const double dt = b.t_s - a.t_s;
  if (tau <= 0.0) return 0.0;
  if (tau >= dt) return b.s_m - a.s_m;
  const double accel = (b.v_ms - a.v_ms) / dt;
  return std::min(b.s_m - a.s_m, a.v_ms * tau + 0.5 * accel * tau * tau);
}

}  // namespace

Trip::Trip(const std::vector<TripSection>& sections, double departure_s, double regen_efficiency)
    : offset_s_(departure_s) {
  if (sections.empty()) throw std::invalid_argument("a trip needs at least one section");
  auto data = std::make_shared<Data>();
  data->regen_efficiency = regen_efficiency;
  std::size_t samples = 1;
  for (const TripSection& sec : sections)
    if (sec.sim != nullptr) samples += sec.sim->trace.size() + 1;
  data->samples.reserve(samples);
  data->routes.reserve(sections.size());
  data->section_start_m.reserve(sections.size());
  data->stops.reserve(sections.size() + 1);
  double t = 0.0, s0 = 0.0;
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const TripSection& sec = sections[i];
    if (sec.route == nullptr || sec.sim == nullptr || sec.sim->trace.empty()) {
      throw std::invalid_argument("a trip section needs a route and a simulated trace");
    }
    const auto& trace = sec.sim->trace;
    data->routes.push_back(*sec.route);
    data->section_start_m.push_back(s0);
    if (i == 0) {
      const TracePoint& p = trace.front();
      data->samples.push_back({0.0, s0 + p.s_m, p.v_ms, 0.0, 0.0, p.regime, 0, false});
      data->stops.push_back({sec.route->from_name(), s0, 0.0, 0.0, 0.0});
    }
    for (std::size_t k = 1; k < trace.size(); ++k) {
      const TracePoint& p = trace[k];
      data->samples.push_back({t + p.t_s, s0 + p.s_m, p.v_ms, p.accel_m_s2, p.force_N, p.regime,
                               static_cast<int>(i), false});
    }
    const EnergyLedger& e = sec.sim->energy;
    data->ledger.traction_work_J += e.traction_work_J;
    data->ledger.brake_work_J += e.brake_work_J;
    data->ledger.regen_J += e.regen_J;
    data->ledger.traction_input_J += e.traction_input_J;
    data->running_time_s += sec.sim->running_time_s;
    t += sec.sim->running_time_s;
    s0 += sec.route->length_m();
    const bool last = i + 1 == sections.size();
    const double dwell = last ? 0.0 : sec.dwell_after_s;
    data->stops.push_back({sec.route->to_name(), s0, t, t + dwell, dwell});
    if (dwell > 0.0) {
      Sample standing = data->samples.back();
      standing.t_s = t + dwell;
      standing.v_ms = standing.accel_m_s2 = standing.force_N = 0.0;
      standing.regime = Regime::Coast;
      standing.dwelling = true;
      data->samples.push_back(standing);
      t += dwell;
    }
  }
  data_ = std::move(data);
}

Trip Trip::shifted(double departure_s) const {
  Trip out = *this;
  out.offset_s_ = departure_s;
  return out;
}

double Trip::arrival_s() const {
  return offset_s_ + data_->stops.back().arrival_s;
}
double Trip::length_m() const {
  return data_->samples.back().s_m;
}
double Trip::running_time_s() const {
  return data_->running_time_s;
}
std::size_t Trip::section_count() const {
  return data_->routes.size();
}
const Route& Trip::route(std::size_t section) const {
  return data_->routes.at(section);
}
double Trip::section_start_m(std::size_t section) const {
  return data_->section_start_m.at(section);
}
const EnergyLedger& Trip::ledger() const {
  return data_->ledger;
}
double Trip::regen_efficiency() const {
  return data_->regen_efficiency;
}
const std::vector<Trip::Sample>& Trip::samples() const {
  return data_->samples;
}

TripStop Trip::stop(std::size_t k) const {
  TripStop s = data_->stops.at(k);
  s.arrival_s += offset_s_;
  s.departure_s += offset_s_;
  return s;
}

std::vector<TripStop> Trip::stops() const {
  std::vector<TripStop> out;
  for (std::size_t k = 0; k < data_->stops.size(); ++k) out.push_back(stop(k));
  return out;
}

TripState Trip::state_at(double t_clock) const {
  const auto& smp = data_->samples;
  const double tau = t_clock - offset_s_;
  TripState st;
  st.t_s = t_clock;
  if (tau <= 0.0 || tau >= smp.back().t_s) {
    const Sample& end = tau <= 0.0 ? smp.front() : smp.back();
    st.position_m = end.s_m;
    st.speed_ms = tau <= 0.0 ? end.v_ms : 0.0;
    st.section = tau <= 0.0 ? 0 : static_cast<int>(section_count()) - 1;
    st.before_departure = tau < 0.0;
    st.after_arrival = tau > smp.back().t_s;
    return st;
  }
  // The step (k-1, k] holding tau: the first sample at or after tau.
  const auto it = std::lower_bound(smp.begin() + 1, smp.end(), tau,
                                   [](const Sample& p, double t) { return p.t_s < t; });
  const Sample& b = *it;
  const Sample& a = *(it - 1);
  st.section = b.section;
  st.dwelling = b.dwelling;
  st.force_N = b.force_N;
  st.regime = b.regime;
  if (b.dwelling) {
    st.position_m = b.s_m;
    return st;
  }
  const double dt = b.t_s - a.t_s;
  const double into = tau - a.t_s;
  st.accel_m_s2 = dt > 0.0 ? (b.v_ms - a.v_ms) / dt : 0.0;
  st.speed_ms = std::max(0.0, a.v_ms + st.accel_m_s2 * into);
  st.position_m = a.s_m + distance_into(a, b, into);
  return st;
}

double Trip::time_at(double position_m) const {
  const auto& smp = data_->samples;
  if (!(position_m >= smp.front().s_m - 1e-9 && position_m <= smp.back().s_m + 1e-9)) {
    throw std::out_of_range("position outside the trip");
  }
  const auto it = std::lower_bound(smp.begin(), smp.end(), position_m,
                                   [](const Sample& p, double s) { return p.s_m < s; });
  return time_between(static_cast<std::size_t>(it - smp.begin()), position_m);
}

double Trip::time_at(double position_m, std::size_t* hint) const {
  const auto& smp = data_->samples;
  if (!(position_m >= smp.front().s_m - 1e-9 && position_m <= smp.back().s_m + 1e-9)) {
    throw std::out_of_range("position outside the trip");
  }
  // The first sample at or past the position (std::lower_bound's answer), walked to from the
  // hint when it is near, else searched.
  const std::size_t size = smp.size();
  std::size_t i = std::min(*hint, size);
  constexpr int kWalk = 16;
  int steps = 0;
  while (i > 0 && smp[i - 1].s_m >= position_m && steps < kWalk) --i, ++steps;
  while (i < size && smp[i].s_m < position_m && steps < kWalk) ++i, ++steps;
  const bool found =
      (i == 0 || smp[i - 1].s_m < position_m) && (i == size || smp[i].s_m >= position_m);
  if (!found)
    i = static_cast<std::size_t>(
        std::lower_bound(smp.begin(), smp.end(), position_m,
                         [](const Sample& p, double s) { return p.s_m < s; }) -
        smp.begin());
  *hint = i;
  return time_between(i, position_m);
}

double Trip::time_between(std::size_t index, double position_m) const {
  const auto& smp = data_->samples;
  if (index == 0) return offset_s_ + smp.front().t_s;
  if (index == smp.size()) return offset_s_ + smp.back().t_s;
  const Sample& b = smp[index];
  const Sample& a = smp[index - 1];
  const double d = position_m - a.s_m;
  const double h = b.s_m - a.s_m;
  const double dt = b.t_s - a.t_s;
  if (h <= 0.0 || dt <= 0.0) return offset_s_ + b.t_s;
  // Solve a.v tau + accel tau^2 / 2 = d in the form that stays exact when accel -> 0.
  const double accel = (b.v_ms - a.v_ms) / dt;
  const double disc = std::max(0.0, a.v_ms * a.v_ms + 2.0 * accel * d);
  const double denom = a.v_ms + std::sqrt(disc);
  const double tau = denom > 0.0 ? 2.0 * d / denom : dt * d / h;
  return offset_s_ + a.t_s + std::min(tau, dt);
}

PowerBins Trip::power_bins(double start_s, double step_s, std::size_t count) const {
  if (!(step_s > 0.0) || !std::isfinite(start_s)) {
    throw std::invalid_argument("power bins need a positive step and a finite start");
  }
  PowerBins out;
  out.start_s = start_s;
  out.step_s = step_s;
  out.traction_W.assign(count, 0.0);
  out.braking_W.assign(count, 0.0);
  const auto& smp = data_->samples;
  // Bin edges are start + k step; a step's energy is split at the edges inside it.
  const double origin = start_s - offset_s_;  // bin 0's start on the trip's time axis
  for (std::size_t k = 1; k < smp.size(); ++k) {
    const Sample& a = smp[k - 1];
    const Sample& b = smp[k];
    const double work = b.force_N * (b.s_m - a.s_m);
    if (b.dwelling || work == 0.0 || !(b.t_s > a.t_s)) continue;
    std::vector<double>& bins = work > 0.0 ? out.traction_W : out.braking_W;
    const double sign = work > 0.0 ? 1.0 : -1.0;
    auto bin = static_cast<long>(std::floor((a.t_s - origin) / step_s));
    if (bin >= static_cast<long>(count) || b.t_s <= origin) continue;
    double done_m = 0.0;  // distance of the step already counted
    if (bin < 0) {
      bin = 0;
      done_m = distance_into(a, b, origin - a.t_s);
    }
    for (; bin < static_cast<long>(count); ++bin) {
      const double edge = origin + static_cast<double>(bin + 1) * step_s;  // end of this bin
      const double upto = edge >= b.t_s ? b.s_m - a.s_m : distance_into(a, b, edge - a.t_s);
      bins[static_cast<std::size_t>(bin)] += sign * b.force_N * (upto - done_m);
      done_m = upto;
      if (edge >= b.t_s) break;
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    out.traction_W[i] /= step_s;
    out.braking_W[i] /= step_s;
  }
  out.regen_W = out.braking_W;
  for (double& p : out.regen_W) p *= data_->regen_efficiency;
  return out;
}

PowerBins Trip::power_bins(double step_s) const {
  if (!(step_s > 0.0)) throw std::invalid_argument("power bins need a positive step");
  const double start = std::floor(offset_s_ / step_s) * step_s;
  const double end = arrival_s();
  const auto count = static_cast<std::size_t>(std::ceil((end - start) / step_s)) + 1;
  return power_bins(start, step_s, count);
}

}  // namespace ecorail::physics
