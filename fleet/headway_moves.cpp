#include "fleet/headway_moves.hpp"

#include <algorithm>
#include <cmath>

namespace ecorail::fleet {

using energy::FleetBalance;
using energy::MicroJoules;
using energy::SearchPlan;
using Clock = SearchClock;

std::pair<int, int> feasible_range(const FleetProblem& p, const std::vector<int>& t, int k) {
  const int lo = std::max(t[k - 1] + p.any_headway_min_s(), t[k + 1] - p.any_headway_max_s());
  const int hi = std::min(t[k - 1] + p.any_headway_max_s(), t[k + 1] - p.any_headway_min_s());
  return {lo, hi};
}

bool allowed(const FleetProblem& p, const std::vector<int>& t, int k, int d) {
  return !p.windowed() || (p.headway_allowed(t[k - 1], d) && p.headway_allowed(d, t[k + 1]));
}

bool past(Clock::time_point t0, double limit_s) {
  return limit_s > 0.0 && seconds_since(t0) > limit_s;
}

RunResult anneal(FleetBalance& balance, const FleetProblem& p, const SearchPlan& plan,
                 std::vector<int> t, std::uint64_t seed, std::uint64_t run, long moves,
                 Clock::time_point t0, double limit_s, bool block_moves, double temperature_scale) {
  const auto draw = [&](std::uint64_t move, std::uint64_t k) {
    return counter_draw(seed, run, move, k, plan.draw_salt);
  };
  RunResult out;
  balance.place_all(t);
  out.departures = t;
  out.substation = balance.substation();
  const int n = p.trains;
  if (n < 3 || moves == 0) return out;
  // Temperature: from the mean size of a few proposals' changes down by 1000x.
  double mean = 0.0;
  int samples = 0;
  for (int i = 0; i < plan.temperature_samples; ++i) {
    const int k = 1 + static_cast<int>(draw(i, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    if (plan.samples_within_move_window) lo = std::max(lo, t[k] - 30), hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    const int d = lo + static_cast<int>(draw(i, 1) % (hi - lo + 1));
    if (!allowed(p, t, k, d)) continue;
    mean += std::fabs(static_cast<double>(balance.change_if_moved(k, t[k], d)));
    ++samples;
  }
  const double t_start = temperature_scale * (samples > 0 ? std::max(1.0, mean / samples) : 1.0);
  const double cool = std::pow(1e-3, 1.0 / static_cast<double>(moves));
  double temperature = t_start;
  MicroJoules current = balance.substation();
  const long check_mask = plan.time_check_every - 1;
  for (long m = 0; m < moves; ++m, temperature *= cool) {
    if ((m & check_mask) == 0 && past(t0, limit_s)) {
      out.stopped = true;
      break;
    }
    const std::uint64_t counter = m + plan.draw_offset;
    const int k = 1 + static_cast<int>(draw(counter, 0) % (n - 2));
    if (block_moves && n > 4 && draw(counter, 3) % 8 == 0) {
      // A block of consecutive trains shifted together: the headways inside keep their lengths
      // (their clock classes are checked again), the two at its ends change.
      const int len = 2 + static_cast<int>((draw(counter, 3) >> 8) % 4);
      const int last = std::min(n - 2, k + len - 1);
      const int d = static_cast<int>(draw(counter, 1) % 61) - 30;
      if (d == 0) continue;
      bool ok = true;
      for (int j = k - 1; j <= last && ok; ++j) {
        const int from = t[j] + (j >= k ? d : 0), to = t[j + 1] + (j + 1 <= last ? d : 0);
        ok = p.headway_allowed(from, to);
      }
      if (!ok) continue;
      MicroJoules delta = 0;
      for (int j = k; j <= last; ++j) delta += balance.move(j, t[j] + d);
      ++out.moves;
      const bool accept = delta <= 0 || uniform01(draw(counter, 2)) <
                                            std::exp(-static_cast<double>(delta) / temperature);
      if (!accept) {
        for (int j = k; j <= last; ++j) balance.move(j, t[j]);
        continue;
      }
      for (int j = k; j <= last; ++j) t[j] += d;
      current += delta;
      if (current < out.substation) out.substation = current, out.departures = t;
      continue;
    }
    auto [lo, hi] = feasible_range(p, t, k);
    lo = std::max(lo, t[k] - 30);
    hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    int d = lo + static_cast<int>(draw(counter, 1) % (hi - lo));
    if (d >= t[k]) ++d;  // never the current departure
    if (d > hi || !allowed(p, t, k, d)) continue;
    // Priced without moving: most proposals are rejected.
    const MicroJoules delta = balance.change_if_moved(k, t[k], d);  // < 0: better
    ++out.moves;
    const bool accept = delta <= 0 || uniform01(draw(counter, 2)) <
                                          std::exp(-static_cast<double>(delta) / temperature);
    if (!accept) continue;
    balance.move(k, d);
    t[k] = d;
    current += delta;
    if (current < out.substation) out.substation = current, out.departures = t;
  }
  return out;
}

long polish(FleetBalance& balance, const FleetProblem& p, std::vector<int>& t, int window,
            int sweeps, Clock::time_point t0, double limit_s, bool* stopped) {
  long moves = 0;
  std::vector<int> candidates;  // departures tried for one train
  std::vector<MicroJoules> substation;
  balance.place_all(t);
  for (int sweep = 0; sweep < sweeps && !*stopped; ++sweep) {
    bool improved = false;
    for (int k = 1; k + 1 < p.trains; ++k) {
      if (past(t0, limit_s)) {
        *stopped = true;
        break;
      }
      auto [lo, hi] = feasible_range(p, t, k);
      lo = std::max(lo, t[k] - window);
      hi = std::min(hi, t[k] + window);
      const int start = t[k];
      candidates.clear();
      for (int d = lo; d <= hi; ++d) {
        if (d != start && allowed(p, t, k, d)) candidates.push_back(d);
      }
      balance.substation_at(k, start, candidates, substation);
      moves += static_cast<long>(candidates.size());
      MicroJoules best = balance.substation();
      int best_d = start;
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (substation[i] < best) best = substation[i], best_d = candidates[i];
      }
      if (best_d != start) balance.move(k, best_d);
      improved |= best_d != start;
      t[k] = best_d;
    }
    if (!improved) break;
  }
  return moves;
}

}  // namespace ecorail::fleet
