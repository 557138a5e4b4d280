#include "dp/capped_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "dp/lambda_bracket.hpp"
#include "dp/objective.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

namespace {

constexpr physics::Control kControls[] = {physics::Control::MaxTraction, physics::Control::Hold,
                                          physics::Control::Coast, physics::Control::MaxBrake};
constexpr double kCreep_ms = 0.05;  // a cap below this holds the train (as the simulator does)

struct Label {
  double e = 0.0;  // v^2 / 2
  double t = 0.0;  // s since the planned departure (wait included)
  double cost = 0.0;
  std::int32_t parent = -1;
  physics::Control control = physics::Control::Coast;
};

struct StageResult {
  double e = 0.0, t = 0.0, traction_J = 0.0, brake_J = 0.0, input_J = 0.0, regen_J = 0.0;
  bool ok = false;
};

// One stage from s0 to s1 with one control, the cap supervised at the end of every substep.
StageResult advance(const physics::Motion& motion, const physics::SpeedCap& cap, double clock0,
                    double s0, double e0, double t0, double s1, physics::Control c,
                    double substep_m, double route_end_m) {
  StageResult r;
  double s = s0, e = e0, t = t0;
  const physics::Route& route = motion.route();
  while (s < s1 - 1e-9) {
    const double seg_end = route.at(s).end_m;
    const double h = std::min({substep_m, s1 - s, seg_end - s});
    physics::Substep sub = motion.substep(s, e, h, c, 2);
    if (cap) {
      double v_cap = cap(clock0 + t + sub.time_s, s + sub.length_m);
      if (v_cap < kCreep_ms) v_cap = 0.0;
      if (sub.e_end > 0.5 * v_cap * v_cap) {
        sub = motion.substep(s, e, h, c, 2, 0.5 * v_cap * v_cap);
        if (!(sub.e_end <= 0.5 * v_cap * v_cap + 1e-6)) return r;  // cannot brake enough
      }
    }
    r.traction_J += sub.traction_work_J;
    r.brake_J += sub.brake_work_J;
    r.input_J += sub.traction_input_J;
    r.regen_J += sub.regen_J;
    t += sub.time_s;
    s += sub.length_m;
    e = sub.e_end;
    if (sub.stopped || sub.length_m <= 0.0) {
      // At rest: only the stop itself ends a stage at rest.
      if (std::fabs(s - route_end_m) <= kStopTolerance_m) break;
      return r;
    }
  }
  r.e = e;
  r.t = t;
  r.ok = true;
  return r;
}

}  // namespace

bool CappedSectionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(stage_m >= 0.5 && stage_m <= 200.0)) return fail("stage_m: expected 0.5 to 200 m");
  if (!(speed_bucket_ms > 0.0 && speed_bucket_ms <= 5.0))
    return fail("speed_bucket_ms: expected (0, 5] m/s");
  if (!(time_bucket_s > 0.0 && time_bucket_s <= 30.0))
    return fail("time_bucket_s: expected (0, 30] s");
  if (!(substep_m > 0.0 && substep_m <= stage_m)) return fail("substep_m: expected (0, stage_m]");
  if (!(max_wait_s >= 0.0 && max_wait_s <= 3600.0)) return fail("max_wait_s: expected 0 to 3600 s");
  if (!(wait_step_s > 0.0)) return fail("wait_step_s: expected > 0 s");
  if (!(resim_step_m > 0.0 && resim_step_m <= 1.0)) return fail("resim_step_m: expected (0, 1] m");
  if (!(time_tolerance_s > 0.0)) return fail("time_tolerance_s: expected > 0 s");
  if (polish_sweeps < 0 || polish_sweeps > 100) return fail("polish_sweeps: expected 0 to 100");
  if (!(polish_window_m >= 0.0 && polish_step_m > 0.0))
    return fail("polish_window_m/polish_step_m: expected a window >= 0 m and a step > 0 m");
  return true;
}

std::string CappedSectionSummary::BriefReport() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: capped-section DP, energy %.1f kJ, wait %.1f s, %.2f s of %.2f s budget, "
                "%ld labels",
                std::string(termination_name(termination)).c_str(), cost_J / 1e3, wait_s,
                total_time_s, time_budget_s, labels);
  return buf;
}

std::string CappedSectionSummary::FullReport() const {
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "%s\n  stages: %d\n  DP estimate: %.1f kJ\n  largest excess over the cap: %.4f "
                "km/h\n  trim iterations: %d\n  polish trials: %ld\n",
                BriefReport().c_str(), stages, dp_cost_J / 1e3, 3.6 * max_cap_overspeed_ms,
                trim_iterations, polish_trials);
  std::string out = buf;
  if (!message.empty()) out += "  " + message + "\n";
  return out;
}

physics::SimulationResult simulate_capped(const SectionEngine& engine,
                                          const physics::ControlProgram& program,
                                          const physics::SpeedCap& cap, double start_clock_s,
                                          double resim_step_m) {
  physics::SimulationOptions opt;
  opt.step_m = resim_step_m;
  opt.rk_order = 4;
  opt.speed_cap = cap;
  opt.start_clock_s = start_clock_s;
  return physics::simulate(engine.motion(), program, opt);
}

CappedSectionResult solve_capped_section(const SectionEngine& engine, const physics::SpeedCap& cap,
                                         double start_clock_s, double time_budget_s,
                                         const CappedSectionOptions& o,
                                         const physics::ControlProgram& hint) {
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  const physics::Motion& motion = engine.motion();
  const physics::Train& train = engine.train();
  const Objective objective = engine.options().objective;
  const double length = engine.route().length_m();
  CappedSectionResult out;
  CappedSectionSummary& sm = out.summary;
  sm.time_budget_s = time_budget_s;
  // The line's top speed bounds how soon the rest of the section can be run.
  double v_top = 0.0;
  for (const auto& seg : engine.route().segments()) v_top = std::max(v_top, seg.speed_limit_ms);

  // First only labels that can still be on time; if none arrives, once more with a slack that
  // keeps late ones (the fastest is then taken).
  bool on_time = false;
  double target_s = time_budget_s;  // the arrival aimed at (later when the budget cannot be met)
  for (const double slack_s : {0.0, 600.0}) {
    std::vector<double> stage_pos{0.0};
    while (stage_pos.back() < length - 1e-9)
      stage_pos.push_back(std::min(length, stage_pos.back() + o.stage_m));
    const int stages = static_cast<int>(stage_pos.size()) - 1;
    sm.stages = stages;
    // Back pointers of every stage, the labels of the current one.
    std::vector<std::vector<std::pair<std::int32_t, physics::Control>>> back(stages + 1);
    std::vector<Label> cur, next;
    for (double w = 0.0; w <= o.max_wait_s + 1e-9; w += o.wait_step_s) {
      cur.push_back({0.0, w, 0.0, -1, physics::Control::Coast});
      back[0].push_back({-1, physics::Control::Coast});
    }
    std::unordered_map<std::int64_t, std::int32_t> bucket;
    for (int j = 0; j < stages; ++j) {
      next.clear();
      bucket.clear();
      const double s0 = stage_pos[j], s1 = stage_pos[j + 1];
      for (std::size_t i = 0; i < cur.size(); ++i) {
        const Label& l = cur[i];
        for (physics::Control c : kControls) {
          const StageResult r =
              advance(motion, cap, start_clock_s, s0, l.e, l.t, s1, c, o.substep_m, length);
          if (!r.ok || r.t + (length - s1) / v_top > time_budget_s + slack_s) continue;
          const double cost = l.cost + energy_cost_J(objective, train, r.traction_J, r.brake_J,
                                                     r.input_J, r.regen_J);
          const std::int64_t key = (static_cast<std::int64_t>(
                                        std::lround(physics::speed_from_e(r.e) / o.speed_bucket_ms))
                                    << 32) |
                                   static_cast<std::int64_t>(std::lround(r.t / o.time_bucket_s));
          const auto [it, fresh] = bucket.try_emplace(key, static_cast<std::int32_t>(next.size()));
          if (fresh) {
            next.push_back({r.e, r.t, cost, static_cast<std::int32_t>(i), c});
          } else if (cost < next[it->second].cost) {
            next[it->second] = {r.e, r.t, cost, static_cast<std::int32_t>(i), c};
          }
        }
      }
      back[j + 1].reserve(next.size());
      for (const Label& l : next) back[j + 1].push_back({l.parent, l.control});
      sm.labels += static_cast<long>(next.size());
      cur.swap(next);
      if (cur.empty()) break;
    }
    if (cur.empty()) {
      if (slack_s == 0.0) continue;
      sm.termination = Termination::FAILURE;
      sm.message = "no run under the cap reaches the stop";
      return out;
    }
    // Least energy on time, else the fastest.
    int best = -1;
    for (std::size_t i = 0; i < cur.size(); ++i) {
      if (cur[i].t > time_budget_s - 0.5 * o.time_tolerance_s) continue;
      if (best < 0 || cur[i].cost < cur[best].cost) best = static_cast<int>(i);
    }
    on_time = best >= 0;
    if (!on_time && slack_s == 0.0) continue;
    if (!on_time) {
      // Late whatever it does: the least energy among the runs within a second of the fastest,
      // trimmed to arrive a second after the fastest could.
      double fastest = INFINITY;
      for (const Label& l : cur) fastest = std::min(fastest, l.t);
      target_s = fastest + 1.0;
      for (std::size_t i = 0; i < cur.size(); ++i)
        if (cur[i].t <= target_s - 0.5 * o.time_tolerance_s &&
            (best < 0 || cur[i].cost < cur[best].cost))
          best = static_cast<int>(i);
    }
    sm.dp_cost_J = cur[best].cost;
    // Back to the first stage: the controls of every stage and the wait.
    std::vector<physics::Control> controls(stages);
    std::int32_t idx = best;
    for (int j = stages; j >= 1; --j) {
      controls[j - 1] = back[j][idx].second;
      idx = back[j][idx].first;
    }
    out.wait_s = idx * o.wait_step_s;
    for (int j = 0; j < stages; ++j)
      if (out.program.empty() || out.program.back().control != controls[j])
        out.program.push_back({stage_pos[j], controls[j]});
    break;
  }

  auto total = [&](const physics::SimulationResult& sim) {
    return out.wait_s + sim.running_time_s;
  };
  // Fits a program to the target arrival: the switch into the last coast moved by the library's
  // root search (LambdaBracket) on the sign of the re-simulated time error (later coasting is
  // faster), so every step halves the bracket (it bisects when an end is infinite): a capped run's
  // time jumps where the cap starts or stops binding, where regula falsi would gain nothing.
  // Keeps the best run it met. Returns whether the time is met.
  auto fit = [&](physics::ControlProgram& program, physics::SimulationResult& sim) {
    sim = simulate_capped(engine, program, cap, start_clock_s + out.wait_s, o.resim_step_m);
    double best_err = std::fabs(total(sim) - target_s);
    if (best_err <= o.time_tolerance_s) return run_arrives(sim);
    int k = -1;
    for (int i = static_cast<int>(program.size()) - 1; i >= 1; --i)
      if (program[i].control == physics::Control::Coast &&
          (program[i - 1].control == physics::Control::MaxTraction ||
           program[i - 1].control == physics::Control::Hold)) {
        k = i;
        break;
      }
    if (k < 1) return false;
    double lo = program[k - 1].from_m;
    double hi = k + 1 < static_cast<int>(program.size()) ? program[k + 1].from_m : length;
    const double inf = std::numeric_limits<double>::infinity();
    physics::ControlProgram trial = program;
    LambdaBracket bracket(
        [&](double switch_m) {
          trial[k].from_m = switch_m;
          physics::SimulationResult t_sim =
              simulate_capped(engine, trial, cap, start_clock_s + out.wait_s, o.resim_step_m);
          ++sm.trim_iterations;
          const double err = total(t_sim) - target_s;
          if (run_arrives(t_sim) && std::fabs(err) < best_err) {
            best_err = std::fabs(err);
            sim = std::move(t_sim);
            program = trial;
          }
          return err > 0.0 ? inf : -inf;  // too slow: the switch moves later
        },
        lo, inf, hi, -inf, 30);
    // No least width: the budget of 30 runs and the tolerance end it.
    bracket.narrow([&] { return best_err <= 0.5 * o.time_tolerance_s; }, -inf);
    return run_arrives(sim) && best_err <= o.time_tolerance_s;
  };
  auto usable = [&](const physics::SimulationResult& sim) {
    return run_arrives(sim) && sim.max_cap_overspeed_ms <= 1e-9;
  };
  bool met = fit(out.program, out.sim);
  // The hint (e.g. the planned control), fitted the same way, when it does better.
  if (!hint.empty() && out.wait_s == 0.0) {
    physics::ControlProgram h = hint;
    physics::SimulationResult h_sim;
    if (fit(h, h_sim) && usable(h_sim) &&
        (!met || engine.energy_cost_J(h_sim) < engine.energy_cost_J(out.sim))) {
      out.program = std::move(h);
      out.sim = std::move(h_sim);
      met = true;
    }
  }
  // Polish: every other switch point tried on a grid around where it is (the grid's stages
  // put switches only at stage ends), each trial fitted to the time, until a sweep changes
  // nothing.
  for (int sweep = 0; met && sweep < o.polish_sweeps; ++sweep) {
    bool improved = false;
    for (std::size_t k = 1; k < out.program.size(); ++k) {
      const double lo = out.program[k - 1].from_m + 0.5;
      const double hi = k + 1 < out.program.size() ? out.program[k + 1].from_m - 0.5 : length;
      const double at = out.program[k].from_m;
      for (double x = std::max(lo, at - o.polish_window_m);
           x <= std::min(hi, at + o.polish_window_m); x += o.polish_step_m) {
        if (std::fabs(x - at) < 1e-9) continue;
        physics::ControlProgram trial = out.program;
        trial[k].from_m = x;
        physics::SimulationResult t_sim;
        ++sm.polish_trials;
        if (fit(trial, t_sim) && usable(t_sim) &&
            engine.energy_cost_J(t_sim) < engine.energy_cost_J(out.sim) - 1.0) {
          out.program = std::move(trial);
          out.sim = std::move(t_sim);
          improved = true;
          break;
        }
      }
    }
    if (!improved) break;
  }
  sm.cost_J = engine.energy_cost_J(out.sim);
  sm.wait_s = out.wait_s;
  sm.total_time_s = total(out.sim);
  sm.max_cap_overspeed_ms = out.sim.max_cap_overspeed_ms;
  const bool arrives = run_arrives(out.sim);
  const bool time_met = std::fabs(sm.total_time_s - time_budget_s) <= o.time_tolerance_s;
  sm.termination = termination_of(arrives, time_met);
  if (!arrives)
    sm.message = "the re-simulated run does not arrive at the stop";
  else if (!on_time)
    sm.message =
        "no run under the cap arrives within the budget: the least energy within a "
        "second of the fastest arrives " +
        std::to_string(sm.total_time_s - time_budget_s) + " s late";
  else if (!time_met)
    sm.message = "the trim could not bring the arrival within the tolerance";
  return out;
}

}  // namespace ecorail::dp
