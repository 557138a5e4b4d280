// What one simulated service day of question 3.2 yields (DayRecord) and the statistics over the
// days (MonteCarloStatistics). Days are independent replications: each statistic is the mean
// over the days of a per-day quantity with a 95 % confidence interval mean +- t(0.975, n - 1)
// s / sqrt(n). The records are kept in day order and every reduction runs in that order, so
// the statistics depend only on which days were simulated, never on threads, processes or
// shards. The JSON of a run holds every day's record (numbers written so that they read back
// bit for bit) and the pooled lateness histogram (integer counts), so shards of a run merge
// into exactly the statistics of the whole run (merge_shards).
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ecorail::recovery {

// Arrivals per second of lateness (bin i: lateness in [i, i + 1) s; the last bin: above).
inline constexpr int kLatenessHistogramBins = 901;

struct DayRecord {
  std::uint64_t day = 0;
  std::int64_t arrivals = 0;  // arrivals served (not taken over)
  std::int64_t punctual = 0;  // of them within the punctuality threshold of the timetable
  std::vector<std::int64_t> station_arrivals, station_punctual;  // per station (0: the first)
  double lateness_sum_s = 0.0;  // sum over arrivals of max(0, arrival - timetable)
  double p95_lateness_s = 0.0;  // the day's 95th percentile of arrival lateness (nearest rank)
  double max_lateness_s = 0.0;
  std::int64_t recoveries = 0;       // late episodes back on time (arrival within the tolerance)
  double recovery_time_sum_s = 0.0;  // from the late departure to that arrival
  std::int64_t unrecovered_episodes = 0;  // late episodes still late at the last station
  std::int64_t primary_delays = 0;        // departures with a drawn delay > 0
  std::int64_t tail_delays = 0;           // of them over the small range (10 s)
  // Departures held by the train ahead: by the separation (shortcut), or by a wait for the line
  // ahead to clear (driven followers).
  std::int64_t knock_on_delays = 0;
  std::int64_t takeovers = 0;            // delays over the take-over threshold (120 s)
  std::int64_t arrivals_taken_over = 0;  // the arrivals those trains did not serve
  double traction_kJ = 0.0, regen_kJ = 0.0, used_regen_kJ = 0.0, substation_kJ = 0.0;
  // Driven followers: trains held up by the one ahead (driven by the follower model), and the
  // least gap and the least gap beyond the braking distance of their re-simulated runs to the
  // train ahead (infinite on a day without one; absent from the JSON then).
  std::int64_t followers_held_up = 0;
  double min_follower_gap_m = std::numeric_limits<double>::infinity();
  double min_follower_margin_m = std::numeric_limits<double>::infinity();
  std::vector<std::int64_t> lateness_histogram;  // kLatenessHistogramBins (not in the JSON)

  double punctuality() const {
    return arrivals > 0 ? static_cast<double>(punctual) / static_cast<double>(arrivals) : 1.0;
  }
  double mean_lateness_s() const {
    return arrivals > 0 ? lateness_sum_s / static_cast<double>(arrivals) : 0.0;
  }
};

struct Estimate {
  std::int64_t n = 0;  // days (replications) it is the mean of
  double mean = 0.0, sd = 0.0;
  double ci95 = 0.0;  // half-width: t(0.975, n - 1) sd / sqrt(n); 0 for n < 2
};

// Student's t quantile t(0.975, dof) (exact table to 30, then the Cornish-Fisher expansion).
double t_quantile_975(std::int64_t dof);
Estimate estimate(const std::vector<double>& values);

struct MonteCarloStatistics {
  std::int64_t days = 0;
  Estimate punctuality, mean_lateness_s, p95_lateness_s, max_lateness_s, recovery_time_s;
  Estimate traction_kJ, substation_kJ, used_regen_kJ;
  Estimate primary_delays, tail_delays, knock_on_delays, takeovers, arrivals_taken_over,
      unrecovered_episodes, followers_held_up;
  double min_follower_gap_m = std::numeric_limits<double>::infinity();  // least over the days
  std::int64_t arrivals = 0, punctual = 0, recoveries = 0;
  double pooled_punctuality = 0.0;
  double pooled_p95_lateness_s = 0.0;  // from the pooled histogram: upper edge of the bin
  std::vector<std::int64_t> station_arrivals, station_punctual;
  std::vector<std::int64_t> lateness_histogram;
};

// records in day order; histogram: the pooled lateness histogram of those days.
MonteCarloStatistics summarise(const std::vector<DayRecord>& records,
                               const std::vector<std::int64_t>& histogram);
std::vector<std::int64_t> pooled_histogram(const std::vector<DayRecord>& records);

// Punctuality at each station after the first: its arrivals, the punctual ones and their share
// (1 at a station without arrivals).
struct StationPunctuality {
  std::string station;
  std::int64_t arrivals = 0, punctual = 0;
  double punctuality = 1.0;
};
std::vector<StationPunctuality> station_punctuality(const MonteCarloStatistics& statistics,
                                                    const std::vector<std::string>& stations);

// A run or a shard of one: what its JSON holds.
struct MonteCarloRun {
  nlohmann::json config;  // everything that shapes the days (plan, seed, options, days total)
  std::vector<std::string> stations;
  std::vector<DayRecord> days;          // in day order
  std::vector<std::int64_t> histogram;  // pooled over days
  nlohmann::json plan_energy;           // the plan without delays (traction, substation)
};

// The run's JSON: format, config, plan, statistics (with confidence intervals), per-station
// punctuality, the pooled histogram and every day's record, and "checksum": FNV-1a (64 bit,
// hex) of the JSON's compact dump without that key, so that an edited or damaged file is
// recognised when it is read back. shard: "" for a whole run, "i/N".
nlohmann::json run_json(const MonteCarloRun& run, const std::string& shard);
// Reads a run's JSON back (std::invalid_argument naming what is missing or wrong): the checksum
// must match the content, and every day must lie in its physical ranges (punctual <= arrivals
// at every station and over the day, counts >= 0, lateness and energies finite and >= 0, used
// regenerated energy at most the regenerated energy).
MonteCarloRun run_from_json(const nlohmann::json& j);
// Shards of one run (same config) into the whole run: every day 0 .. days-1 exactly once
// (std::invalid_argument otherwise, naming the shard by names[i] when names are given).
MonteCarloRun merge_runs(const std::vector<MonteCarloRun>& shards,
                         const std::vector<std::string>& names = {});
// Memory a run keeps per simulated day (its record, per-station counts and lateness histogram,
// and its JSON), for stations stations: what --days is checked against before anything is
// allocated.
std::size_t day_memory_bytes(std::size_t stations);
// The days [first, last) of shard i (1-based) of N over total days: contiguous, sizes differing
// by at most one.
std::pair<std::uint64_t, std::uint64_t> shard_days(std::uint64_t total, int index, int count);

}  // namespace ecorail::recovery
