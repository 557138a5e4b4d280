#include "dp/timing_label_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "dp/objective.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp::timing {

namespace {

using physics::Control;

// A repaired passing time lands this far inside the bound it missed.
constexpr double kRepairInside_s = 0.01;
constexpr int kRepairBisections = 60;
// Switches stay at least this far apart (m).
constexpr double kLeastSwitchGap_m = 1e-3;

constexpr Control kControls[] = {Control::MaxTraction, Control::Hold, Control::Coast,
                                 Control::MaxBrake};

struct Label {
  double e = 0.0;  // v^2 / 2 (J/kg)
  double t = 0.0;  // s since the part's departure
  double cost = 0.0;
};

// Back pointer of a label: its parent in the stage before and the control that led to it.
struct Back {
  std::int32_t parent = -1;
  Control control = Control::Coast;
};

struct StageEnd {
  double e = 0.0, t = 0.0, cost = 0.0;
  bool ok = false;
  bool stopped = false;  // came to rest at the part's end
};

// One stage from s0 to s1 with control c (coarse Heun substeps, the envelope supervised).
StageEnd advance(const physics::Motion& motion, Objective objective, const physics::Train& train,
                 double s0, double e0, double t0, double s1, Control c, double substep_m,
                 double length_m) {
  StageEnd r;
  double s = s0, e = e0, t = t0, traction = 0.0, brake = 0.0, input = 0.0, regen = 0.0;
  while (s < s1 - 1e-9) {
    const double seg_end = motion.route().at(s).end_m;
    const double h = std::min({substep_m, s1 - s, seg_end - s});
    const physics::Substep sub = motion.substep(s, e, h, c, 2);
    traction += sub.traction_work_J;
    brake += sub.regen_brake_work_J;
    input += sub.traction_input_J;
    regen += sub.regen_J;
    t += sub.time_s;
    s += sub.length_m;
    e = sub.e_end;
    if (sub.stopped || sub.length_m <= 0.0) {
      // At rest: only at the part's end (its stop) is that an end.
      if (std::fabs(s - length_m) > kStopTolerance_m) return r;
      r.stopped = true;
      break;
    }
  }
  r.e = e;
  r.t = t;
  r.cost = energy_cost_J(objective, train, traction, brake, input, regen);
  r.ok = true;
  return r;
}

// [lo, hi] kept `margin` inside (its middle half when narrower than twice the margin).
std::pair<double, double> inside(double lo, double hi, double margin) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi - lo >= 2.0 * margin) {
    return {std::isfinite(lo) ? lo + margin : lo, std::isfinite(hi) ? hi - margin : hi};
  }
  const double q = 0.25 * (hi - lo);
  return {lo + q, hi - q};
}

}  // namespace

LabelSearchResult label_search(const SectionEngine& engine, const StartState& start,
                               const EndCheck& end, double earliest_arrival_s,
                               double latest_arrival_s, const std::vector<LabelWindow>& windows,
                               const LabelSearchOptions& o, const ProgressFn& progress) {
  LabelSearchResult out;
  if (!o.IsValid()) return out;
  const physics::Motion& motion = engine.motion();
  const physics::Train& train = engine.train();
  const Objective objective = engine.options().objective;
  const double length = engine.route().length_m();
  double v_top = 0.0;
  for (const auto& seg : engine.route().segments()) v_top = std::max(v_top, seg.speed_limit_ms);
  if (!(length > 0.0 && v_top > 0.0)) return out;

  // Stage ends: every stage_m (stretched so that there are at most max_stages), and every
  // passing point.
  const double stage_m = std::max(o.stage_m, length / o.max_stages);
  std::vector<double> pos{0.0};
  std::vector<int> window_at;  // per stage end: the window checked there, or -1
  window_at.push_back(-1);
  std::vector<std::size_t> order(windows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return windows[a].s_m < windows[b].s_m; });
  std::size_t next_window = 0;
  while (pos.back() < length - 1e-9) {
    double s = std::min(length, pos.back() + stage_m);
    int w = -1;
    if (next_window < order.size() && windows[order[next_window]].s_m <= s + 1e-9 &&
        windows[order[next_window]].s_m < length - 1e-9) {
      w = static_cast<int>(order[next_window++]);
      s = windows[w].s_m;
      if (s <= pos.back() + 1e-9) {  // (two windows at one place, or one at the start)
        window_at.back() = w;
        continue;
      }
    }
    pos.push_back(s);
    window_at.push_back(w);
  }
  const int stages = static_cast<int>(pos.size()) - 1;
  out.stages = stages;

  // The accepted ranges of every window, and per stage end the latest time a label may have
  // there and still meet every later latest bound (and the arrival) at the line's top speed.
  struct Range {
    double t_lo, t_hi, v_lo, v_hi;
  };
  std::vector<Range> ranges(windows.size());
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const LabelWindow& w = windows[i];
    const auto [t_lo, t_hi] = inside(w.earliest_s, w.latest_s, o.time_margin_s);
    const auto [v_lo, v_hi] = inside(w.min_ms, w.max_ms, o.speed_margin_ms);
    ranges[i] = {t_lo, t_hi, v_lo, v_hi};
  }
  const auto [arr_lo, arr_hi] = inside(earliest_arrival_s, latest_arrival_s, o.time_margin_s);
  const auto [end_lo, end_hi] = end.moving ? inside(end.min_ms, end.max_ms, o.speed_margin_ms)
                                           : std::pair<double, double>{0.0, 0.0};
  std::vector<double> latest_at(pos.size(), arr_hi + o.repair_s);
  for (int j = stages - 1; j >= 0; --j) {
    latest_at[j] = latest_at[j + 1] - (pos[j + 1] - pos[j]) / v_top;
    if (window_at[j] >= 0) {
      latest_at[j] = std::min(latest_at[j], ranges[window_at[j]].t_hi + o.repair_s);
    }
  }
  // The penalty of a label outside a range by less than its repair band (the caller moves the
  // run onto the window); +infinity beyond it.
  auto miss_J = [&](double x, double lo, double hi, double band, double penalty) {
    const double d = std::max({0.0, lo - x, x - hi});
    return d == 0.0 ? 0.0 : d <= band ? penalty * d : kInf;
  };
  auto window_miss_J = [&](int w, double e, double t) {
    if (w < 0) return 0.0;
    const Range& r = ranges[w];
    return miss_J(t, r.t_lo, r.t_hi, o.repair_s, o.time_penalty_J_per_s) +
           miss_J(physics::speed_from_e(e), r.v_lo, r.v_hi, o.repair_ms, o.speed_penalty_J_per_ms);
  };

  // Labels slower than a crawl are dropped between the ends: at walking pace the coarse
  // integration's time drifts from the fine re-simulation's by seconds (a run braked to 0.2 m/s
  // and driven off again arrived 7 s earlier on the simulator), and no window is met by
  // crawling that a run a little faster does not meet too (a speed window below the crawl
  // lowers it).
  double v_crawl = o.crawl_ms;
  for (const Range& r : ranges) v_crawl = std::min(v_crawl, 0.5 * r.v_hi);
  const double e_crawl = 0.5 * v_crawl * v_crawl;
  std::vector<std::vector<Back>> back(pos.size());
  std::vector<Label> cur, next;
  const double e0 = 0.5 * start.speed_ms * start.speed_ms;
  cur.push_back({e0, 0.0, 0.0});
  back[0].push_back({});
  // A label's bucket is a key of its (speed, time) buckets; the stage's labels are sorted by
  // key, then by cost.
  const int speed_buckets = static_cast<int>(std::ceil(v_top / o.speed_bucket_ms)) + 2;
  std::vector<std::pair<std::int64_t, std::int32_t>> keyed;
  for (int j = 0; j < stages; ++j) {
    if (j % 20 == 0) report_progress(progress, "label search", j, stages);
    const double s0 = pos[j], s1 = pos[j + 1];
    const bool last = j + 1 == stages;
    std::vector<Label> made;
    std::vector<Back> made_back;
    for (std::size_t i = 0; i < cur.size(); ++i) {
      const Label& l = cur[i];
      for (const Control c : kControls) {
        if (++out.advances > o.max_advances) {
          out.out_of_budget = true;
          return out;
        }
        const StageEnd r =
            advance(motion, objective, train, s0, l.e, l.t, s1, c, o.substep_m, length);
        if (!r.ok || r.t > latest_at[j + 1] || (r.stopped && !last)) continue;
        if (!last && r.e < e_crawl) continue;
        double miss = window_miss_J(window_at[j + 1], r.e, r.t);
        if (last) {
          if (!end.moving && !r.stopped) continue;
          miss += miss_J(r.t, arr_lo, arr_hi, o.repair_s, o.time_penalty_J_per_s);
          if (end.moving) {
            miss += miss_J(physics::speed_from_e(r.e), end_lo, end_hi, o.repair_ms,
                           o.speed_penalty_J_per_ms);
          }
        }
        if (!std::isfinite(miss)) continue;
        made.push_back({r.e, r.t, l.cost + r.cost + miss});
        made_back.push_back({static_cast<std::int32_t>(i), c});
      }
    }
    keyed.clear();
    for (std::size_t k = 0; k < made.size(); ++k) {
      const std::int64_t vb = std::clamp(static_cast<std::int64_t>(std::lround(
                                             physics::speed_from_e(made[k].e) / o.speed_bucket_ms)),
                                         std::int64_t{0}, std::int64_t{speed_buckets});
      const std::int64_t tb = static_cast<std::int64_t>(std::floor(made[k].t / o.time_bucket_s));
      keyed.push_back({tb * (speed_buckets + 1) + vb, static_cast<std::int32_t>(k)});
    }
    std::sort(keyed.begin(), keyed.end(), [&](const auto& a, const auto& b) {
      return a.first != b.first ? a.first < b.first : made[a.second].cost < made[b.second].cost;
    });
    next.clear();
    back[j + 1].clear();
    // Per bucket the cheapest label, and the soonest, the latest, the fastest and the slowest
    // when they are others: a bucket holding only its cheapest label would lose the run a
    // later window needs (a stage of full traction at speed gains less than a bucket, and
    // beside a hold it would never let the run speed up; a label a little later or sooner than
    // the cheapest meets an earliest or a latest bound it misses).
    for (std::size_t k = 0; k < keyed.size();) {
      const std::int32_t cheapest = keyed[k].second;
      std::int32_t keep[] = {cheapest, cheapest, cheapest, cheapest, cheapest};
      std::size_t end_k = k;
      for (; end_k < keyed.size() && keyed[end_k].first == keyed[k].first; ++end_k) {
        const std::int32_t m = keyed[end_k].second;
        if (made[m].t < made[keep[1]].t) keep[1] = m;
        if (made[m].t > made[keep[2]].t) keep[2] = m;
        if (made[m].e > made[keep[3]].e) keep[3] = m;
        if (made[m].e < made[keep[4]].e) keep[4] = m;
      }
      for (int a = 0; a < 5; ++a) {
        bool again = false;
        for (int b = 0; b < a; ++b) again = again || keep[b] == keep[a];
        if (again) continue;
        next.push_back(made[keep[a]]);
        back[j + 1].push_back(made_back[keep[a]]);
      }
      k = end_k;
    }
    out.labels += static_cast<long>(next.size());
    cur.swap(next);
    if (cur.empty()) return out;
  }
  // The least energy at the end, back to the start: the control of every stage.
  std::size_t best = 0;
  for (std::size_t i = 1; i < cur.size(); ++i) {
    if (cur[i].cost < cur[best].cost) best = i;
  }
  out.dp_cost_J = cur[best].cost;
  std::vector<Control> controls(stages);
  std::int32_t idx = static_cast<std::int32_t>(best);
  for (int j = stages; j >= 1; --j) {
    controls[j - 1] = back[j][idx].control;
    idx = back[j][idx].parent;
  }
  LambdaRun run;
  run.lambda = NAN;
  run.start = start;
  for (int j = 0; j < stages; ++j) {
    if (run.program.empty() || run.program.back().control != controls[j]) {
      run.program.push_back({pos[j], controls[j]});
    }
  }
  run.sim = engine.simulate(run.program, start);
  run.cost_J = engine.energy_cost_J(run.sim);
  out.run = std::move(run);
  return out;
}

bool repair_passing_times(const SectionEngine& engine, const StartState& start, LambdaRun& run,
                          const std::vector<LabelWindow>& windows, int* simulations) {
  std::vector<LabelWindow> sorted = windows;
  std::sort(sorted.begin(), sorted.end(),
            [](const LabelWindow& a, const LabelWindow& b) { return a.s_m < b.s_m; });
  double before_m = 0.0;  // switches up to here are fixed
  for (const LabelWindow& w : sorted) {
    const double t = passing_at(run.sim.trace, w.s_m).t_s;
    const bool exact = w.earliest_s == w.latest_s;
    double target = NAN;
    if (exact && std::fabs(t - w.earliest_s) > 0.25 * kZeroWidthTime_s) {
      target = w.earliest_s;
    } else if (!exact && t > w.latest_s) {
      target = w.latest_s - kRepairInside_s;
    } else if (!exact && t < w.earliest_s) {
      target = w.earliest_s + kRepairInside_s;
    }
    if (std::isfinite(target)) {
      bool met = false;
      physics::ControlProgram& p = run.program;
      for (std::size_t k = p.size(); k-- > 1 && !met;) {
        if (!(p[k].from_m > before_m && p[k].from_m < w.s_m)) continue;
        const double lo = std::max(p[k - 1].from_m, before_m) + kLeastSwitchGap_m;
        const double hi =
            std::min(k + 1 < p.size() ? p[k + 1].from_m : w.s_m, w.s_m) - kLeastSwitchGap_m;
        if (!(hi > lo)) continue;
        // Passing time minus target with switch k at x (NaN when the run does not pass).
        auto miss = [&](double x, physics::SimulationResult* sim) {
          physics::ControlProgram q = p;
          q[k].from_m = x;
          *sim = engine.resimulate(q, start, run.sim);
          ++*simulations;
          return passing_at(sim->trace, w.s_m).t_s - target;
        };
        physics::SimulationResult sim_lo, sim_hi, sim_mid;
        double f_lo = miss(lo, &sim_lo), f_hi = miss(hi, &sim_hi);
        if (!(f_lo * f_hi <= 0.0)) continue;  // (NaN too)
        double a = lo, b = hi;
        for (int it = 0; it < kRepairBisections; ++it) {
          const double mid = 0.5 * (a + b);
          const double f_mid = miss(mid, &sim_mid);
          if (!std::isfinite(f_mid)) break;
          if ((f_mid <= 0.0) == (f_lo <= 0.0)) {
            a = mid;
            f_lo = f_mid;
          } else {
            b = mid;
          }
          if (std::fabs(f_mid) <= 0.25 * kZeroWidthTime_s) {
            p[k].from_m = mid;
            run.sim = std::move(sim_mid);
            met = true;
            break;
          }
        }
      }
      if (!met) return false;
    }
    before_m = w.s_m;
  }
  run.cost_J = engine.energy_cost_J(run.sim);
  return true;
}

}  // namespace ecorail::dp::timing
