#include "energy/power_flow_balance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecorail::energy {

PowerBalance::PowerBalance(std::vector<const PowerProfile*> profiles, double horizon_s)
    : profiles_(std::move(profiles)), departure_s_(profiles_.size(), -1) {
  if (profiles_.empty()) throw std::invalid_argument("a power balance needs at least one train");
  ticks_per_second_ = profiles_.front()->ticks_per_second();
  sections_ = profiles_.front()->sections();
  for (const PowerProfile* p : profiles_) check_grid(*p);
  bins_ = static_cast<long>(std::ceil(horizon_s * ticks_per_second_)) + 1;
  traction_bins_.assign(static_cast<std::size_t>(sections_) * bins_, 0);
  regen_bins_.assign(traction_bins_.size(), 0);
}

void PowerBalance::check_grid(const PowerProfile& profile) const {
  if (profile.ticks_per_second() != ticks_per_second_ || profile.sections() != sections_)
    throw std::invalid_argument("every profile of a power balance needs the same grid");
}

void PowerBalance::add(int train, int departure_s, int sign) {
  const PowerProfile& p = *profiles_[train];
  const long base = static_cast<long>(departure_s) * ticks_per_second_;
  if (departure_s < 0 || base + p.span_bins() > bins_)
    throw std::out_of_range("a departure outside the power balance's horizon");
  MicroJoules used = used_;
  MicroJoules* tb = traction_bins_.data();
  MicroJoules* rb = regen_bins_.data();
  for (const PowerBin& b : p.bins()) {
    const std::size_t i = index(b.section, base + b.offset);
    used -= std::min(tb[i], rb[i]);
    tb[i] += sign * b.traction;
    rb[i] += sign * b.regen;
    used += std::min(tb[i], rb[i]);
  }
  used_ = used;
  traction_ += sign * p.traction_total();
  regen_ += sign * p.regen_total();
}

void PowerBalance::place_all(const std::vector<int>& departures_s) {
  if (departures_s.size() != profiles_.size())
    throw std::invalid_argument("one departure per train expected");
  for (int k = 0; k < trains(); ++k) {
    if (placed(k)) add(k, departure_s_[k], -1);
  }
  for (int k = 0; k < trains(); ++k) {
    add(k, departures_s[k], +1);
    departure_s_[k] = departures_s[k];
  }
}

MicroJoules PowerBalance::move(int train, int departure_s) {
  const MicroJoules before = used_;
  add(train, departure_s_[train], -1);
  add(train, departure_s, +1);
  departure_s_[train] = departure_s;
  return used_ - before;
}

MicroJoules PowerBalance::gain_if_added(const PowerProfile& p, int departure_s) const {
  const long base = static_cast<long>(departure_s) * ticks_per_second_;
  if (departure_s < 0 || base + p.span_bins() > bins_)
    throw std::out_of_range("a departure outside the power balance's horizon");
  const MicroJoules* tb = traction_bins_.data();
  const MicroJoules* rb = regen_bins_.data();
  MicroJoules gain = 0;
  for (const PowerBin& b : p.bins()) {
    const std::size_t i = index(b.section, base + b.offset);
    gain += std::min(tb[i] + b.traction, rb[i] + b.regen) - std::min(tb[i], rb[i]);
  }
  return gain;
}

void PowerBalance::used_at(int train, const std::vector<int>& departures_s,
                           std::vector<MicroJoules>& used_J) {
  if (!placed(train)) throw std::logic_error("used_at: the train is not placed");
  // Every departure checked before the train is lifted: a throw leaves the balance as it was.
  const long span = profiles_[train]->span_bins();
  for (const int d : departures_s) {
    if (d < 0 || static_cast<long>(d) * ticks_per_second_ + span > bins_)
      throw std::out_of_range("a departure outside the power balance's horizon");
  }
  used_J.resize(departures_s.size());
  const int kept = departure_s_[train];
  add(train, kept, -1);
  const MicroJoules without = used_;
  for (std::size_t i = 0; i < departures_s.size(); ++i)
    used_J[i] = without + gain_if_added(*profiles_[train], departures_s[i]);
  add(train, kept, +1);
}

void PowerBalance::set_profile_all(const PowerProfile* profile) {
  check_grid(*profile);
  std::fill(traction_bins_.begin(), traction_bins_.end(), 0);
  std::fill(regen_bins_.begin(), regen_bins_.end(), 0);
  traction_ = regen_ = used_ = 0;
  MicroJoules* tb = traction_bins_.data();
  MicroJoules* rb = regen_bins_.data();
  for (int k = 0; k < trains(); ++k) {
    profiles_[k] = profile;
    if (!placed(k)) continue;
    const long base = static_cast<long>(departure_s_[k]) * ticks_per_second_;
    if (base + profile->span_bins() > bins_)
      throw std::out_of_range("a departure outside the power balance's horizon");
    for (const PowerBin& b : profile->bins()) {
      const std::size_t i = index(b.section, base + b.offset);
      tb[i] += b.traction;
      rb[i] += b.regen;
    }
    traction_ += profile->traction_total();
    regen_ += profile->regen_total();
  }
  used_ = recount_used();
}

void PowerBalance::set_profile(int train, const PowerProfile* profile) {
  check_grid(*profile);
  if (!placed(train)) {
    profiles_[train] = profile;
    return;
  }
  const int departure = departure_s_[train];
  add(train, departure, -1);
  profiles_[train] = profile;
  add(train, departure, +1);
}

namespace {

// sum over bins x in [from, to) of min(t[x] + dt, r[x] + dr) - min(t[x], r[x]), where dt, dr are
// sign * the profile's dense bins at x - base.
MicroJoules shifted_change(const MicroJoules* t, const MicroJoules* r, const MicroJoules* pt,
                           const MicroJoules* pr, long from, long to, long base, int sign) {
  MicroJoules change = 0;
  for (long x = from; x < to; ++x) {
    const MicroJoules dt = sign * pt[x - base], dr = sign * pr[x - base];
    change += std::min(t[x] + dt, r[x] + dr) - std::min(t[x], r[x]);
  }
  return change;
}

}  // namespace

MicroJoules PowerBalance::used_change_if_swapped(const PowerProfile& now, long base_now,
                                                 const PowerProfile& next, long base_next) const {
  if (base_next + next.span_bins() > bins_ || base_next < 0)
    throw std::out_of_range("a departure outside the power balance's horizon");
  if (&now == &next && sections_ == 1 && !now.dense_traction().empty()) {
    // One profile shifted (the annealing's proposals): by regions of the day, no merge. Bins
    // only the earlier placement covers, only the later one, and both (where the change is the
    // difference of two bins of the profile).
    const MicroJoules* t = traction_bins_.data();
    const MicroJoules* r = regen_bins_.data();
    const MicroJoules* pt = now.dense_traction().data();
    const MicroJoules* pr = now.dense_regen().data();
    const long n = now.span_bins();
    if (base_now == base_next) return 0;
    const bool later = base_next > base_now;  // the new placement is the later one
    const long early = later ? base_now : base_next, late = later ? base_next : base_now;
    const int early_sign = later ? -1 : +1;  // the old placement leaves, the new one arrives
    if (late >= early + n)
      return shifted_change(t, r, pt, pr, early, early + n, early, early_sign) +
             shifted_change(t, r, pt, pr, late, late + n, late, -early_sign);
    MicroJoules change = shifted_change(t, r, pt, pr, early, late, early, early_sign);
    for (long x = late; x < early + n; ++x) {
      const MicroJoules dt = pt[x - base_next] - pt[x - base_now];
      const MicroJoules dr = pr[x - base_next] - pr[x - base_now];
      change += std::min(t[x] + dt, r[x] + dr) - std::min(t[x], r[x]);
    }
    return change + shifted_change(t, r, pt, pr, early + n, late + n, late, -early_sign);
  }
  // Both bin lists are sorted by offset and hold one bin per offset, so one merge walk by
  // absolute bin visits every affected bin once; a bin both placements touch in the same
  // section gets both changes.
  MicroJoules used_change = 0;
  const MicroJoules* tb = traction_bins_.data();
  const MicroJoules* rb = regen_bins_.data();
  const auto change_at = [&](std::size_t i, MicroJoules dt, MicroJoules dr) {
    used_change += std::min(tb[i] + dt, rb[i] + dr) - std::min(tb[i], rb[i]);
  };
  const std::vector<PowerBin>& a = now.bins();
  const std::vector<PowerBin>& b = next.bins();
  std::size_t ia = 0, ib = 0;
  while (ia < a.size() || ib < b.size()) {
    const long pa = ia < a.size() ? base_now + a[ia].offset : 0;
    const long pb = ib < b.size() ? base_next + b[ib].offset : 0;
    const bool take_a = ib == b.size() || (ia < a.size() && pa <= pb);
    const bool take_b = ia == a.size() || (ib < b.size() && pb <= pa);
    if (take_a && take_b && a[ia].section == b[ib].section) {
      change_at(index(a[ia].section, pa), b[ib].traction - a[ia].traction,
                b[ib].regen - a[ia].regen);
    } else {
      if (take_a) change_at(index(a[ia].section, pa), -a[ia].traction, -a[ia].regen);
      if (take_b) change_at(index(b[ib].section, pb), b[ib].traction, b[ib].regen);
    }
    if (take_a) ++ia;
    if (take_b) ++ib;
  }
  return used_change;
}

MicroJoules PowerBalance::substation_change_if(int train, const PowerProfile& candidate) const {
  check_grid(candidate);
  const PowerProfile& now = *profiles_[train];
  const MicroJoules traction_change = candidate.traction_total() - now.traction_total();
  if (!placed(train)) return traction_change;
  const long base = static_cast<long>(departure_s_[train]) * ticks_per_second_;
  return traction_change - used_change_if_swapped(now, base, candidate, base);
}

MicroJoules PowerBalance::used_change_if_moved(int train, int departure_s) const {
  if (!placed(train)) throw std::logic_error("used_change_if_moved: the train is not placed");
  if (departure_s < 0) throw std::out_of_range("a departure outside the power balance's horizon");
  const PowerProfile& p = *profiles_[train];
  return used_change_if_swapped(p, static_cast<long>(departure_s_[train]) * ticks_per_second_, p,
                                static_cast<long>(departure_s) * ticks_per_second_);
}

FleetEnergy PowerBalance::energy() const {
  return {to_joules(traction_), to_joules(regen_), to_joules(used_)};
}

MicroJoules PowerBalance::recount_used() const {
  MicroJoules used = 0;
  for (std::size_t i = 0; i < traction_bins_.size(); ++i)
    used += std::min(traction_bins_[i], regen_bins_[i]);
  return used;
}

void PowerBalance::accumulate(BinSum& sum, int section, long bin) const {
  const std::size_t i = index(section, bin);
  sum.traction += traction_bins_[i];
  sum.regen += regen_bins_[i];
  sum.used += std::min(traction_bins_[i], regen_bins_[i]);
}

std::vector<FleetEnergy> PowerBalance::section_energy() const {
  std::vector<FleetEnergy> out(sections_);
  for (int s = 0; s < sections_; ++s) {
    BinSum sum;
    for (long b = 0; b < bins_; ++b) accumulate(sum, s, b);
    out[s] = {to_joules(sum.traction), to_joules(sum.regen), to_joules(sum.used)};
  }
  return out;
}

std::vector<FleetEnergy> PowerBalance::train_energy() const {
  std::vector<FleetEnergy> out(profiles_.size());
  for (int k = 0; k < trains(); ++k) {
    const PowerProfile& p = *profiles_[k];
    out[k].traction_J = to_joules(p.traction_total());
    out[k].regen_J = to_joules(p.regen_total());
    if (!placed(k)) continue;
    const long base = static_cast<long>(departure_s_[k]) * ticks_per_second_;
    double used = 0.0;
    for (const PowerBin& b : p.bins()) {
      if (b.regen == 0) continue;
      const std::size_t i = index(b.section, base + b.offset);
      const MicroJoules u = std::min(traction_bins_[i], regen_bins_[i]);
      used += static_cast<double>(u) * static_cast<double>(b.regen) /
              static_cast<double>(regen_bins_[i]);
    }
    out[k].used_regen_J = used / kMicroJoulesPerJoule;
  }
  return out;
}

PowerBalance::Trace PowerBalance::trace(double from_s, double to_s) const {
  Trace out;
  const double step = 1.0 / ticks_per_second_;
  out.step_s = step;
  const long b0 = std::clamp(static_cast<long>(std::floor(from_s * ticks_per_second_)), 0L, bins_);
  const long b1 = std::clamp(static_cast<long>(std::ceil(to_s * ticks_per_second_)), b0, bins_);
  out.start_s = static_cast<double>(b0) * step;
  const double per_bin = kMicroJoulesPerJoule * step;  // uJ per bin -> W
  for (long b = b0; b < b1; ++b) {
    BinSum sum;
    for (int s = 0; s < sections_; ++s) accumulate(sum, s, b);
    out.traction_W.push_back(static_cast<double>(sum.traction) / per_bin);
    out.regen_W.push_back(static_cast<double>(sum.regen) / per_bin);
    out.used_W.push_back(static_cast<double>(sum.used) / per_bin);
  }
  return out;
}

}  // namespace ecorail::energy
