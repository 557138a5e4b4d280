#include "dp/regimes.hpp"

namespace ecorail::dp {

std::vector<RegimeSpan> regime_spans(const std::vector<physics::TracePoint>& trace,
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
  return merged;
}

}  // namespace ecorail::dp
