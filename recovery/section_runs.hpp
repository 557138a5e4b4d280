// SectionRuns: what the Monte Carlo simulator of question 3.2 needs of every section, computed
// once so that a simulated day does no optimal-control solve at all. Per section:
//  - the frontier's time price as a table (-dE/dT every 0.01 s from the flat-out time to the end
//    of the frontier, made non-increasing), which inverts a price into a running time by binary
//    search: the exact allocation of recovery/allocation.hpp, done in microseconds;
//  - "pieces": the energy-optimal run re-simulated at knot running times (the flat-out time, then
//    every knot step, and every running time a plan asks for exactly), each kept as sparse power
//    bins in integer micro-joules on the power-flow grid (bin step, e.g. 0.1 s) with the run
//    departing at 0. A run of any time between two knots is the linear blend of the two pieces
//    (weights by time), laid on the day's grid at its departure rounded to the nearest bin; a
//    run at a knot is that re-simulated run exactly. docs/delays.md gives the study of the knot
//    step and the bin step.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dp/section_library.hpp"
#include "physics/simulator.hpp"

namespace ecorail::recovery {

struct SectionPiece {
  double time_s = 0.0;  // knot running time (the target; the re-simulation meets it within 0.1 s)
  double resimulated_time_s = 0.0;
  std::int64_t traction_uJ = 0, regen_uJ = 0;  // totals of the bins
  std::vector<std::int32_t> offsets;           // bins after the departure
  std::vector<std::int64_t> traction, regen;   // micro-joules per bin, where either is not 0
  physics::SimulationResult sim;               // empty for a piece loaded from a store
  bool has_sim = false;
};

// Keeps section runs between runs of the program (the file cache is output/section_run_cache):
// a stored piece holds the bins, not the trajectory (sim stays empty). load() returns nothing
// for an absent, corrupt or stale entry.
class SectionRunStore {
 public:
  virtual ~SectionRunStore() = default;
  virtual bool load(const std::string& key, SectionPiece* piece) = 0;
  virtual void save(const std::string& key, const SectionPiece& piece) = 0;
};

// A day's power bins of the one supply section (power-flow model), in micro-joules.
struct DayBins {
  double step_s = 0.1;
  std::vector<std::int64_t> traction, regen;
  void reset(std::size_t bins);
  // Regenerated energy used at the same moment: sum over bins of min(traction, regen).
  std::int64_t used_uJ() const;
  std::int64_t traction_uJ() const;
  std::int64_t regen_uJ() const;
};

class SectionRuns {
 public:
  // knot_step_s: spacing of the knots above the flat-out time; bin_step_s must divide 1 s.
  // store (may be null) keeps the pieces between runs.
  SectionRuns(const dp::SectionLibrary& library, dp::FrontierStore* store, double knot_step_s,
              double bin_step_s, SectionRunStore* run_store = nullptr);

  std::size_t sections() const { return min_time_s_.size(); }
  double bin_step_s() const { return bin_step_s_; }
  double min_time_s(std::size_t k) const { return min_time_s_[k]; }
  // Longest running time a run may take: the end of the frontier (pieces are made up to it on
  // demand, see ensure_range).
  double max_time_s(std::size_t k) const { return max_time_s_[k]; }

  // Makes the knots of section k on the knot grid up to upper_s and one at exactly time_s for
  // every time in exact_times_s (rounded to the millisecond). Solves what is missing, sections
  // side by side (OpenMP). A grid knot whose solve misses its time is left out (the blend then
  // spans its neighbours; counted in skipped_knots); an exact time that cannot be solved is a
  // std::runtime_error. Not thread-safe: call before simulating.
  void ensure(std::size_t k, double upper_s, const std::vector<double>& exact_times_s);
  void ensure_all(const std::vector<double>& upper_s,
                  const std::vector<std::vector<double>>& exact_times_s);
  // The piece of an exact time, with its trajectory (solved again when it came from the store).
  const SectionPiece& piece_with_sim(std::size_t k, double time_s);
  int skipped_knots() const { return skipped_knots_; }

  // The running time of section k at which its marginal energy per second equals price (J/s),
  // by the price table; the flat-out time for a price above every marginal, the frontier's end
  // below every marginal.
  double time_for_price(std::size_t k, double price_J_per_s) const;
  // The section's marginal at its flat-out time + one table step (the highest finite price).
  double top_price(std::size_t k) const { return prices_[k].size() > 1 ? prices_[k][1] : 0.0; }

  // Traction (J, by the pieces) of section k run in time_s; adds its bins to day (departure at
  // departure_s on the day's clock). time_s must lie within [min_time_s, the last knot].
  double lay(std::size_t k, double time_s, double departure_s, DayBins& day) const;
  // The re-simulated piece of a knot at exactly time_s (nullptr if there is none).
  const SectionPiece* piece_at(std::size_t k, double time_s) const;
  double last_knot_s(std::size_t k) const;
  std::size_t piece_count() const;

 private:
  // Solves (or loads) one piece; false when a grid knot's solve misses its time.
  bool make_piece(std::size_t k, double time_s, bool required, SectionPiece* out) const;
  std::string piece_key(std::size_t k, long long time_ms) const;
  const dp::SectionLibrary& library_;
  double knot_step_s_, bin_step_s_;
  SectionRunStore* run_store_ = nullptr;
  int skipped_knots_ = 0;
  std::vector<std::map<long long, bool>> skipped_;  // knots left out, by time in ms
  static constexpr double kPriceStep_s = 0.01;
  std::vector<double> min_time_s_, max_time_s_;
  std::vector<std::vector<double>> prices_;                // per section, -dE/dT every kPriceStep_s
  std::vector<std::map<long long, SectionPiece>> pieces_;  // by time in ms
};

// The exact split of total_s over sections (indices into runs) with bounds lo <= t <= hi:
// one time price for every section not at a bound (bisection on the price tables), the sum
// closed exactly between the two ends of the final bracket. out gets one time per section.
void split_by_price(const SectionRuns& runs, const std::vector<std::size_t>& sections,
                    const std::vector<double>& lo, const std::vector<double>& hi, double total_s,
                    std::vector<double>& out);

}  // namespace ecorail::recovery
