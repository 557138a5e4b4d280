#include "fleet/regime_start.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

#include "fleet/regime_arrangement.hpp"
#include "fleet/windowed_classes.hpp"

namespace ecorail::fleet {

namespace {

constexpr int kRefinedRegimes = 8;  // best regimes of each class refined to whole seconds

// Blocks of one class: single headways (one entry per grid value) and alternating pairs.
struct ClassBlocks {
  std::map<int, double> single_J;  // headway -> used energy of one headway (constant regime)
  std::vector<PeriodicRegime> pairs;
};

ClassBlocks blocks_of(const std::vector<PeriodicRegime>& regimes, int pairs_per_class) {
  ClassBlocks out;
  for (const PeriodicRegime& r : regimes)
    if (r.a_s == r.b_s) out.single_J[r.a_s] = r.used_per_headway_J();
  // A pair is a block of its own only when alternating beats its two constants side by side.
  std::vector<std::pair<double, PeriodicRegime>> gain;
  for (const PeriodicRegime& r : regimes) {
    if (r.a_s == r.b_s) continue;
    const double g = r.used_per_period_J - out.single_J[r.a_s] - out.single_J[r.b_s];
    if (g > 0.0) gain.push_back({g, r});
  }
  std::stable_sort(gain.begin(), gain.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  for (std::size_t i = 0; i < gain.size() && static_cast<int>(i) < pairs_per_class; ++i)
    out.pairs.push_back(gain[i].second);
  return out;
}

}  // namespace

int regime_grid_s(int lo_s, int hi_s) {
  // The analysis only samples the class's range: the DP that follows steps by whole seconds,
  // so neither the span nor the windows' edges need to fall on this grid (they once had to,
  // and a peak window moved by 3 s then lost the regime start).
  const int range = hi_s - lo_s;
  return range >= 10 ? 10 : std::max(1, range / 2);
}

RegimeStart regime_start_from(const FleetProblem& p, int g, std::vector<PeriodicRegime> offpeak,
                              std::vector<PeriodicRegime> peak, int pairs_per_class,
                              const std::function<bool()>& stop) {
  RegimeStart out;
  out.grid_s = g;
  out.offpeak = std::move(offpeak);
  out.peak = std::move(peak);
  if (g <= 0 || p.span_s % g != 0) return out;
  const ClassBlocks off = blocks_of(out.offpeak, pairs_per_class);
  const ClassBlocks pk = blocks_of(out.peak, pairs_per_class);
  // Block list: singles of either class (the class is checked where the block lands), then
  // pairs; a block is (first headway, second headway or 0, value, class is peak).
  struct Block {
    int h1, h2;
    double value_J;
    bool peak;
  };
  std::vector<Block> blocks;
  for (const auto& [h, v] : off.single_J) blocks.push_back({h, 0, v, false});
  if (p.windowed())
    for (const auto& [h, v] : pk.single_J) blocks.push_back({h, 0, v, true});
  const auto add_pairs = [&](const ClassBlocks& c, bool is_peak) {
    for (const PeriodicRegime& r : c.pairs) {
      blocks.push_back({r.a_s, r.b_s, r.used_per_period_J, is_peak});
      blocks.push_back({r.b_s, r.a_s, r.used_per_period_J, is_peak});
    }
  };
  add_pairs(off, false);
  if (p.windowed()) add_pairs(pk, true);
  const auto fits = [&](int from_s, int h, bool is_peak) {
    const int to_s = from_s + h;
    if (to_s > p.span_s) return false;
    if (!p.windowed()) return h >= p.headway_min_s && h <= p.headway_max_s;
    const bool peak_here = is_peak_headway(p.peak_windows, from_s, to_s);
    return peak_here == is_peak && p.headway_allowed(from_s, to_s);
  };

  const int headways = p.trains - 1, ticks = p.span_s / g;
  const double none = -std::numeric_limits<double>::infinity();
  // value[k % 3][tick]: the best value with k headways, the last departure at tick * g.
  std::vector<std::vector<double>> value(3, std::vector<double>(ticks + 1, none));
  std::vector<std::uint16_t> back(static_cast<std::size_t>(headways + 1) * (ticks + 1), 0);
  const auto at = [&](int k, int t) { return static_cast<std::size_t>(k) * (ticks + 1) + t; };
  value[0][0] = 0.0;
  for (int k = 1; k <= headways; ++k) {
    if (stop && stop()) return out;
    std::vector<double>& cur = value[k % 3];
    std::fill(cur.begin(), cur.end(), none);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const Block& bl = blocks[b];
      const int n = bl.h2 == 0 ? 1 : 2;
      if (k < n || (bl.h1 + bl.h2) % g != 0) continue;
      const std::vector<double>& prev = value[(k - n) % 3];
      const int step = (bl.h1 + bl.h2) / g;
      for (int t = 0; t + step <= ticks; ++t) {
        if (prev[t] == none) continue;
        const int from = t * g;
        if (!fits(from, bl.h1, bl.peak)) continue;
        if (n == 2 && !fits(from + bl.h1, bl.h2, bl.peak)) continue;
        const double v = prev[t] + bl.value_J;
        if (v > cur[t + step]) cur[t + step] = v, back[at(k, t + step)] = b + 1;
      }
    }
  }
  if (value[headways % 3][ticks] == none) return out;
  out.predicted_used_J = value[headways % 3][ticks];
  std::vector<int> h;
  // A regime's label: one per (its two headways in order, a constant's twice; its class).
  std::map<std::tuple<int, int, bool>, int> label_of;
  for (int k = headways, t = ticks; k > 0;) {
    const Block& bl = blocks[back[at(k, t)] - 1];
    const int lo = bl.h2 == 0 ? bl.h1 : std::min(bl.h1, bl.h2);
    const int hi = bl.h2 == 0 ? bl.h1 : std::max(bl.h1, bl.h2);
    const int label =
        label_of.emplace(std::tuple{lo, hi, bl.peak}, static_cast<int>(label_of.size()))
            .first->second;
    if (bl.h2 != 0)
      h.push_back(bl.h2), h.push_back(bl.h1), k -= 2;
    else
      h.push_back(bl.h1), k -= 1;
    out.regime_of_headway.resize(h.size(), label);
    t -= (bl.h1 + bl.h2) / g;
  }
  std::reverse(h.begin(), h.end());
  std::reverse(out.regime_of_headway.begin(), out.regime_of_headway.end());
  out.departures_s = departures_from_headways(h);
  return out;
}

std::vector<PeriodicRegime> refine_regimes(const energy::FleetEnergyModel& model,
                                           std::vector<PeriodicRegime> regimes, int lo_s, int hi_s,
                                           int top, int threads,
                                           const std::function<bool()>& stop) {
  std::vector<PeriodicRegime> best = regimes;
  std::stable_sort(best.begin(), best.end(), [](const auto& x, const auto& y) {
    return x.used_per_headway_J() > y.used_per_headway_J();
  });
  best.resize(std::min<std::size_t>(best.size(), top));
  const int n = static_cast<int>(best.size());
  std::vector<std::vector<PeriodicRegime>> found(n);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int i = 0; i < n; ++i) {
    // Hill climbing by whole seconds (a constant stays a constant).
    PeriodicRegime r = best[i];
    for (bool moved = true; moved && !(stop && stop());) {
      moved = false;
      for (auto [da, db] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, 1}}) {
        if (r.a_s == r.b_s && da != db) continue;
        const int a = r.a_s + da, b = r.b_s + db;
        if (a < lo_s || b > hi_s || a > b) continue;
        const double v = steady_used_per_period_J(model, a, b);
        if (v > r.used_per_period_J) r = {a, b, v}, moved = true;
      }
    }
    found[i].push_back(r);
    // A pair's own constants, so that its gain over them is known.
    if (r.a_s != r.b_s)
      for (int h : {r.a_s, r.b_s})
        found[i].push_back({h, h, steady_used_per_period_J(model, h, h)});
  }
  for (const auto& f : found)
    for (const PeriodicRegime& r : f) {
      bool known = false;
      for (const PeriodicRegime& q : regimes) known |= q.a_s == r.a_s && q.b_s == r.b_s;
      if (!known) regimes.push_back(r);
    }
  return regimes;
}

RegimeStart build_regime_start(const energy::FleetEnergyModel& model, const FleetProblem& p,
                               int threads, const energy::FleetEnergyModel* arrange_on,
                               const std::function<bool()>& stop) {
  const auto stopped = [&] { return stop && stop(); };
  PeriodicRegimeOptions o;
  o.threads = threads;
  o.stop = stop;
  o.lo_s = p.headway_min_s;
  o.hi_s = p.headway_max_s;
  const int g = o.grid_s = regime_grid_s(o.lo_s, o.hi_s);
  std::vector<PeriodicRegime> offpeak = refine_regimes(
      model, analyse_periodic_regimes(model, o), o.lo_s, o.hi_s, kRefinedRegimes, threads, stop);
  std::vector<PeriodicRegime> peak;
  if (p.windowed()) {
    o.lo_s = p.peak_headway_min_s;
    o.hi_s = p.peak_headway_max_s;
    o.grid_s = regime_grid_s(o.lo_s, o.hi_s);
    peak = refine_regimes(model, analyse_periodic_regimes(model, o), o.lo_s, o.hi_s,
                          kRefinedRegimes, threads, stop);
  }
  // An analysis cut short would mislead the DP: no start then.
  if (stopped()) return {};
  // The refined regimes lie off the analysis grid: the DP then steps by whole seconds.
  RegimeStart out = regime_start_from(p, 1, std::move(offpeak), std::move(peak), 16, stop);
  out.grid_s = g;
  if (out.departures_s.empty()) return out;
  RegimeArrangementOptions ao;
  ao.threads = threads;
  ao.stop = stop;
  const RegimeArrangement a =
      arrange_regime_runs(arrange_on ? *arrange_on : model, p,
                          headways_from_departures(out.departures_s), out.regime_of_headway, ao);
  out.dp_used_J = a.start_used_J;
  out.arranged_used_J = a.used_J;
  out.arrangement_evaluations = a.evaluations;
  out.departures_s = departures_from_headways(a.headways_s);
  out.regime_of_headway = a.run_of_headway;
  return out;
}

}  // namespace ecorail::fleet
