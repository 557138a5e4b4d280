// StagePrices: a time price per stretch of a section instead of one for the whole of it, and
// speed bands at chosen stages. A journey with timing points prices a second spent before a
// binding window differently from one spent after it (dp/timing_journey.hpp): the backward
// sweep then charges lambda(stage) * dt on each transition out of a stage, and a speed window
// at a timing point makes every node of its stage outside the window infeasible (or, for a
// point between two stages, every transition passing it outside the window), and a band at
// the last stage lets a run end moving. With one price everywhere and no band, a sweep gives
// bit for bit what the single-price sweep gives.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace ecorail::dp {

// Speeds allowed at one stage of the grid (m/s; open bounds are +-infinity). With at_fraction
// 0 the band holds the stage's nodes. With at_fraction in (0, 1) it holds the transitions out
// of the stage instead, at that fraction of the way to the next stage (a timing point between
// two stages): a transition may be taken only when its speed there, with v^2 linear in the
// distance (exact under a constant force), lies in the band. A band on the nodes of both
// neighbouring stages would be stricter than the window: a run slowing through the point passes
// the stage before it above the window's top.
struct SpeedBand {
  int stage = 0;
  double min_ms = 0.0;
  double max_ms = 0.0;
  double at_fraction = 0.0;

  // Whether a run from speed^2 v0_sq to v1_sq passes the point f of the way along inside the
  // band (v^2 linear in the distance). The sweep and the run's extraction both ask this.
  bool passes(double v0_sq, double v1_sq, double f) const {
    const double v = std::sqrt(std::max(0.0, v0_sq + f * (v1_sq - v0_sq)));
    return v >= min_ms && v <= max_ms;
  }
};

struct StagePrices {
  // One price (J/s) per transition out of stage i (i = 0 .. stage_count - 2).
  std::vector<double> lambda_J_per_s;
  std::vector<SpeedBand> bands;
  // A run that ends moving (a journey's last timing point with a speed window above 0): every
  // node of the last stage with a speed in [end_min_ms, end_max_ms] ends the run at cost 0, the
  // others are infeasible. Off (the default): the run ends at rest at the stop. The grid's last
  // stage has nodes above 0 only when the engine's speed envelope does not brake to rest at the
  // end (SectionEngine built with an envelope route that runs on past the end).
  bool end_moving = false;
  double end_min_ms = 0.0;
  double end_max_ms = 0.0;
};

}  // namespace ecorail::dp
