#include "dp/section_engine.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "dp/resource_estimate.hpp"
#include "dp/threads.hpp"

namespace ecorail::dp {

bool EngineOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(grid.ds_m > 0.0 && grid.ds_m <= 100.0)) return fail("grid ds_m must be in (0, 100] m");
  if (!(grid.dv_kmh > 0.0 && grid.dv_kmh <= 10.0)) {
    return fail("grid dv_kmh must be in (0, 10] km/h");
  }
  if (!(grid.substep_m > 0.0 && grid.substep_m <= grid.ds_m)) {
    return fail("grid substep_m must be in (0, ds_m]");
  }
  if (objective != Objective::Traction && objective != Objective::Net) {
    return fail("objective must be traction or net");
  }
  if (!(resim_step_m > 0.0 && resim_step_m <= 1.0)) return fail("resim_step_m must be in (0, 1] m");
  if (!(envelope_resolution_m > 0.0 && envelope_resolution_m <= 10.0)) {
    return fail("envelope_resolution_m must be in (0, 10] m");
  }
  if (!(decision_step_m > 0.0 && std::isfinite(decision_step_m))) {
    return fail("decision_step_m must be a positive number of metres");
  }
  if (threads < 0 || threads > kMaxThreads) {
    return fail("threads must be 0 (OpenMP's default) to 1024 (dp::kMaxThreads)");
  }
  return true;
}

namespace {
// Options are checked before any work (the envelope and the table are the expensive part).
// The grid's memory is estimated too, so a grid too fine is refused before it is allocated.
const EngineOptions& validated(const EngineOptions& options, const physics::Train& train,
                               const physics::Route& route) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  check_engine_fits(train, route, options.grid, options.envelope_resolution_m);
  return options;
}
}  // namespace

SectionEngine::SectionEngine(const physics::Train& train, const physics::Route& route,
                             const EngineOptions& options)
    : SectionEngine(train, route, options, route) {}

SectionEngine::SectionEngine(const physics::Train& train, const physics::Route& route,
                             const EngineOptions& options, const physics::Route& envelope_route)
    : train_(train),
      route_(route),
      own_envelope_(&route == &envelope_route ||
                    physics::track_key(route) == physics::track_key(envelope_route)),
      options_(validated(options, train, envelope_route)),
      envelope_(train_, envelope_route, options.envelope_resolution_m),
      motion_(train_, route_, envelope_),
      grid_(envelope_, route_.length_m(), options.grid) {
  if (options_.keep_transitions) {
    const ThreadScope threads(options_.threads);
    table_ = build_table();
  }
}

SectionEngine::SectionEngine(const physics::Route& route, const SectionEngine& twin)
    : train_(twin.train_),
      route_(route),
      options_(twin.options_),
      envelope_(train_, route_, options_.envelope_resolution_m),
      motion_(train_, route_, envelope_),
      grid_(envelope_, route_.length_m(), options_.grid) {
  if (!twin.own_envelope_ || physics::track_key(route_) != physics::track_key(twin.route_)) {
    throw std::invalid_argument("an engine can share only the table of a route with equal track");
  }
  if (options_.keep_transitions) {
    table_ = twin.table_;
    if (table_ == nullptr) {
      const ThreadScope threads(options_.threads);
      table_ = build_table();
    }
  }
}

SectionEngine::SectionEngine(const SectionEngine& twin, GridCruises)
    : train_(twin.train_),
      route_(twin.route_),
      own_envelope_(twin.own_envelope_),
      options_(twin.options_),
      envelope_(twin.envelope_),
      motion_(train_, route_, envelope_),
      grid_(twin.grid_),
      table_(twin.table_) {
  options_.cruise_as_hold = false;
}

std::unique_ptr<TransitionTable> SectionEngine::build_table() const {
  return std::make_unique<TransitionTable>(motion_, grid_, options_.objective, dp_step());
}

const TransitionTable& SectionEngine::transitions() const {
  std::call_once(table_once_, [&] {
    if (table_ == nullptr) {
      const ThreadScope threads(options_.threads);
      table_ = build_table();
    }
  });
  return *table_;
}

const TransitionTable& SectionEngine::table_for_sweep(
    std::unique_ptr<TransitionTable>& local) const {
  if (options_.keep_transitions) return *table_;
  local = build_table();  // under the caller's ThreadScope
  return *local;
}

physics::SimulationResult SectionEngine::simulate(const physics::ControlProgram& program,
                                                  const StartState& start) const {
  return simulate(program, start, options_.resim_step_m);
}

physics::SimulationResult SectionEngine::simulate(const physics::ControlProgram& program,
                                                  const StartState& start, double step_m) const {
  physics::SimulationOptions opt;
  opt.step_m = step_m;
  opt.start_position_m = start.position_m;
  opt.start_speed_ms = start.speed_ms;
  return physics::simulate(motion_, program, opt);
}

physics::SimulationResult SectionEngine::resimulate(
    const physics::ControlProgram& program, const StartState& start,
    const physics::SimulationResult& earlier) const {
  return resimulate(program, start, options_.resim_step_m, earlier);
}

physics::SimulationResult SectionEngine::resimulate(
    const physics::ControlProgram& program, const StartState& start, double step_m,
    const physics::SimulationResult& earlier) const {
  physics::SimulationOptions opt;
  opt.step_m = step_m;
  opt.start_position_m = start.position_m;
  opt.start_speed_ms = start.speed_ms;
  return physics::simulate(motion_, program, opt, earlier);
}

double SectionEngine::energy_cost_J(const physics::SimulationResult& sim) const {
  return dp::energy_cost_J(options_.objective, train_, sim.energy.traction_work_J,
                           sim.energy.brake_work_J, sim.energy.traction_input_J,
                           sim.energy.regen_J);
}

ValueFunction SectionEngine::sweep(double lambda) const {
  const ThreadScope threads(options_.threads);
  std::unique_ptr<TransitionTable> local;
  ValueFunction value;
  backward_sweep(grid_, table_for_sweep(local), lambda, value);
  return value;
}

LambdaRun SectionEngine::run(double lambda, const StartState& start) const {
  return run(lambda, start, options_.resim_step_m);
}

ValueFunction SectionEngine::sweep(const StagePrices& prices) const {
  const ThreadScope threads(options_.threads);
  std::unique_ptr<TransitionTable> local;
  ValueFunction value;
  backward_sweep(grid_, table_for_sweep(local), prices, value);
  return value;
}

LambdaRun SectionEngine::run(double lambda, const StartState& start, double resim_step_m) const {
  return run_from(sweep(lambda), start, resim_step_m);
}

LambdaRun SectionEngine::run(const StagePrices& prices, const StartState& start,
                             double resim_step_m) const {
  return run_from(sweep(prices), start, resim_step_m);
}

LambdaRun SectionEngine::fine_run(const LambdaRun& run) const {
  if (!run.kept) return run;
  return run_program(run.kept->value, run.kept->extracted, run.start, options_.resim_step_m);
}

namespace {

// Positions where a stage-priced value function's price changes.
std::vector<double> price_changes_m(const StageGrid& grid, const ValueFunction& value) {
  std::vector<double> cuts;
  for (std::size_t i = 1; i < value.stage_lambda.size(); ++i) {
    if (value.stage_lambda[i] != value.stage_lambda[i - 1]) {
      cuts.push_back(grid.position(static_cast<int>(i)));
    }
  }
  return cuts;
}

// hold_cruising applied to each stretch between cuts on its own; the same program when no
// stretch has a saw tooth.
physics::ControlProgram hold_cruising_by_stretch(const physics::ControlProgram& program,
                                                 const physics::SimulationResult& sim,
                                                 const std::vector<double>& cuts) {
  if (cuts.empty()) return hold_cruising(program, sim);
  std::vector<double> bounds = {-1.0};
  bounds.insert(bounds.end(), cuts.begin(), cuts.end());
  bounds.push_back(std::numeric_limits<double>::infinity());
  physics::ControlProgram out;
  bool changed = false;
  for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
    const double lo = bounds[b], hi = bounds[b + 1];
    physics::ControlProgram piece;
    for (std::size_t i = 0; i < program.size(); ++i) {
      if (program[i].from_m >= lo && program[i].from_m < hi) piece.push_back(program[i]);
    }
    if (b > 0 && (piece.empty() || piece.front().from_m > lo)) {
      // The control running into the stretch goes on at its start.
      physics::Control running = program.front().control;
      for (const auto& step : program) {
        if (step.from_m <= lo) running = step.control;
      }
      piece.insert(piece.begin(), {lo, running});
    }
    if (piece.empty()) continue;
    physics::ControlProgram held = hold_cruising(piece, sim);
    changed = changed || held.size() < piece.size();
    for (const auto& step : held) {
      if (!out.empty() && out.back().control == step.control) continue;
      out.push_back(step);
    }
  }
  return changed ? out : program;
}

}  // namespace

LambdaRun SectionEngine::run_from(ValueFunction value, const StartState& start,
                                  double resim_step_m) const {
  ExtractionSettings settings;
  settings.start_position_m = start.position_m;
  settings.start_speed_ms = start.speed_ms;
  settings.decision_step_m = options_.decision_step_m;
  settings.dp_step = dp_step();
  physics::ControlProgram extracted =
      extract_program(motion_, grid_, value, options_.objective, settings);
  if (resim_step_m == options_.resim_step_m) {
    return run_program(value, std::move(extracted), start, resim_step_m);
  }
  // A coarse run keeps what its fine run needs (fine_run): the extraction does not depend on
  // the re-simulation step.
  auto kept = std::make_shared<const KeptForFineRun>(KeptForFineRun{std::move(value), extracted});
  LambdaRun out = run_program(kept->value, std::move(extracted), start, resim_step_m);
  out.kept = std::move(kept);
  return out;
}

namespace {

// A run's cost by the objective plus its running time at the value function's time prices
// (each trace step at the price of the stage it starts in): the sum the sweep minimised.
double priced_cost_J(const SectionEngine& engine, const ValueFunction& value,
                     const physics::SimulationResult& sim) {
  const StageGrid& grid = engine.grid();
  double time_cost_J = 0.0;
  if (value.stage_lambda.empty()) {
    time_cost_J = value.lambda * sim.running_time_s;
  } else {
    const auto& trace = sim.trace;
    const int last = std::min(static_cast<int>(value.stage_lambda.size()), grid.stage_count()) - 1;
    int stage = 0;  // the last stage at or before the step's start (the trace runs forwards)
    for (std::size_t k = 1; k < trace.size(); ++k) {
      while (stage < last && grid.position(stage + 1) <= trace[k - 1].s_m + 1e-9) ++stage;
      time_cost_J += value.price(stage) * (trace[k].t_s - trace[k - 1].t_s);
    }
  }
  return engine.energy_cost_J(sim) + time_cost_J;
}

}  // namespace

LambdaRun SectionEngine::run_program(const ValueFunction& value, physics::ControlProgram program,
                                     const StartState& start, double resim_step_m) const {
  LambdaRun out;
  out.lambda = value.lambda;
  out.start = start;
  out.program = std::move(program);
  std::shared_ptr<const physics::SimulationResult> base;
  {
    const std::lock_guard<std::mutex> lock(resume_mutex_);
    base = resume_base_;
  }
  out.sim = base ? resimulate(out.program, start, resim_step_m, *base)
                 : simulate(out.program, start, resim_step_m);
  if (!out.sim.checkpoints.empty()) {
    // Kept up to the end of the second phase, a trade of memory for reach: on the full line (1726
    // s, 30 s dwells) keeping whole runs took 10.47 G instructions and 348 MB, up to the second
    // switch 10.76 G and 329 MB, up to the first 11.04 G and 322 MB (320 MB without keeping any).
    const double kept_to_m =
        out.program.size() > 2 ? out.program[2].from_m : std::numeric_limits<double>::infinity();
    auto kept = std::make_shared<const physics::SimulationResult>(
        physics::resume_prefix(out.sim, kept_to_m));
    const std::lock_guard<std::mutex> lock(resume_mutex_);
    resume_base_ = std::move(kept);
  }
  if (options_.cruise_as_hold) {
    // A stage-priced run cruises at a different speed on each side of a price change, so its
    // cruises are held stretch by stretch.
    physics::ControlProgram held =
        value.stage_lambda.empty()
            ? hold_cruising(out.program, out.sim)
            : hold_cruising_by_stretch(out.program, out.sim, price_changes_m(grid_, value));
    // The grid's run as extracted, priced, where a cruise is held (NAN where none is).
    double grid_priced_J = NAN;
    if (held.size() != out.program.size()) {
      grid_priced_J = priced_cost_J(*this, value, out.sim);
      // The held program equals the extracted one up to its first held cruise: resumed.
      out.sim = resimulate(held, start, resim_step_m, out.sim);
      out.program = std::move(held);
    }
    // A hold that would brake below the limit (a descent) coasts instead. Each trial differs
    // from the run before it only from its new coast on, so it resumes from that run.
    // (The first trial resumes from the run as extracted, unchanged until it returns.)
    const physics::SimulationResult& extracted_sim = out.sim;
    bool first_trial = true;
    physics::SimulationResult last_sim;
    out.program = coast_instead_of_braking_holds(
        out.program, out.sim, envelope_, [&](const physics::ControlProgram& p) {
          physics::SimulationResult sim =
              resimulate(p, start, resim_step_m, first_trial ? extracted_sim : last_sim);
          first_trial = false;
          last_sim = sim;
          return sim;
        });
    // The held run is kept (the cruise polish starts from its holds), and what the grid's own
    // run as extracted saves at the run's time prices is recorded: a run of phases that only
    // looks like a saw tooth (a ride of a limit, a long coast into a lower limit) can be held
    // dearer (CH_Fribourg_Bern, FLIRT, 5 m x 0.1 km/h: 0.6 % at 743 kJ/s), and dp::solve_for_time
    // then searches the grid's own runs too (dp/time_target.hpp).
    if (grid_priced_J > 0.0) {
      const double held_priced_J = priced_cost_J(*this, value, out.sim);
      if (held_priced_J > grid_priced_J) {
        out.held_excess_share = held_priced_J / grid_priced_J - 1.0;
      }
    }
  }
  out.cost_J = energy_cost_J(out.sim);
  return out;
}

physics::SimulationResult SectionEngine::min_time_run(const StartState& start) const {
  if (!(start.position_m == 0.0 && start.speed_ms == 0.0)) {
    return simulate({{start.position_m, physics::Control::MaxTraction}}, start);
  }
  std::call_once(flat_out_once_, [&] {
    flat_out_ = simulate({{start.position_m, physics::Control::MaxTraction}}, start);
  });
  return flat_out_;
}

}  // namespace ecorail::dp
