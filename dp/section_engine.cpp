#include "dp/section_engine.hpp"

namespace ecorail::dp {

SectionEngine::SectionEngine(const physics::Train& train, const physics::Route& route,
                             const EngineOptions& options)
    : train_(train),
      route_(route),
      options_(options),
      envelope_(train_, route_, options.envelope_resolution_m),
      motion_(train_, route_, envelope_),
      grid_(envelope_, route_.length_m(), options.grid) {
  table_ = std::make_unique<TransitionTable>(motion_, grid_, options_.objective, dp_step());
}

physics::SimulationResult SectionEngine::simulate(const physics::ControlProgram& program,
                                                  const StartState& start) const {
  physics::SimulationOptions opt;
  opt.step_m = options_.resim_step_m;
  opt.start_position_m = start.position_m;
  opt.start_speed_ms = start.speed_ms;
  return physics::simulate(motion_, program, opt);
}

double SectionEngine::energy_cost_J(const physics::SimulationResult& sim) const {
  return dp::energy_cost_J(options_.objective, train_, sim.energy.traction_work_J,
                           sim.energy.brake_work_J);
}

ValueFunction SectionEngine::sweep(double lambda) const {
  ValueFunction value;
  backward_sweep(grid_, *table_, lambda, value);
  return value;
}

LambdaRun SectionEngine::run(double lambda, const StartState& start) const {
  const ValueFunction value = sweep(lambda);
  ExtractionSettings settings;
  settings.start_position_m = start.position_m;
  settings.start_speed_ms = start.speed_ms;
  settings.decision_step_m = options_.decision_step_m;
  settings.dp_step = dp_step();
  LambdaRun out;
  out.lambda = lambda;
  out.start = start;
  out.program = extract_program(motion_, grid_, value, options_.objective, settings);
  out.sim = simulate(out.program, start);
  out.cost_J = energy_cost_J(out.sim);
  return out;
}

physics::SimulationResult SectionEngine::min_time_run(const StartState& start) const {
  return simulate({{start.position_m, physics::Control::MaxTraction}}, start);
}

}  // namespace ecorail::dp
