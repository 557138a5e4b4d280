#include "dp/regimes.hpp"

#include <cmath>
#include <stdexcept>

#include "dp/policy_extraction.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

std::vector<RegimeSpan> regime_spans(const BigVector<physics::TracePoint>& trace,
                                     double min_length_m) {
  std::vector<RegimeSpan> spans;
  for (std::size_t k = 1; k < trace.size(); ++k) {
    const auto& a = trace[k - 1];
    const auto& b = trace[k];
    if (b.s_m <= a.s_m && b.t_s <= a.t_s) continue;
    if (!spans.empty() && spans.back().regime == b.regime) {
      spans.back().end_m = b.s_m;
      spans.back().end_speed_ms = b.v_ms;
      spans.back().end_time_s = b.t_s;
      continue;
    }
    spans.push_back({b.regime, a.s_m, b.s_m, a.v_ms, b.v_ms, a.t_s, b.t_s});
  }
  // Merge slivers into their predecessor, then re-join neighbours that became equal.
  std::vector<RegimeSpan> merged;
  for (const auto& span : spans) {
    const bool sliver = span.end_m - span.start_m < min_length_m;
    if (!merged.empty() && (sliver || merged.back().regime == span.regime)) {
      merged.back().end_m = span.end_m;
      merged.back().end_speed_ms = span.end_speed_ms;
      merged.back().end_time_s = span.end_time_s;
    } else {
      merged.push_back(span);
    }
  }
  // A partial force at a steady speed is a speed hold. The band is checked on every trace point
  // of the span, not only its ends.
  std::size_t k = 0;
  for (auto& span : merged) {
    if (span.regime != physics::Regime::PartialTraction &&
        span.regime != physics::Regime::PartialBrake) {
      continue;
    }
    double lo = INFINITY, hi = -INFINITY;
    while (k < trace.size() && trace[k].s_m < span.start_m) ++k;
    for (std::size_t m = k; m < trace.size() && trace[m].s_m <= span.end_m; ++m) {
      lo = std::min(lo, trace[m].v_ms);
      hi = std::max(hi, trace[m].v_ms);
    }
    span.speed_hold = hi >= lo && hi - lo <= kHoldBand_ms && lo > 0.0;
  }
  return merged;
}

std::string_view span_name(const RegimeSpan& span) {
  return span.speed_hold ? "speed_hold" : physics::regime_name(span.regime);
}

bool MinRegimeOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(min_length_m >= 0.0 && min_length_m <= 10000.0)) {
    return fail("min_length_m must be a length in [0, 10000] m (0: none)");
  }
  if (!(min_duration_s >= 0.0 && min_duration_s <= 3600.0)) {
    return fail("min_duration_s must be a duration in [0, 3600] s (0: none)");
  }
  return true;
}

namespace {
// Phases of the program still below the minimum in its re-simulation.
int short_entries(const physics::ControlProgram& program, const physics::SimulationResult& sim,
                  const MinRegimeOptions& o) {
  int merged = 0;
  merge_short_entries(program, sim, o.min_length_m, o.min_duration_s, &merged);
  return merged;
}
}  // namespace

MinRegimeResult enforce_min_regime(const SectionEngine& engine, const LambdaRun& run,
                                   double target_time_s, const MinRegimeOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  MinRegimeResult out;
  out.run = run;
  out.cost_before_J = out.cost_after_J = engine.energy_cost_J(run.sim);
  if (!options.active()) return out;
  constexpr int kRounds = 3;
  for (int round = 0; round < kRounds; ++round) {
    int merged = 0;
    physics::ControlProgram program = merge_short_entries(
        out.run.program, out.run.sim, options.min_length_m, options.min_duration_s, &merged);
    if (merged == 0) break;
    ++out.rounds;
    out.merged_entries += merged;
    TimeSearchResult trimmed;
    trimmed.run = out.run;
    trimmed.run.program = std::move(program);
    trimmed.run.sim = engine.simulate(trimmed.run.program, run.start);
    trimmed.run.cost_J = engine.energy_cost_J(trimmed.run.sim);
    // The trim's own tolerance is the search's final one (TimeSearchOptions::tolerance_s).
    // The merged program is no optimum of its price: any switch may be trimmed.
    trim_to_time(engine, target_time_s, TimeSearchOptions{}.tolerance_s, trimmed, 0.0, false);
    out.trim_simulations += trimmed.trim_iterations;
    out.run = std::move(trimmed.run);
  }
  out.cost_after_J = engine.energy_cost_J(out.run.sim);
  out.short_entries_left = short_entries(out.run.program, out.run.sim, options);
  out.met = run_arrives(out.run.sim) &&
            std::abs(out.run.sim.running_time_s - target_time_s) <= kTimeTolerance_s;
  return out;
}

}  // namespace ecorail::dp
