#include "cli/montecarlo_options.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/errors.hpp"
#include "cli/plan_input.hpp"
#include "recovery/monte_carlo_run.hpp"
#include "recovery/monte_carlo_stats.hpp"

namespace ecorail::cli {

namespace {

// "i/N" with 1 <= i <= N <= 100000.
std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int i = 0, n = 0;
  char extra = 0;
  if (slash == std::string::npos || std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &extra) != 2 ||
      n < 1 || n > 100000 || i < 1 || i > n)
    bad("--shard", "i/N with 1 <= i <= N (e.g. 1/2); got '" + text + "'");
  return {i, n};
}

std::vector<double> parse_list(const std::string& text, const std::string& flag) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      bad(flag, "a comma-separated list of numbers; got '" + text + "'");
    out.push_back(v);
    at = comma + 1;
  }
  return out;
}

}  // namespace

void check_day_memory(std::uint64_t days, std::size_t stations) {
  const double need =
      static_cast<double>(days) * static_cast<double>(recovery::day_memory_bytes(stations));
  const double have =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (have > 0.0 && need > 0.5 * have) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "at most half the memory for the day records: %llu days need about %.1f GB, "
                  "the machine has %.1f GB; run them in shards (--shard i/N) and merge",
                  static_cast<unsigned long long>(days), need / 1e9, have / 1e9);
    bad("--days", buf);
  }
}

recovery::MonteCarloOptions simulation_options(const MonteCarloArgs& a) {
  if (a.days < 1 || a.days > 100000000) bad("--days", "a number of days from 1 to 1e8");
  if (a.seed < 0) bad("--seed", "a seed >= 0");
  recovery::MonteCarloOptions o = a.sim;
  const auto policy = recovery::recovery_policy_from_name(a.recovery);
  if (!policy) bad("--recovery", "exact, exact-punctual or rule; got '" + a.recovery + "'");
  o.recovery = *policy;
  const auto followers = recovery::follower_model_from_name(a.followers);
  if (!followers) bad("--followers", "driven or shortcut; got '" + a.followers + "'");
  o.followers = *followers;
  std::string why;
  if (!recovery::parse_delay_tail(a.tail, o.delays, &why)) bad("--tail", why);
  o.seed = static_cast<std::uint64_t>(a.seed);
  require_valid(o);
  if (!(a.frontier_span_s >= 10.0 && a.frontier_span_s <= 600.0))
    bad("--frontier-span", "a span in [10, 600] s");
  return o;
}

std::pair<int, int> shard_of(const MonteCarloArgs& a) {
  std::pair<int, int> shard{1, 1};
  if (!a.shard.empty()) shard = parse_shard(a.shard);
  if (a.adjust && !a.shard.empty()) bad("--shard", "no shards with --adjust");
  return shard;
}

recovery::PlanAdjustmentOptions adjustment_options(const MonteCarloArgs& a) {
  recovery::PlanAdjustmentOptions adj;
  if (a.adjust) {
    if (a.adjusted_csv.empty()) bad("--adjusted-csv", "the file the adjusted plan goes to");
    adj.thetas = parse_list(a.thetas, "--thetas");
    adj.extra_dwells_s = parse_list(a.extra_dwells, "--extra-dwells");
    adj.run_early_s = parse_list(a.run_early_values, "--run-early-values");
    for (double b : adj.run_early_s)
      if (!(b >= 0.0 && b <= a.sim.early_s))
        bad("--run-early-values", "offsets within [0, --early]; got '" + a.run_early_values + "'");
    if (a.sim.run_early_s != 0.0) bad("--run-early", "--run-early-values with --adjust");
    adj.target_punctuality = a.target;
    adj.search_days = static_cast<std::uint64_t>(std::max(0LL, a.search_days));
    adj.threads = a.problem.threads;
    require_valid(adj);
  } else if (!a.adjusted_csv.empty()) {
    bad("--adjusted-csv", "only with --adjust");
  }
  return adj;
}

void add_montecarlo_options(CLI::App* cmd, MonteCarloArgs& a) {
  add_plan_source_options(cmd, a.plan_file, a.reference);
  cmd->add_option("--days", a.days, "simulated days")->capture_default_str();
  cmd->add_option("--seed", a.seed, "seed of the delay draws")->capture_default_str();
  cmd->add_option("--recovery", a.recovery,
                  "exact (question 3.1's policy, early running allowed), exact-punctual (the same, "
                  "every arrival on the way punctual where flat out can make it) or rule (flat "
                  "out until on time)")
      ->capture_default_str();
  cmd->add_option("--followers", a.followers,
                  "driven (a train held up by the one ahead waits and is driven back on time "
                  "under the cap, as `delay` drives it) or shortcut (the fast mode: departures "
                  "at least --separation apart, nothing re-simulated)")
      ->capture_default_str();
  cmd->add_option("--tail", a.tail,
                  "delays over 10 s: exponential:MEAN (10 s + exponential) or uniform:LOW:HIGH")
      ->capture_default_str();
  cmd->add_option("--early", a.sim.early_s, "trains may arrive and depart this early (s)")
      ->capture_default_str();
  cmd->add_option("--run-early", a.sim.run_early_s,
                  "run the plan this much ahead of the timetable, within --early (s)")
      ->capture_default_str();
  cmd->add_option("--run-early-values", a.run_early_values,
                  "operating offsets searched by --adjust (s)")
      ->capture_default_str();
  cmd->add_option("--min-dwell", a.sim.min_dwell_s, "shortest dwell at a stop (s)")
      ->capture_default_str();
  cmd->add_option("--takeover", a.sim.takeover_s,
                  "a delay over this is not recovered: the next service takes over (s)")
      ->capture_default_str();
  cmd->add_option("--punctual", a.sim.punctual_s, "an arrival this late is still punctual (s)")
      ->capture_default_str();
  cmd->add_option("--separation", a.sim.separation_s,
                  "least time between departures from a station (s; default: from the cap)");
  cmd->add_option("--knot-step", a.sim.knot_step_s,
                  "section runs precomputed every this many seconds of running time")
      ->capture_default_str();
  cmd->add_option("--step", a.sim.bin_step_s, "power-flow time step (s, divides 1 s)")
      ->capture_default_str();
  cmd->add_option("--shard", a.shard, "simulate slice i of N of the days (i/N)");
  cmd->add_flag("--adjust", a.adjust,
                "search the plan family for the least substation energy at the punctuality "
                "target");
  cmd->add_option("--target", a.target, "punctuality target of --adjust (share)")
      ->capture_default_str();
  cmd->add_option("--search-days", a.search_days, "days per candidate plan of --adjust")
      ->capture_default_str();
  cmd->add_option("--thetas", a.thetas,
                  "margin mixes searched by --adjust (0: optimal split, "
                  "1: equal margins)")
      ->capture_default_str();
  cmd->add_option("--extra-dwells", a.extra_dwells, "extra dwells searched by --adjust (s)")
      ->capture_default_str();
  cmd->add_option("--adjusted-csv", a.adjusted_csv, "write the adjusted plan (timetable CSV)");
  add_plan_engine_options(cmd, a.problem, a.frontier_span_s, a.cache_dir, a.no_cache);
  cmd->add_flag("--quiet", a.quiet, "no progress line on stderr");
  cmd->add_flag("--full-report", a.full_report, "print the full report");
  cmd->add_option("--json", a.json, "write the statistics and every day's record (JSON)");
  cmd->add_option("--csv", a.csv, "write one row per day (CSV)");
  cmd->add_option("--svg-prefix", a.svg_prefix,
                  "write P_lateness.svg, P_energy.svg and P_punctuality.svg");
}

}  // namespace ecorail::cli
