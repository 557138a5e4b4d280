#include "dp/section_library.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>

#include "dp/resource_estimate.hpp"
#include "dp/text_format.hpp"
#include "dp/threads.hpp"

namespace ecorail::dp {

struct SectionLibrary::Slot {
  std::once_flag engine_once, frontier_once;
  std::unique_ptr<SectionEngine> engine;
  physics::SimulationResult min_run;
  FrontierCurve frontier;
  bool frontier_from_store = false;
  std::atomic<bool> frontier_ready{false};
};

bool SectionLibraryOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!engine.IsValid(error) || !search.IsValid(error)) return false;
  if (!(frontier_span_s > 0.0 && std::isfinite(frontier_span_s))) {
    return fail("frontier_span_s must be a positive number of seconds");
  }
  if (!(frontier_step_s > 0.0 && frontier_step_s <= frontier_span_s)) {
    return fail("frontier_step_s must be in (0, frontier_span_s]");
  }
  if (!(memory_budget_bytes >= 0.0 && std::isfinite(memory_budget_bytes))) {
    return fail("memory_budget_bytes must be 0 (automatic) or a finite number of bytes");
  }
  return true;
}

SectionLibrary::SectionLibrary(const physics::Train& train, std::vector<physics::Route> routes,
                               const SectionLibraryOptions& options, std::string problem_key)
    : train_(train),
      routes_(std::move(routes)),
      options_(options),
      problem_key_(std::move(problem_key)) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument(why);
  if (routes_.empty()) throw std::invalid_argument("a section library needs at least one route");
  std::map<std::vector<double>, std::size_t> first_with_track;
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    slots_.push_back(std::make_unique<Slot>());
    const auto [it, fresh] = first_with_track.emplace(physics::track_key(routes_[i]), i);
    twins_.push_back(it->second);
    if (!fresh) continue;  // shares its twin's table
    tables_estimate_bytes_ += estimate_engine(train_, routes_[i], options_.engine.grid,
                                              options_.engine.envelope_resolution_m)
                                  .bytes;
  }
  const double budget = options_.memory_budget_bytes > 0.0 ? options_.memory_budget_bytes
                                                           : 0.5 * memory_limit_bytes();
  streams_tables_ = routes_.size() > 1 && tables_estimate_bytes_ > budget;
  if (streams_tables_) options_.engine.keep_transitions = false;
}

SectionLibrary::~SectionLibrary() = default;

SectionLibrary::Slot& SectionLibrary::slot(std::size_t i) const {
  return *slots_.at(i);
}

const SectionEngine& SectionLibrary::engine(std::size_t i) const {
  Slot& s = slot(i);
  std::call_once(s.engine_once, [&] {
    s.engine = twins_[i] == i ? std::make_unique<SectionEngine>(train_, routes_[i], options_.engine)
                              : std::make_unique<SectionEngine>(routes_[i], engine(twins_[i]));
    s.min_run = s.engine->min_time_run();
    ++engine_builds_;
  });
  return *s.engine;
}

const physics::SimulationResult& SectionLibrary::min_time_run(std::size_t i) const {
  engine(i);
  return slot(i).min_run;
}

std::string SectionLibrary::frontier_key(std::size_t i) const {
  const GridSpec& g = options_.engine.grid;
  return format_text(
      "%s|%s|%s->%s|ds %.17g|dv %.17g|sub %.17g|resim %.17g|obj %d|span %.17g|"
      "step %.17g|cruise %d",
      kFrontierVersion, problem_key_.c_str(), routes_.at(i).from_name().c_str(),
      routes_.at(i).to_name().c_str(), g.ds_m, g.dv_kmh, g.substep_m, options_.engine.resim_step_m,
      static_cast<int>(options_.engine.objective), options_.frontier_span_s,
      options_.frontier_step_s, options_.engine.cruise_as_hold ? 1 : 0);
}

namespace {

// Near the minimum running time the frontier is steep: a coast of length x inserted in the
// flat-out run saves energy in proportion to x but time only in proportion to x^2, so
// E ~ E_min_time - k sqrt(T - T_min). Points spaced evenly in sqrt(T - T_min) over the first
// seconds keep the interpolation there as close as elsewhere.
void refine_near_minimum(const SectionEngine& engine, const TimeSearchOptions& search,
                         Frontier& f) {
  constexpr double kSpan_s = 4.0;
  constexpr int kPoints = 12;
  const double t_min = f.min_time_s;
  const double t_end = std::min(t_min + kSpan_s, f.points.back().running_time_s);
  std::vector<FrontierPoint> extra;
  for (int k = 1; k < kPoints; ++k) {
    const double t = t_min + (t_end - t_min) * (k * k) / double(kPoints * kPoints);
    bool near = false;
    for (const FrontierPoint& p : f.points) near |= std::abs(p.running_time_s - t) < 0.05;
    if (near) continue;
    const TimeSearchResult r = solve_for_time(engine, t, search);
    if (!r.converged) continue;
    const auto& sim = r.run.sim;
    extra.push_back({t, sim.running_time_s, sim.energy.traction_work_J, sim.energy.regen_J,
                     sim.energy.net_J(), engine.energy_cost_J(sim), r.run.lambda, true,
                     r.iterations + r.trim_iterations});
  }
  f.points.insert(f.points.end(), extra.begin(), extra.end());
  std::sort(f.points.begin(), f.points.end(), [](const FrontierPoint& a, const FrontierPoint& b) {
    return a.running_time_s < b.running_time_s;
  });
  check_frontier_shape(f, FrontierOptions{}.convexity_tolerance);
}

}  // namespace

const FrontierCurve& SectionLibrary::frontier(std::size_t i, FrontierStore* store) const {
  Slot& s = slot(i);
  std::call_once(s.frontier_once, [&] {
    if (const std::size_t t = twin(i); t != i) {
      // A twin's frontier is its twin's (same track, same engine table): computed once. The
      // twin is an earlier section, which never waits on a later one.
      s.frontier = frontier(t, store);
      s.frontier_from_store = slot(t).frontier_from_store;
      s.frontier_ready = true;
      return;
    }
    const std::string key = frontier_key(i);
    if (store != nullptr) {
      if (std::optional<Frontier> f = store->load(key)) {
        try {
          s.frontier = FrontierCurve(*f);
          s.frontier_from_store = true;
          ++frontier_loads_;
          s.frontier_ready = true;
          return;
        } catch (const std::invalid_argument&) {
          // A stored frontier that cannot make a curve is recomputed.
        }
      }
    }
    FrontierOptions fo;
    fo.t_max_s = min_time_s(i) + options_.frontier_span_s;
    fo.step_s = options_.frontier_step_s;
    fo.search = options_.search;
    Frontier f = compute_frontier(engine(i), fo);
    refine_near_minimum(engine(i), options_.search, f);
    s.frontier = FrontierCurve(f);
    ++frontier_computations_;
    if (store != nullptr) store->save(key, f);
    s.frontier_ready = true;
  });
  return s.frontier;
}

bool SectionLibrary::has_frontier(std::size_t i) const {
  return slot(i).frontier_ready;
}

bool SectionLibrary::frontier_from_store(std::size_t i) const {
  return slot(i).frontier_from_store;
}

namespace {

// Runs job(i) for i in [first, last) side by side; the first exception is rethrown after the
// loop (exceptions may not leave an OpenMP region).
template <typename Job>
void side_by_side(std::size_t first, std::size_t last, const Job& job) {
  std::exception_ptr failure;
  const long n = static_cast<long>(last) - static_cast<long>(first);
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < n; ++k) {
    try {
      job(first + static_cast<std::size_t>(k));
    } catch (...) {
#pragma omp critical(section_library_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

void SectionLibrary::build_engines(std::size_t first, std::size_t last) const {
  const ThreadScope threads(options_.engine.threads);
  side_by_side(first, last, [&](std::size_t i) { engine(i); });
}

void SectionLibrary::build_frontiers(std::size_t first, std::size_t last,
                                     FrontierStore* store) const {
  const ThreadScope threads(options_.engine.threads);
  side_by_side(first, last, [&](std::size_t i) { frontier(i, store); });
}

TimeSearchResult SectionLibrary::time_search(std::size_t i, double running_time_s,
                                             LatticeRuns* memo) const {
  return solve_for_time(engine(i), running_time_s, options_.search, {}, memo);
}

SectionTimeSolve SectionLibrary::solve(std::size_t i, double running_time_s,
                                       LatticeRuns* memo) const {
  SectionTimeSolve out;
  out.search = time_search(i, running_time_s, memo);
  out.trip = physics::Trip({{&routes_[i], &out.search.run.sim, 0.0}}, 0.0, train_.regen_efficiency);
  return out;
}

}  // namespace ecorail::dp
