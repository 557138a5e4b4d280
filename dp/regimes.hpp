// Regime spans: the driving regimes of a re-simulated run (full traction, partial traction or
// cruise, coast, partial brake, full brake), each with where and when it starts and ends and
// the speeds there. Built from the trace, so they describe what the train did, not what the
// optimiser intended.
#pragma once

#include <vector>

#include "physics/simulator.hpp"

namespace ecorail::dp {

struct RegimeSpan {
  physics::Regime regime = physics::Regime::Coast;
  double start_m = 0.0, end_m = 0.0;
  double start_speed_ms = 0.0, end_speed_ms = 0.0;
  double start_time_s = 0.0, end_time_s = 0.0;
};

// Consecutive trace steps with the same regime form a span; spans shorter than min_length_m
// (integration slivers at switch points) are merged into the span before them.
std::vector<RegimeSpan> regime_spans(const std::vector<physics::TracePoint>& trace,
                                     double min_length_m = 0.5);

}  // namespace ecorail::dp
