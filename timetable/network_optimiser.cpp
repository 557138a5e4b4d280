#include "timetable/network_optimiser.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "timetable/headway_dp.hpp"
#include "timetable/network_balance.hpp"
#include "timetable/network_bound.hpp"
#include "timetable/search_support.hpp"
#include "timetable/windowed_dp.hpp"

namespace ecorail::timetable {

namespace {

using Clock = SearchClock;

// The annealing stops at this share of --time-limit, leaving the rest to the polish (a sweep of
// a long day on the model's grid costs minutes).
constexpr double kAnnealShareOfTimeLimit = 0.6;

// The network search's draws (search_support.hpp), salted apart from the power-flow search's.
std::uint64_t draw(std::uint64_t seed, std::uint64_t run, std::uint64_t move, std::uint64_t k) {
  return counter_draw(seed, run, move, k, 0x6e6574776f726bULL);
}

// The departure range of train k (0 < k < N-1) given its neighbours (with peak windows: the
// range of any class; allowed() then checks the classes of both headways, as the power-flow
// search does).
std::pair<int, int> feasible_range(const FleetProblem& p, const std::vector<int>& t, int k) {
  return {std::max(t[k - 1] + p.any_headway_min_s(), t[k + 1] - p.any_headway_max_s()),
          std::min(t[k - 1] + p.any_headway_max_s(), t[k + 1] - p.any_headway_min_s())};
}

bool allowed(const FleetProblem& p, const std::vector<int>& t, int k, int d) {
  return !p.windowed() || (p.headway_allowed(t[k - 1], d) && p.headway_allowed(d, t[k + 1]));
}

struct RunResult {
  std::vector<int> departures;
  MicroJoules substation = 0;
  long moves = 0;
  bool stopped = false;
};

// Simulated annealing minimising the substation energy.
RunResult anneal(NetworkBalance& balance, const FleetProblem& p, std::vector<int> t,
                 std::uint64_t seed, std::uint64_t run, long moves, Clock::time_point t0,
                 double limit_s) {
  RunResult out;
  balance.place_all(t);
  out.departures = t;
  out.substation = balance.substation();
  const int n = p.trains;
  if (n < 3 || moves == 0) return out;
  double mean = 0.0;
  int samples = 0;
  for (int i = 0; i < 16; ++i) {
    const int k = 1 + static_cast<int>(draw(seed, run, i, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    lo = std::max(lo, t[k] - 30), hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    const int d = lo + static_cast<int>(draw(seed, run, i, 1) % (hi - lo + 1));
    if (!allowed(p, t, k, d)) continue;
    const int back = t[k];
    mean += std::fabs(static_cast<double>(balance.move(k, d)));
    balance.move(k, back);
    ++samples;
  }
  const double t_start = samples > 0 ? std::max(1.0, mean / samples) : 1.0;
  const double cool = std::pow(1e-3, 1.0 / static_cast<double>(moves));
  double temperature = t_start;
  MicroJoules current = balance.substation();
  for (long m = 0; m < moves; ++m, temperature *= cool) {
    if (limit_s > 0.0 && (m & 15) == 0 && seconds_since(t0) > limit_s) {
      out.stopped = true;
      break;
    }
    const int k = 1 + static_cast<int>(draw(seed, run, m + 64, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    lo = std::max(lo, t[k] - 30), hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    int d = lo + static_cast<int>(draw(seed, run, m + 64, 1) % (hi - lo));
    if (d >= t[k]) ++d;
    if (d > hi || !allowed(p, t, k, d)) continue;
    const MicroJoules delta = balance.move(k, d);  // < 0: better
    ++out.moves;
    const bool accept = delta <= 0 || uniform01(draw(seed, run, m + 64, 2)) <
                                          std::exp(-static_cast<double>(delta) / temperature);
    if (!accept) {
      balance.move(k, t[k]);
      continue;
    }
    t[k] = d;
    current += delta;
    if (current < out.substation) out.substation = current, out.departures = t;
  }
  return out;
}

// Every train tried at every departure within +-window, the best kept, until a sweep changes
// nothing (at most `sweeps`). A sweep of a long day costs minutes on the model's grid, so the
// time limit stops it between trains (*stopped set; the timetable so far is kept).
long polish(NetworkBalance& balance, const FleetProblem& p, std::vector<int>& t, int window,
            int sweeps, Clock::time_point t0, double limit_s, bool* stopped) {
  long moves = 0;
  balance.place_all(t);
  for (int sweep = 0; sweep < sweeps && !*stopped; ++sweep) {
    bool improved = false;
    for (int k = 1; k + 1 < p.trains; ++k) {
      if (limit_s > 0.0 && seconds_since(t0) > limit_s) {
        *stopped = true;
        break;
      }
      auto [lo, hi] = feasible_range(p, t, k);
      lo = std::max(lo, t[k] - window), hi = std::min(hi, t[k] + window);
      const int start = t[k];
      MicroJoules best = balance.substation();
      int best_d = start;
      for (int d = lo; d <= hi; ++d) {
        if (d == start || !allowed(p, t, k, d)) continue;
        balance.move(k, d);
        ++moves;
        if (balance.substation() < best) best = balance.substation(), best_d = d;
      }
      balance.move(k, best_d);
      improved |= best_d != start;
      t[k] = best_d;
    }
    if (!improved) break;
  }
  return moves;
}

}  // namespace

HeadwayOptimiserResult optimise_network_headways(const FleetModels& models,
                                                 const HeadwayOptimiserOptions& options) {
  const auto t0 = Clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const FleetProblem& p = models.problem();
  const EnergyModelOptions& eo = models.options();
  if (eo.model != EnergyModel::Network)
    throw std::invalid_argument("optimise_network_headways needs the network model");
  const power::PowerSupply& supply = *eo.power_supply;
  const double horizon = p.span_s + models.trip().arrival_s() + 10.0;
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  HeadwayOptimiserResult out;
  HeadwayOptimiserSummary& s = out.summary;
  auto report = [&](const std::string& stage, double best) {
    if (options.progress) options.progress({seconds_since(t0), best, NAN, stage});
  };
  // The coarse grid of the annealing and first polish.
  EnergyModelOptions coarse_options = eo;
  coarse_options.time_step_s = std::max(eo.time_step_s, options.anneal_step_s);
  const NetworkProfile coarse(models.trip(), coarse_options.ticks_per_second());

  // Starts: the two-train approximation's exact optimum (with peak windows: the windowed DP's,
  // the same values for both classes) and the uniform timetable.
  const int lo = p.any_headway_min_s(), m = p.any_headway_max_s() - lo + 1;
  std::vector<double> value(m, 0.0);
  {
    NetworkBalance two(coarse, supply, eo.traction_efficiency, 2,
                       p.any_headway_max_s() + models.trip().arrival_s() + 10.0, threads);
    for (int e = 0; e < m; ++e) {
      two.place_all({0, lo + e});
      value[e] = -to_joules(two.substation());
    }
  }
  std::vector<std::vector<int>> starts;
  if (p.windowed()) {
    starts.push_back(
        departures_from_headways(maximise_windowed(p, WindowedValue{value, value}).headways_s));
  } else {
    const HeadwayDomain dom{p.trains - 1, p.headway_min_s, p.headway_max_s, p.span_s};
    starts.push_back(departures_from_headways(maximise_separable(dom, value).headways_s));
  }
  starts.push_back(departures_from_headways(uniform_headways(p)));
  report("starts", 0.0);

  const int runs = static_cast<int>(starts.size()) * std::max(1, options.restarts);
  const long moves = options.restarts == 0 ? 0 : options.moves_per_run;
  std::vector<RunResult> results(runs);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int r = 0; r < runs; ++r) {
    NetworkBalance balance(coarse, supply, eo.traction_efficiency, p.trains, horizon, 1);
    results[r] = anneal(balance, p, starts[r % starts.size()], options.seed, r, moves, t0,
                        kAnnealShareOfTimeLimit * options.time_limit_s);
  }
  std::size_t best = 0;
  for (std::size_t r = 0; r < results.size(); ++r) {
    s.moves += results[r].moves;
    s.time_limit_reached |= results[r].stopped;
    if (results[r].substation < results[best].substation) best = r;
  }
  s.start_used_J = 0.0;
  report("annealing done", 0.0);
  // Polish the best annealed timetable: on the coarse grid, then on the model's own, until the
  // time limit.
  std::vector<int> t = results[best].departures;
  bool polish_stopped = false;
  {
    NetworkBalance balance(coarse, supply, eo.traction_efficiency, p.trains, horizon, threads);
    s.moves += polish(balance, p, t, options.polish_window_s, 5, t0, options.time_limit_s,
                      &polish_stopped);
  }
  if (coarse.ticks_per_second() != eo.ticks_per_second() && !polish_stopped) {
    NetworkBalance balance(models.network_profile(), supply, eo.traction_efficiency, p.trains,
                           horizon, threads);
    s.moves += polish(balance, p, t, std::min(2, options.polish_window_s), 3, t0,
                      options.time_limit_s, &polish_stopped);
  }
  s.time_limit_reached |= polish_stopped;
  out.headways_s = headways_from_departures(t);
  out.evaluation = models.evaluate(t);
  s.method = "annealing (" + std::to_string(runs) +
             " runs) and polish on the network model, network bound";
  // The regenerated energy the line took (the fleet total's "used" is traction minus substation
  // energy, which auxiliaries and line losses make negative on the network).
  s.used_regen_J = out.evaluation.network ? out.evaluation.network->used_regen_J
                                          : out.evaluation.total.used_regen_J;
  s.substation_J = out.evaluation.total.substation_J();
  // The bound is on substation + curtailed traction energy (network_bound.hpp); the gap counts
  // the result's curtailed traction (none on the example supply) as drawn.
  s.bound_used_regen_J = NAN;
  s.bound_substation_J =
      network_substation_bound(models.network_profile(), supply, eo.traction_efficiency, p)
          .substation_J;
  s.curtailed_traction_J =
      out.evaluation.network ? out.evaluation.network->curtailed_traction_J : 0.0;
  s.gap_fraction =
      (s.substation_J + s.curtailed_traction_J - s.bound_substation_J) / s.substation_J;
  const bool unsolved = out.evaluation.network && out.evaluation.network->unsolved_instants > 0;
  s.termination = unsolved               ? Termination::FAILURE
                  : s.time_limit_reached ? Termination::NO_CONVERGENCE
                                         : Termination::CONVERGENCE;
  if (unsolved)
    s.message = "the load flow found no solution at some instants";
  else if (s.time_limit_reached)
    s.message = "the time limit stopped the annealing or the polish early";
  s.wall_s = seconds_since(t0);
  report("done", s.used_regen_J);
  return out;
}

}  // namespace ecorail::timetable
