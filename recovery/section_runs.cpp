#include "recovery/section_runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <stdexcept>

#include "dp/time_target.hpp"
#include "physics/trip.hpp"

namespace ecorail::recovery {

namespace {

long long ms_key(double time_s) {
  return std::llround(time_s * 1000.0);
}

}  // namespace

void DayBins::reset(std::size_t bins) {
  traction.assign(bins, 0);
  regen.assign(bins, 0);
}

std::int64_t DayBins::used_uJ() const {
  std::int64_t used = 0;
  for (std::size_t i = 0; i < traction.size(); ++i) used += std::min(traction[i], regen[i]);
  return used;
}

std::int64_t DayBins::traction_uJ() const {
  std::int64_t s = 0;
  for (std::int64_t v : traction) s += v;
  return s;
}

std::int64_t DayBins::regen_uJ() const {
  std::int64_t s = 0;
  for (std::int64_t v : regen) s += v;
  return s;
}

SectionRuns::SectionRuns(const dp::SectionLibrary& library, dp::FrontierStore* store,
                         double knot_step_s, double bin_step_s, SectionRunStore* run_store)
    : library_(library), knot_step_s_(knot_step_s), bin_step_s_(bin_step_s), run_store_(run_store) {
  if (!(knot_step_s > 0.0 && knot_step_s <= 60.0))
    throw std::invalid_argument("SectionRuns: the knot step must lie in (0, 60] s");
  const double ticks = 1.0 / bin_step_s;
  if (!(bin_step_s > 0.0 && bin_step_s <= 1.0) || std::fabs(ticks - std::round(ticks)) > 1e-9)
    throw std::invalid_argument("SectionRuns: the bin step must divide one second");
  const std::size_t n = library.size();
  library.build_frontiers(0, n, store);
  min_time_s_.resize(n);
  max_time_s_.resize(n);
  prices_.resize(n);
  pieces_.resize(n);
  skipped_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    // The frontier as the cache stores it, to the millijoule: a frontier computed in this run
    // and the same frontier read back from the cache (kept in kJ) then give the same price
    // table to the last bit, so a run's statistics do not depend on whether the cache was warm.
    dp::Frontier canonical = library.frontier(k, store).frontier();
    for (dp::FrontierPoint& pt : canonical.points)
      for (double* e : {&pt.traction_work_J, &pt.regen_J, &pt.net_J, &pt.cost_J})
        *e = std::round(*e * 1e3) / 1e3;
    const dp::FrontierCurve c(canonical);
    min_time_s_[k] = std::max(library.min_time_s(k), c.t_min_s());
    max_time_s_[k] = c.t_max_s();
    // The price table, every kPriceStep_s: the marginal energy per second of the frontier's
    // lower convex hull (where grid wobble makes the curve locally non-convex, e.g. A3 -> A4
    // just above its flat-out time, the hull is what a time price can reach: the minimiser of
    // E(t) + lambda t lies on it), so the price falls as the time grows.
    const int count =
        static_cast<int>(std::floor((max_time_s_[k] - min_time_s_[k]) / kPriceStep_s)) + 1;
    std::vector<double> ts(static_cast<std::size_t>(count)), es(ts.size());
    for (int i = 0; i < count; ++i) {
      ts[i] = std::min(max_time_s_[k], min_time_s_[k] + i * kPriceStep_s);
      es[i] = c.energy_at(ts[i]);
    }
    std::vector<int> hull;  // indices of the lower hull's vertices (monotone chain)
    for (int i = 0; i < count; ++i) {
      while (hull.size() >= 2) {
        const int a0 = hull[hull.size() - 2], a1 = hull.back();
        const double cross =
            (ts[a1] - ts[a0]) * (es[i] - es[a0]) - (es[a1] - es[a0]) * (ts[i] - ts[a0]);
        if (cross <= 0.0)
          hull.pop_back();
        else
          break;
      }
      hull.push_back(i);
    }
    std::vector<double>& p = prices_[k];
    p.assign(static_cast<std::size_t>(count), 0.0);
    for (std::size_t h = 0; h + 1 < hull.size(); ++h) {
      const int i0 = hull[h], i1 = hull[h + 1];
      const double price = std::max(0.0, -(es[i1] - es[i0]) / (ts[i1] - ts[i0]));
      for (int i = i0 + 1; i <= i1; ++i) p[i] = price;
    }
    p[0] = std::numeric_limits<double>::infinity();  // the flat-out end: every price
  }
  ensure_all(std::vector<double>(n, 0.0), std::vector<std::vector<double>>(n));
}

std::string SectionRuns::piece_key(std::size_t k, long long time_ms) const {
  char buf[120];
  std::snprintf(buf, sizeof buf, "|piece|%lld|bin|%.6f", time_ms, bin_step_s_);
  return library_.frontier_key(k) + buf;
}

double SectionRuns::time_for_price(std::size_t k, double price) const {
  const std::vector<double>& p = prices_[k];
  if (p.size() < 2 || p.back() > price) return max_time_s_[k];
  // First index whose marginal is <= price (p non-increasing, p[0] infinite).
  const auto it = std::lower_bound(p.begin(), p.end(), price, std::greater<double>());
  // lower_bound with greater: first element with !(element > price), i.e. element <= price.
  const std::size_t i = static_cast<std::size_t>(it - p.begin());
  if (i == 0) return min_time_s_[k];
  const double t_hi = min_time_s_[k] + static_cast<double>(i) * kPriceStep_s;
  const double m_lo = p[i - 1], m_hi = p[i];
  if (!std::isfinite(m_lo)) {
    // Next to the flat-out time the frontier falls like -sqrt(T - T_min): its marginal like
    // 1 / sqrt(T - T_min), so T - T_min = step (m(step) / price)^2 there.
    const double r = m_hi / price;
    return std::min(max_time_s_[k], min_time_s_[k] + kPriceStep_s * r * r);
  }
  double f = 1.0;
  if (m_lo > m_hi) f = (m_lo - price) / (m_lo - m_hi);
  return std::min(max_time_s_[k], t_hi - kPriceStep_s * (1.0 - f));
}

bool SectionRuns::make_piece(std::size_t k, double time_s, bool required, SectionPiece* out) const {
  SectionPiece& piece = *out;
  const long long key = ms_key(time_s);
  const bool flat_out = time_s <= library_.min_time_s(k) + 1e-9;
  piece.time_s = flat_out ? time_s : static_cast<double>(key) / 1000.0;
  const std::string store_key = piece_key(k, ms_key(piece.time_s));
  if (run_store_ != nullptr && run_store_->load(store_key, &piece)) return true;
  if (flat_out) {
    piece.sim = library_.min_time_run(k);
  } else {
    const dp::SectionTimeSolve sol = library_.solve(k, piece.time_s);
    piece.sim = sol.search.run.sim;
    if (!sol.search.converged || !dp::run_arrives(piece.sim) ||
        std::fabs(piece.sim.running_time_s - piece.time_s) > dp::kTimeTolerance_s) {
      if (!required) return false;
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "section %zu (%s -> %s): no run meets the running time %.3f s (got %.3f s)",
                    k + 1, library_.route(k).from_name().c_str(),
                    library_.route(k).to_name().c_str(), piece.time_s, piece.sim.running_time_s);
      throw std::runtime_error(buf);
    }
  }
  piece.has_sim = true;
  piece.resimulated_time_s = piece.sim.running_time_s;
  const physics::Trip trip({{&library_.route(k), &piece.sim, 0.0}}, 0.0,
                           library_.train().regen_efficiency);
  const physics::PowerBins bins = trip.power_bins(
      0.0, bin_step_s_,
      static_cast<std::size_t>(std::ceil((piece.sim.running_time_s + 1.0) / bin_step_s_)));
  for (std::size_t i = 0; i < bins.traction_W.size(); ++i) {
    const std::int64_t tr = std::llround(bins.traction_W[i] * bin_step_s_ * 1e6);
    const std::int64_t rg = std::llround(bins.regen_W[i] * bin_step_s_ * 1e6);
    if (tr == 0 && rg == 0) continue;
    piece.offsets.push_back(static_cast<std::int32_t>(i));
    piece.traction.push_back(tr);
    piece.regen.push_back(rg);
    piece.traction_uJ += tr;
    piece.regen_uJ += rg;
  }
  if (run_store_ != nullptr) run_store_->save(store_key, piece);
  if (!required) {  // the trajectory is only wanted of a plan's own runs (separation scan)
    piece.sim = physics::SimulationResult();
    piece.has_sim = false;
  }
  return true;
}

void SectionRuns::ensure_all(const std::vector<double>& upper_s,
                             const std::vector<std::vector<double>>& exact_times_s) {
  const std::size_t n = sections();
  // What is missing, per section: (time, required).
  std::vector<std::vector<std::pair<double, bool>>> todo(n);
  for (std::size_t k = 0; k < n; ++k) {
    auto want = [&](double t, bool required) {
      const long long key = ms_key(t);
      if (pieces_[k].count(key) != 0 || (!required && skipped_[k].count(key) != 0)) return;
      for (const auto& w : todo[k])
        if (ms_key(w.first) == key) return;
      todo[k].push_back({t, required});
    };
    want(min_time_s_[k], true);
    for (double t : exact_times_s[k]) {
      if (t < min_time_s_[k] - dp::kTimeTolerance_s || t > max_time_s_[k] + 1e-9) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "section %zu (%s -> %s): a planned running time of %.3f s lies outside the "
                      "frontier [%.3f, %.3f] s",
                      k + 1, library_.route(k).from_name().c_str(),
                      library_.route(k).to_name().c_str(), t, min_time_s_[k], max_time_s_[k]);
        throw std::invalid_argument(buf);
      }
      want(std::max(t, min_time_s_[k]), true);
    }
    const double upper = std::min(upper_s[k], max_time_s_[k]);
    for (int i = 1;; ++i) {
      const double t = min_time_s_[k] + i * knot_step_s_;
      if (t > upper + knot_step_s_ - 1e-9 || t > max_time_s_[k] + 1e-9) break;
      want(std::min(t, max_time_s_[k]), false);
    }
  }
  // Sections side by side (a section's engine is used by one thread at a time).
  std::vector<std::vector<std::pair<SectionPiece, bool>>> made(n);
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 1)
  for (long kk = 0; kk < static_cast<long>(n); ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    try {
      for (const auto& [t, required] : todo[k]) {
        SectionPiece piece;
        const bool ok = make_piece(k, t, required, &piece);
        made[k].push_back({std::move(piece), ok});
      }
    } catch (...) {
#pragma omp critical(section_runs_failure)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < made[k].size(); ++i) {
      const long long key = ms_key(todo[k][i].first);
      if (made[k][i].second) {
        pieces_[k].emplace(ms_key(made[k][i].first.time_s), std::move(made[k][i].first));
      } else if (skipped_[k].emplace(key, true).second) {
        ++skipped_knots_;
      }
    }
}

const SectionPiece& SectionRuns::piece_with_sim(std::size_t k, double time_s) {
  auto it = pieces_[k].find(ms_key(time_s));
  if (it == pieces_[k].end()) throw std::logic_error("SectionRuns: no piece at that time");
  if (!it->second.has_sim) {
    SectionRunStore* keep = run_store_;
    run_store_ = nullptr;  // solve it afresh
    SectionPiece fresh;
    make_piece(k, time_s, true, &fresh);
    run_store_ = keep;
    it->second.sim = std::move(fresh.sim);
    it->second.has_sim = true;
  }
  return it->second;
}

void SectionRuns::ensure(std::size_t k, double upper_s, const std::vector<double>& exact_times_s) {
  std::vector<double> upper(sections(), 0.0);
  std::vector<std::vector<double>> exact(sections());
  upper[k] = upper_s;
  exact[k] = exact_times_s;
  ensure_all(upper, exact);
}

const SectionPiece* SectionRuns::piece_at(std::size_t k, double time_s) const {
  const auto it = pieces_[k].find(ms_key(time_s));
  return it == pieces_[k].end() ? nullptr : &it->second;
}

double SectionRuns::last_knot_s(std::size_t k) const {
  return pieces_[k].rbegin()->second.time_s;
}

std::size_t SectionRuns::piece_count() const {
  std::size_t c = 0;
  for (const auto& m : pieces_) c += m.size();
  return c;
}

double SectionRuns::lay(std::size_t k, double time_s, double departure_s, DayBins& day) const {
  const auto& m = pieces_[k];
  // The knots around time_s: b the first at or after it, a the one before.
  long long key = std::llround(time_s * 1000.0);
  if (std::fabs(time_s * 1000.0 - static_cast<double>(key)) > 1e-3)
    key = static_cast<long long>(std::ceil(time_s * 1000.0));
  auto b = m.lower_bound(key);
  if (b == m.end()) b = std::prev(m.end());
  const SectionPiece* pb = &b->second;
  const SectionPiece* pa = pb;
  double w = 0.0;  // the weight of pa
  if (std::fabs(pb->time_s - time_s) > 1e-6 && b != m.begin()) {
    pa = &std::prev(b)->second;
    w = std::clamp((pb->time_s - time_s) / (pb->time_s - pa->time_s), 0.0, 1.0);  // weight of pa
  }
  const long shift = std::lround(departure_s / day.step_s);
  auto add = [&](const SectionPiece& p, double weight) {
    const long need = shift + (p.offsets.empty() ? 0 : p.offsets.back()) + 1;
    if (need > static_cast<long>(day.traction.size())) {
      day.traction.resize(static_cast<std::size_t>(need) + 36000, 0);
      day.regen.resize(static_cast<std::size_t>(need) + 36000, 0);
    }
    for (std::size_t i = 0; i < p.offsets.size(); ++i) {
      const long at = shift + p.offsets[i];
      if (at < 0) continue;  // before the day's clock starts: not on the grid
      if (weight == 1.0) {
        day.traction[static_cast<std::size_t>(at)] += p.traction[i];
        day.regen[static_cast<std::size_t>(at)] += p.regen[i];
      } else {
        day.traction[static_cast<std::size_t>(at)] +=
            std::llround(weight * static_cast<double>(p.traction[i]));
        day.regen[static_cast<std::size_t>(at)] +=
            std::llround(weight * static_cast<double>(p.regen[i]));
      }
    }
  };
  if (pa == pb || w == 0.0) {
    add(*pb, 1.0);
    return static_cast<double>(pb->traction_uJ) / 1e6;
  }
  if (w == 1.0) {
    add(*pa, 1.0);
    return static_cast<double>(pa->traction_uJ) / 1e6;
  }
  add(*pa, w);
  add(*pb, 1.0 - w);
  return (w * static_cast<double>(pa->traction_uJ) +
          (1.0 - w) * static_cast<double>(pb->traction_uJ)) /
         1e6;
}

void split_by_price(const SectionRuns& runs, const std::vector<std::size_t>& sections,
                    const std::vector<double>& lo, const std::vector<double>& hi, double total_s,
                    std::vector<double>& out) {
  const std::size_t m = sections.size();
  out.assign(m, 0.0);
  double sum_lo = 0.0, sum_hi = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    sum_lo += lo[i];
    sum_hi += hi[i];
  }
  if (total_s <= sum_lo) {
    out = lo;
    return;
  }
  if (total_s >= sum_hi) {
    out = hi;
    return;
  }
  std::vector<double> t_lo(m), t_hi(m);  // times at the low and the high price
  auto times = [&](double price, std::vector<double>& t) {
    double s = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      t[i] = std::clamp(runs.time_for_price(sections[i], price), lo[i], hi[i]);
      s += t[i];
    }
    return s;
  };
  // The low price gives the most time (at least the total), the high price the least.
  double p_lo = 1e-6, p_hi = 1.0;
  for (std::size_t i = 0; i < m; ++i) p_hi = std::max(p_hi, runs.top_price(sections[i]));
  double s_lo = times(p_lo, t_lo), s_hi = times(p_hi, t_hi);
  for (int guard = 0; s_hi > total_s && guard < 80; ++guard) s_hi = times(p_hi *= 4.0, t_hi);
  if (s_lo < total_s) {
    // The frontiers are flat (no price) above the low price's times: the time left is free;
    // share it in proportion to the room below each upper bound.
    const double room = sum_hi - s_lo, f = (total_s - s_lo) / room;
    for (std::size_t i = 0; i < m; ++i) out[i] = t_lo[i] + f * (hi[i] - t_lo[i]);
    return;
  }
  std::vector<double> t_mid(m);
  for (int it = 0; it < 64 && p_hi / p_lo > 1.0 + 1e-12; ++it) {
    const double p_mid = std::sqrt(p_lo * p_hi);
    const double s = times(p_mid, t_mid);
    if (s >= total_s) {
      p_lo = p_mid;
      s_lo = s;
      t_lo.swap(t_mid);
    } else {
      p_hi = p_mid;
      s_hi = s;
      t_hi.swap(t_mid);
    }
  }
  // Close the sum exactly between the two ends of the bracket (a linear stretch of a frontier
  // makes the sum jump; any split of the jump is optimal).
  const double f = s_lo > s_hi ? (total_s - s_hi) / (s_lo - s_hi) : 0.0;
  for (std::size_t i = 0; i < m; ++i) out[i] = t_hi[i] + f * (t_lo[i] - t_hi[i]);
}

}  // namespace ecorail::recovery
