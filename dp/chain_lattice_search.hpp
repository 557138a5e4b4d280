// The minimum of a sum of costs along a chain, f(x) = c_0(x_0) + c_1(x_0, x_1) + ... +
// c_{n-1}(x_{n-2}, x_{n-1}) + c_n(x_{n-1}), each cost one expensive evaluation (a solve of a
// DP between two pinned states), searched on a lattice that is moved and refined: around the
// centre, each variable takes three values (centre and one step either side), and the best of
// all 3^n combinations is found exactly by a DP along the chain, 3 + 9 (n - 1) + 3 costs, not
// 3^n evaluations of f. The centre moves to that best; when the centre itself is best, the step
// halves. Every variable moves at once, so a valley along a diagonal (two points 100 m apart
// that must be passed 9 s apart want the same speed) is followed as fast as an axis. Costs are
// kept by their lattice indices, so a moved or refined lattice evaluates only its new pairs.
// The costs a DP stage needs are solved side by side on `threads` OpenMP threads (each call of
// the cost then runs alone on its thread: nested regions are serial), and the search takes the
// same path for any thread count: costs are keyed, not ordered by who finished first.
// Used for the speeds of the points pinned in a part the label search ran
// (dp/timing_binding_pins.hpp). A local search: the best of each lattice, not a global minimum.
#pragma once

#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include <omp.h>

namespace ecorail::dp {

struct ChainLatticeResult {
  std::vector<double> x;  // the best point found
  double f = std::numeric_limits<double>::infinity();
  // The best point of each lattice searched, with its f, in the order found (for callers that
  // re-check the cheapest few another way).
  std::vector<std::pair<double, std::vector<double>>> lattice_bests;
  int cost_evaluations = 0;  // distinct calls of the cost
  bool converged = false;    // the centre was best at the finest step (else the budget ran out)
};

// cost(k, a, b) is c_k: k = 0 has no a (NaN is passed), k = n no b. Variable i lies in
// [lo[i], hi[i]]; values outside are not evaluated. The lattice starts around x0 with steps of
// first_step, halved (levels - 1) times at most; the search stops when the centre is best at
// the finest step, or before a lattice whose new costs would exceed max_cost_evaluations.
// +inf costs are allowed (an infeasible pair). cost must be safe to call from several threads
// at once when threads is not 1 (threads <= 0: OpenMP's default); an exception it throws ends
// the search (the one of the first cost in the stage's order, whichever thread threw it).
template <class Cost>
ChainLatticeResult chain_lattice_minimum(const Cost& cost, const std::vector<double>& x0,
                                         const std::vector<double>& lo,
                                         const std::vector<double>& hi, double first_step,
                                         int levels, int max_cost_evaluations, int threads = 1) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::size_t n = x0.size();
  ChainLatticeResult out;
  if (n == 0 || levels < 1) return out;
  // Values are x0 + j unit, j an integer, so a moved lattice meets the same values exactly.
  const long finest = 1;
  long step = finest << (levels - 1);
  const double unit = first_step / static_cast<double>(step);
  auto value = [&](std::size_t i, long j) { return x0[i] + unit * static_cast<double>(j); };
  using Key = std::tuple<std::size_t, long, long>;
  std::map<Key, double> known;
  // Solves the costs of keys not known yet, side by side (a stage's keys are distinct: each
  // variable's values are).
  const int team = threads > 0 ? threads : omp_get_max_threads();
  auto solve_costs = [&](const std::vector<Key>& keys) {
    std::vector<Key> fresh;
    for (const Key& key : keys) {
      if (known.count(key) == 0) fresh.push_back(key);
    }
    const long count = static_cast<long>(fresh.size());
    std::vector<double> costs(fresh.size(), kInf);
    std::vector<std::exception_ptr> errors(fresh.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(team) if (team > 1 && count > 1)
    for (long q = 0; q < count; ++q) {
      const auto [k, a, b] = fresh[static_cast<std::size_t>(q)];
      try {
        costs[static_cast<std::size_t>(q)] =
            cost(k, k == 0 ? std::nan("") : value(k - 1, a), k == n ? std::nan("") : value(k, b));
      } catch (...) {
        errors[static_cast<std::size_t>(q)] = std::current_exception();
      }
    }
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    for (std::size_t q = 0; q < fresh.size(); ++q) known.emplace(fresh[q], costs[q]);
    out.cost_evaluations += static_cast<int>(fresh.size());
  };
  auto pair_cost = [&](std::size_t k, long a, long b) { return known.at(Key{k, a, b}); };
  std::vector<long> centre(n, 0);
  while (true) {
    // The values of each variable: the centre first, so that a tie keeps it.
    std::vector<std::vector<long>> values(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (const long d : {0L, -step, step}) {
        const double x = value(i, centre[i] + d);
        if (d == 0 || (x >= lo[i] && x <= hi[i])) values[i].push_back(centre[i] + d);
      }
    }
    // The new costs this lattice needs; stop before it if they exceed the budget.
    int fresh = 0;
    auto count = [&](std::size_t k, long a, long b) {
      fresh += known.count(std::make_tuple(k, a, b)) == 0 ? 1 : 0;
    };
    for (const long b : values[0]) count(0, 0, b);
    for (std::size_t k = 1; k < n; ++k) {
      for (const long a : values[k - 1]) {
        for (const long b : values[k]) count(k, a, b);
      }
    }
    for (const long a : values[n - 1]) count(n, a, 0);
    if (out.cost_evaluations + fresh > max_cost_evaluations) break;
    // The DP along the chain: best[i][v] is the least cost of c_0..c_i with x_i = values[i][v].
    std::vector<std::vector<double>> best(n);
    std::vector<std::vector<std::size_t>> from(n);
    std::vector<Key> needed;
    for (const long b : values[0]) needed.emplace_back(0, 0, b);
    solve_costs(needed);
    for (std::size_t v = 0; v < values[0].size(); ++v)
      best[0].push_back(pair_cost(0, 0, values[0][v]));
    from[0].assign(values[0].size(), 0);
    for (std::size_t i = 1; i < n; ++i) {
      // The stage's costs: none after a value no run reaches.
      needed.clear();
      for (std::size_t u = 0; u < values[i - 1].size(); ++u) {
        if (!(best[i - 1][u] < kInf)) continue;
        for (const long b : values[i]) needed.emplace_back(i, values[i - 1][u], b);
      }
      solve_costs(needed);
      for (const long b : values[i]) {
        double least = kInf;
        std::size_t arg = 0;
        for (std::size_t u = 0; u < values[i - 1].size(); ++u) {
          if (!(best[i - 1][u] < kInf)) continue;
          const double c = best[i - 1][u] + pair_cost(i, values[i - 1][u], b);
          if (c < least) least = c, arg = u;
        }
        best[i].push_back(least);
        from[i].push_back(arg);
      }
    }
    needed.clear();
    for (std::size_t u = 0; u < values[n - 1].size(); ++u) {
      if (best[n - 1][u] < kInf) needed.emplace_back(n, values[n - 1][u], 0);
    }
    solve_costs(needed);
    double least = kInf;
    std::size_t arg = 0;
    for (std::size_t u = 0; u < values[n - 1].size(); ++u) {
      if (!(best[n - 1][u] < kInf)) continue;
      const double c = best[n - 1][u] + pair_cost(n, values[n - 1][u], 0);
      if (c < least) least = c, arg = u;
    }
    std::vector<long> chosen(n, 0);
    bool moved = false;
    if (least < kInf) {
      for (std::size_t i = n; i-- > 0;) {
        chosen[i] = values[i][arg];
        moved = moved || arg != 0;
        arg = from[i][arg];
      }
      std::vector<double> x(n);
      for (std::size_t i = 0; i < n; ++i) x[i] = value(i, chosen[i]);
      if (moved || out.lattice_bests.empty()) out.lattice_bests.push_back({least, x});
      if (least < out.f) out.f = least, out.x = x;
    }
    if (least < kInf && moved) {
      centre = chosen;
    } else if (step == finest) {
      out.converged = least < kInf;
      break;
    } else {
      step /= 2;
    }
  }
  return out;
}

}  // namespace ecorail::dp
