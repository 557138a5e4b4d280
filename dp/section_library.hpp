// SectionLibrary: every section of a line for one train, built once and kept. It holds, per
// consecutive station pair, the section engine (speed envelope, grid and transition table), the
// flat-out run and minimum running time, and the energy-time frontier as a FrontierCurve, each
// made on first use (thread-safe) or all at once side by side. Journeys, fleet timetables, delay
// recovery and Monte Carlo ask it for engines, prices and exact-time solves instead of
// rebuilding engines per call; counters say what was built, so a test can show that a second
// solve rebuilt nothing. Frontiers can be kept between runs in a FrontierStore (the file cache
// lives in output/: dp reads and writes no files); a stored frontier is used only under the
// exact key of its line, train, grid, range and engine version.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dp/frontier.hpp"
#include "dp/frontier_curve.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "physics/trip.hpp"

namespace ecorail::dp {

// Bumped whenever the engine's results change, so frontiers stored by an older engine are
// never read.
inline constexpr const char* kFrontierVersion = "ecorail-frontier-14";

struct SectionLibraryOptions {
  EngineOptions engine;
  TimeSearchOptions search;
  double frontier_span_s = 60.0;  // a section's frontier covers [T_min, T_min + span]
  double frontier_step_s = 1.0;
  // Memory the library's transition tables may take together (bytes; 0: half of what this
  // process can have, dp::memory_limit_bytes). When the estimate of all its sections' tables
  // exceeds it, the library streams: each engine builds its table for each sweep and frees it
  // (EngineOptions::keep_transitions), so a long line needs the memory of the tables in use at
  // once, not of all of them. Results are bit for bit the same; sweeps cost more.
  double memory_budget_bytes = 0.0;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// Keeps frontiers between runs. load() returns nothing for an absent, corrupt or stale entry.
class FrontierStore {
 public:
  virtual ~FrontierStore() = default;
  virtual std::optional<Frontier> load(const std::string& key) = 0;
  virtual void save(const std::string& key, const Frontier& frontier) = 0;
};

// An exact-time solve of one section, with its run laid out as a trip departing at 0.
struct SectionTimeSolve {
  TimeSearchResult search;
  physics::Trip trip;
};

class SectionLibrary {
 public:
  // problem_key identifies line and train (e.g. their checksums) in frontier-store keys.
  SectionLibrary(const physics::Train& train, std::vector<physics::Route> routes,
                 const SectionLibraryOptions& options, std::string problem_key = "");
  ~SectionLibrary();
  SectionLibrary(const SectionLibrary&) = delete;
  SectionLibrary& operator=(const SectionLibrary&) = delete;

  std::size_t size() const { return routes_.size(); }
  const physics::Route& route(std::size_t i) const { return routes_.at(i); }
  const physics::Train& train() const { return train_; }
  const SectionLibraryOptions& options() const { return options_; }

  const SectionEngine& engine(std::size_t i) const;
  // The first section whose track equals section i's (physics::track_key; i itself when no
  // earlier one does). Twins share one transition table and one frontier, and a journey runs a
  // twin's price once.
  std::size_t twin(std::size_t i) const { return twins_.at(i); }
  const physics::SimulationResult& min_time_run(std::size_t i) const;
  double min_time_s(std::size_t i) const { return min_time_run(i).running_time_s; }
  // The frontier, from the store when one is given and holds it, else computed (and saved).
  const FrontierCurve& frontier(std::size_t i, FrontierStore* store = nullptr) const;
  // Whether section i's frontier came from the store.
  bool frontier_from_store(std::size_t i) const;
  // Whether section i's frontier is already computed or loaded (asking never builds it).
  bool has_frontier(std::size_t i) const;
  // The store key of section i's frontier.
  std::string frontier_key(std::size_t i) const;

  // Builds engines of sections [first, last) side by side (each engine's own parallel parts
  // then run on the thread they are given).
  void build_engines(std::size_t first, std::size_t last) const;
  void build_frontiers(std::size_t first, std::size_t last, FrontierStore* store) const;

  // The energy-optimal run of section i in exactly running_time_s (re-simulated). With a memo,
  // the lattice prices its search walks are taken from (and kept in) it: a caller that solves
  // many times of one section keeps one memo for it (dp::LatticeRuns); the run is the same.
  SectionTimeSolve solve(std::size_t i, double running_time_s, LatticeRuns* memo = nullptr) const;
  // The same search without laying its run out as a trip, for a caller that keeps only the run.
  TimeSearchResult time_search(std::size_t i, double running_time_s,
                               LatticeRuns* memo = nullptr) const;

  // What was built so far: engines, flat-out runs, frontiers computed, frontiers loaded.
  int engine_builds() const { return engine_builds_; }
  int frontier_computations() const { return frontier_computations_; }
  int frontier_loads() const { return frontier_loads_; }
  // Whether the tables are built per sweep (see SectionLibraryOptions::memory_budget_bytes),
  // and the estimate of all the sections' tables held together that decided it.
  bool streams_tables() const { return streams_tables_; }
  double tables_estimate_bytes() const { return tables_estimate_bytes_; }

 private:
  struct Slot;
  Slot& slot(std::size_t i) const;

  physics::Train train_;
  std::vector<physics::Route> routes_;
  SectionLibraryOptions options_;
  std::string problem_key_;
  std::vector<std::unique_ptr<Slot>> slots_;
  std::vector<std::size_t> twins_;
  double tables_estimate_bytes_ = 0.0;
  bool streams_tables_ = false;
  mutable std::atomic<int> engine_builds_{0};
  mutable std::atomic<int> frontier_computations_{0};
  mutable std::atomic<int> frontier_loads_{0};
};

}  // namespace ecorail::dp
