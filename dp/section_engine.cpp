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

physics::SimulationResult SectionEngine::simulate(const physics::ControlProgram& program) const {
  physics::SimulationOptions opt;
  opt.step_m = options_.resim_step_m;
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

LambdaRun SectionEngine::run(double lambda) const {
  const ValueFunction value = sweep(lambda);
  ExtractionSettings settings;
  settings.decision_step_m = options_.decision_step_m;
  settings.dp_step = dp_step();
  LambdaRun out;
  out.lambda = lambda;
  out.program = extract_program(motion_, grid_, value, options_.objective, settings);
  out.sim = simulate(out.program);
  out.cost_J = energy_cost_J(out.sim);
  return out;
}

physics::SimulationResult SectionEngine::min_time_run() const {
  return simulate({{0.0, physics::Control::MaxTraction}});
}

}  // namespace ecorail::dp
