#include "recovery/monte_carlo_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::recovery {

double t_quantile_975(std::int64_t dof) {
  static const double table[] = {0.0,   12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365,
                                 2.306, 2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
                                 2.120, 2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069,
                                 2.064, 2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return 0.0;
  if (dof <= 30) return table[dof];
  const double z = 1.959963984540054, v = static_cast<double>(dof);
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * v * v * v);
}

Estimate estimate(const std::vector<double>& values) {
  Estimate e;
  e.n = static_cast<std::int64_t>(values.size());
  if (e.n == 0) return e;
  double sum = 0.0;
  for (double v : values) sum += v;  // in day order
  e.mean = sum / static_cast<double>(e.n);
  if (e.n < 2) return e;
  double ss = 0.0;
  for (double v : values) ss += (v - e.mean) * (v - e.mean);
  e.sd = std::sqrt(ss / static_cast<double>(e.n - 1));
  e.ci95 = t_quantile_975(e.n - 1) * e.sd / std::sqrt(static_cast<double>(e.n));
  return e;
}

std::vector<std::int64_t> pooled_histogram(const std::vector<DayRecord>& records) {
  std::vector<std::int64_t> h(kLatenessHistogramBins, 0);
  for (const DayRecord& r : records)
    for (std::size_t i = 0; i < r.lateness_histogram.size() && i < h.size(); ++i)
      h[i] += r.lateness_histogram[i];
  return h;
}

MonteCarloStatistics summarise(const std::vector<DayRecord>& records,
                               const std::vector<std::int64_t>& histogram) {
  MonteCarloStatistics s;
  s.days = static_cast<std::int64_t>(records.size());
  auto field = [&](auto get) {
    std::vector<double> v;
    v.reserve(records.size());
    for (const DayRecord& r : records) v.push_back(static_cast<double>(get(r)));
    return estimate(v);
  };
  s.punctuality = field([](const DayRecord& r) { return r.punctuality(); });
  s.mean_lateness_s = field([](const DayRecord& r) { return r.mean_lateness_s(); });
  s.p95_lateness_s = field([](const DayRecord& r) { return r.p95_lateness_s; });
  s.max_lateness_s = field([](const DayRecord& r) { return r.max_lateness_s; });
  {
    std::vector<double> v;
    for (const DayRecord& r : records)
      if (r.recoveries > 0) v.push_back(r.recovery_time_sum_s / static_cast<double>(r.recoveries));
    s.recovery_time_s = estimate(v);
  }
  s.traction_kJ = field([](const DayRecord& r) { return r.traction_kJ; });
  s.substation_kJ = field([](const DayRecord& r) { return r.substation_kJ; });
  s.used_regen_kJ = field([](const DayRecord& r) { return r.used_regen_kJ; });
  s.primary_delays = field([](const DayRecord& r) { return r.primary_delays; });
  s.tail_delays = field([](const DayRecord& r) { return r.tail_delays; });
  s.knock_on_delays = field([](const DayRecord& r) { return r.knock_on_delays; });
  s.takeovers = field([](const DayRecord& r) { return r.takeovers; });
  s.arrivals_taken_over = field([](const DayRecord& r) { return r.arrivals_taken_over; });
  s.unrecovered_episodes = field([](const DayRecord& r) { return r.unrecovered_episodes; });
  s.followers_held_up = field([](const DayRecord& r) { return r.followers_held_up; });
  for (const DayRecord& r : records) {
    s.arrivals += r.arrivals;
    s.punctual += r.punctual;
    s.recoveries += r.recoveries;
    s.min_follower_gap_m = std::min(s.min_follower_gap_m, r.min_follower_gap_m);
    if (s.station_arrivals.size() < r.station_arrivals.size()) {
      s.station_arrivals.resize(r.station_arrivals.size(), 0);
      s.station_punctual.resize(r.station_arrivals.size(), 0);
    }
    for (std::size_t i = 0; i < r.station_arrivals.size(); ++i) {
      s.station_arrivals[i] += r.station_arrivals[i];
      s.station_punctual[i] += r.station_punctual[i];
    }
  }
  s.pooled_punctuality =
      s.arrivals > 0 ? static_cast<double>(s.punctual) / static_cast<double>(s.arrivals) : 1.0;
  s.lateness_histogram = histogram;
  std::int64_t total = 0;
  for (std::int64_t c : histogram) total += c;
  if (total > 0) {
    // Nearest rank: the bin holding the ceil(0.95 total)-th smallest lateness.
    const std::int64_t rank = (95 * total + 99) / 100;
    std::int64_t seen = 0;
    for (std::size_t i = 0; i < histogram.size(); ++i) {
      seen += histogram[i];
      if (seen >= rank) {
        s.pooled_p95_lateness_s = static_cast<double>(i + 1);
        break;
      }
    }
  }
  return s;
}

std::vector<StationPunctuality> station_punctuality(const MonteCarloStatistics& s,
                                                    const std::vector<std::string>& stations) {
  std::vector<StationPunctuality> out;
  for (std::size_t i = 1; i < s.station_arrivals.size() && i < stations.size(); ++i) {
    StationPunctuality p;
    p.station = stations[i];
    p.arrivals = s.station_arrivals[i];
    p.punctual = s.station_punctual[i];
    p.punctuality =
        p.arrivals > 0 ? static_cast<double>(p.punctual) / static_cast<double>(p.arrivals) : 1.0;
    out.push_back(std::move(p));
  }
  return out;
}

namespace {

nlohmann::json estimate_json(const Estimate& e) {
  return {{"mean", e.mean}, {"ci95", e.ci95}, {"sd", e.sd}, {"n", e.n}};
}

nlohmann::json day_json(const DayRecord& r) {
  nlohmann::json j = {{"day", r.day},
                      {"arrivals", r.arrivals},
                      {"punctual", r.punctual},
                      {"station_arrivals", r.station_arrivals},
                      {"station_punctual", r.station_punctual},
                      {"lateness_sum_s", r.lateness_sum_s},
                      {"p95_lateness_s", r.p95_lateness_s},
                      {"max_lateness_s", r.max_lateness_s},
                      {"recoveries", r.recoveries},
                      {"recovery_time_sum_s", r.recovery_time_sum_s},
                      {"unrecovered_episodes", r.unrecovered_episodes},
                      {"primary_delays", r.primary_delays},
                      {"tail_delays", r.tail_delays},
                      {"knock_on_delays", r.knock_on_delays},
                      {"takeovers", r.takeovers},
                      {"arrivals_taken_over", r.arrivals_taken_over},
                      {"traction_kJ", r.traction_kJ},
                      {"regen_kJ", r.regen_kJ},
                      {"used_regen_kJ", r.used_regen_kJ},
                      {"substation_kJ", r.substation_kJ},
                      {"followers_held_up", r.followers_held_up}};
  if (std::isfinite(r.min_follower_gap_m) && r.min_follower_gap_m < 1e299) {
    j["min_follower_gap_m"] = r.min_follower_gap_m;
    j["min_follower_margin_m"] = r.min_follower_margin_m;
  }
  return j;
}

DayRecord day_from_json(const nlohmann::json& j) {
  DayRecord r;
  r.day = j.at("day").get<std::uint64_t>();
  r.arrivals = j.at("arrivals").get<std::int64_t>();
  r.punctual = j.at("punctual").get<std::int64_t>();
  r.station_arrivals = j.at("station_arrivals").get<std::vector<std::int64_t>>();
  r.station_punctual = j.at("station_punctual").get<std::vector<std::int64_t>>();
  r.lateness_sum_s = j.at("lateness_sum_s").get<double>();
  r.p95_lateness_s = j.at("p95_lateness_s").get<double>();
  r.max_lateness_s = j.at("max_lateness_s").get<double>();
  r.recoveries = j.at("recoveries").get<std::int64_t>();
  r.recovery_time_sum_s = j.at("recovery_time_sum_s").get<double>();
  r.unrecovered_episodes = j.at("unrecovered_episodes").get<std::int64_t>();
  r.primary_delays = j.at("primary_delays").get<std::int64_t>();
  r.tail_delays = j.at("tail_delays").get<std::int64_t>();
  r.knock_on_delays = j.at("knock_on_delays").get<std::int64_t>();
  r.takeovers = j.at("takeovers").get<std::int64_t>();
  r.arrivals_taken_over = j.at("arrivals_taken_over").get<std::int64_t>();
  r.traction_kJ = j.at("traction_kJ").get<double>();
  r.regen_kJ = j.at("regen_kJ").get<double>();
  r.used_regen_kJ = j.at("used_regen_kJ").get<double>();
  r.substation_kJ = j.at("substation_kJ").get<double>();
  r.followers_held_up = j.value("followers_held_up", std::int64_t{0});
  if (j.contains("min_follower_gap_m")) {
    r.min_follower_gap_m = j.at("min_follower_gap_m").get<double>();
    r.min_follower_margin_m = j.at("min_follower_margin_m").get<double>();
  }
  return r;
}

constexpr const char* kFormat = "ecorail-montecarlo-1";

// FNV-1a over the compact dump of the JSON without its "checksum" key (keys are sorted, numbers
// printed to round-trip, so a file read back dumps to the same text).
std::string content_checksum(nlohmann::json j) {
  j.erase("checksum");
  const std::string text = j.dump();
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// A day's record within its physical ranges, or std::invalid_argument saying which field.
void check_day(const DayRecord& r) {
  const std::string day = "day " + std::to_string(r.day) + ": ";
  auto fail = [&](const std::string& what) { throw std::invalid_argument(day + what); };
  if (r.arrivals < 0 || r.punctual < 0 || r.punctual > r.arrivals)
    fail("punctual arrivals between 0 and the arrivals");
  if (r.station_arrivals.size() != r.station_punctual.size())
    fail("as many station punctual counts as station arrivals");
  for (std::size_t i = 0; i < r.station_arrivals.size(); ++i)
    if (r.station_arrivals[i] < 0 || r.station_punctual[i] < 0 ||
        r.station_punctual[i] > r.station_arrivals[i])
      fail("punctual arrivals between 0 and the arrivals at station " + std::to_string(i + 1));
  for (std::int64_t c :
       {r.recoveries, r.unrecovered_episodes, r.primary_delays, r.tail_delays, r.knock_on_delays,
        r.takeovers, r.arrivals_taken_over, r.followers_held_up})
    if (c < 0) fail("counts >= 0");
  if (r.tail_delays > r.primary_delays) fail("tail delays at most the delays");
  for (double x : {r.lateness_sum_s, r.p95_lateness_s, r.max_lateness_s, r.recovery_time_sum_s})
    if (!(std::isfinite(x) && x >= 0.0)) fail("lateness and recovery times finite and >= 0");
  if (r.p95_lateness_s > r.max_lateness_s) fail("a 95th percentile at most the largest lateness");
  for (double x : {r.traction_kJ, r.regen_kJ, r.used_regen_kJ, r.substation_kJ})
    if (!(std::isfinite(x) && x >= 0.0)) fail("energies finite and >= 0");
  if (r.used_regen_kJ > r.regen_kJ * (1.0 + 1e-9) + 1e-6)
    fail("used regenerated energy at most the regenerated energy");
  if (!(r.min_follower_gap_m >= 0.0) || !(r.min_follower_margin_m >= -0.01))
    fail("followers never closer than their braking distance to the train ahead");
}

}  // namespace

nlohmann::json run_json(const MonteCarloRun& run, const std::string& shard) {
  const MonteCarloStatistics s = summarise(run.days, run.histogram);
  nlohmann::json per_station = nlohmann::json::array();
  for (const StationPunctuality& p : station_punctuality(s, run.stations))
    per_station.push_back({{"station", p.station},
                           {"arrivals", p.arrivals},
                           {"punctual", p.punctual},
                           {"punctuality", p.punctuality}});
  nlohmann::json days = nlohmann::json::array();
  for (const DayRecord& r : run.days) days.push_back(day_json(r));
  nlohmann::json stats = {{"days", s.days},
                          {"punctuality", estimate_json(s.punctuality)},
                          {"pooled_punctuality", s.pooled_punctuality},
                          {"arrivals", s.arrivals},
                          {"punctual_arrivals", s.punctual},
                          {"mean_lateness_s", estimate_json(s.mean_lateness_s)},
                          {"p95_lateness_s", estimate_json(s.p95_lateness_s)},
                          {"pooled_p95_lateness_s", s.pooled_p95_lateness_s},
                          {"max_lateness_s", estimate_json(s.max_lateness_s)},
                          {"recovery_time_s", estimate_json(s.recovery_time_s)},
                          {"recoveries", s.recoveries},
                          {"traction_kJ", estimate_json(s.traction_kJ)},
                          {"substation_kJ", estimate_json(s.substation_kJ)},
                          {"used_regen_kJ", estimate_json(s.used_regen_kJ)},
                          {"primary_delays", estimate_json(s.primary_delays)},
                          {"tail_delays", estimate_json(s.tail_delays)},
                          {"knock_on_delays", estimate_json(s.knock_on_delays)},
                          {"takeovers", estimate_json(s.takeovers)},
                          {"arrivals_taken_over", estimate_json(s.arrivals_taken_over)},
                          {"unrecovered_episodes", estimate_json(s.unrecovered_episodes)},
                          {"followers_held_up", estimate_json(s.followers_held_up)}};
  if (std::isfinite(s.min_follower_gap_m)) stats["min_follower_gap_m"] = s.min_follower_gap_m;
  nlohmann::json j = {{"format", kFormat},
                      {"config", run.config},
                      {"stations", run.stations},
                      {"plan_energy", run.plan_energy},
                      {"statistics", stats},
                      {"per_station", per_station},
                      {"lateness_histogram", {{"bin_s", 1}, {"counts", run.histogram}}},
                      {"days", days}};
  if (!shard.empty()) j["shard"] = shard;
  j["checksum"] = content_checksum(j);
  return j;
}

MonteCarloRun run_from_json(const nlohmann::json& j) {
  try {
    if (j.at("format").get<std::string>() != kFormat)
      throw std::invalid_argument(std::string("format '") + kFormat + "'");
    if (!j.contains("checksum") || j.at("checksum").get<std::string>() != content_checksum(j))
      throw std::invalid_argument(
          "a checksum that matches its content (the file was edited, damaged or written by an "
          "older program; run the shard again)");
    MonteCarloRun r;
    r.config = j.at("config");
    r.stations = j.at("stations").get<std::vector<std::string>>();
    r.plan_energy = j.at("plan_energy");
    r.histogram = j.at("lateness_histogram").at("counts").get<std::vector<std::int64_t>>();
    if (r.histogram.size() != static_cast<std::size_t>(kLatenessHistogramBins))
      throw std::invalid_argument("a lateness histogram of " +
                                  std::to_string(kLatenessHistogramBins) + " bins");
    for (const nlohmann::json& d : j.at("days")) {
      r.days.push_back(day_from_json(d));
      check_day(r.days.back());
    }
    for (std::int64_t c : r.histogram)
      if (c < 0) throw std::invalid_argument("lateness histogram counts >= 0");
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("a Monte Carlo JSON (") + e.what() + ")");
  }
}

MonteCarloRun merge_runs(const std::vector<MonteCarloRun>& shards,
                         const std::vector<std::string>& names) {
  if (shards.empty()) throw std::invalid_argument("at least one shard to merge");
  auto name = [&](std::size_t i) {
    return i < names.size() ? names[i] : "shard " + std::to_string(i + 1);
  };
  MonteCarloRun out;
  out.config = shards.front().config;
  out.stations = shards.front().stations;
  out.plan_energy = shards.front().plan_energy;
  out.histogram.assign(kLatenessHistogramBins, 0);
  std::vector<std::size_t> owner;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const MonteCarloRun& s = shards[k];
    if (s.config != out.config || s.stations != out.stations || s.plan_energy != out.plan_energy)
      throw std::invalid_argument(name(k) + ": a shard of the same run as " + name(0) +
                                  " (the same plan, seed, days and options); its config differs");
    for (std::size_t i = 0; i < out.histogram.size(); ++i) out.histogram[i] += s.histogram[i];
    out.days.insert(out.days.end(), s.days.begin(), s.days.end());
    owner.insert(owner.end(), s.days.size(), k);
  }
  std::vector<std::size_t> order(out.days.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return out.days[a].day < out.days[b].day; });
  std::vector<DayRecord> sorted;
  sorted.reserve(order.size());
  const std::uint64_t total = out.config.at("days").get<std::uint64_t>();
  for (std::size_t i = 0; i < order.size(); ++i) {
    const DayRecord& d = out.days[order[i]];
    if (i > 0 && d.day == sorted.back().day)
      throw std::invalid_argument(
          name(owner[order[i]]) + ": every day of the run exactly once; day " +
          std::to_string(d.day) + " is also in " + name(owner[order[i - 1]]));
    if (d.day >= total)
      throw std::invalid_argument(name(owner[order[i]]) + ": days of the run (0 to " +
                                  std::to_string(total) + "); it holds day " +
                                  std::to_string(d.day));
    sorted.push_back(d);
  }
  out.days = std::move(sorted);
  if (out.days.size() != total) {
    std::string missing;
    for (std::uint64_t i = 0, k = 0; i < total && missing.empty(); ++i, ++k)
      if (k >= out.days.size() || out.days[k].day != i) missing = std::to_string(i);
    throw std::invalid_argument("every day of the run exactly once: the shards hold " +
                                std::to_string(out.days.size()) + " days of " +
                                std::to_string(total) + " (day " + missing +
                                " is missing; merge every shard of the run)");
  }
  return out;
}

std::size_t day_memory_bytes(std::size_t stations) {
  // The record, its per-station counts and histogram, and about 1 KB of JSON per day.
  return sizeof(DayRecord) + sizeof(std::int64_t) * (2 * stations + kLatenessHistogramBins) + 1024;
}

std::pair<std::uint64_t, std::uint64_t> shard_days(std::uint64_t total, int index, int count) {
  const auto i = static_cast<std::uint64_t>(index - 1), n = static_cast<std::uint64_t>(count);
  return {total * i / n, total * (i + 1) / n};
}

}  // namespace ecorail::recovery
