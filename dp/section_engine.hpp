// SectionEngine: the single-section optimal-control engine. Construction builds the speed
// envelope, the grid and the lambda-independent transition table (the expensive, parallel
// part) once; run(lambda) then does one backward sweep, extracts the control program and
// re-simulates it at a fine step, returning the measured run. Journeys, frontiers and the
// lambda search for a running time are all built on run(lambda). The engine owns copies of
// the train and route, so it is self-contained.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "dp/backward_sweep.hpp"
#include "dp/objective.hpp"
#include "dp/policy_extraction.hpp"
#include "dp/stage_grid.hpp"
#include "dp/stage_prices.hpp"
#include "dp/transition_table.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp {

struct EngineOptions {
  GridSpec grid;
  Objective objective = Objective::Traction;
  double resim_step_m = 0.05;  // fine step of the forward re-simulation (RK4)
  double envelope_resolution_m = 0.1;
  double decision_step_m = 1.0;  // policy extraction
  // OpenMP threads for this engine's parallel parts (0: OpenMP's default). Results do not
  // depend on it (tested); see dp/threads.hpp.
  int threads = 0;
  // Cruising as a speed hold: a saw tooth of traction and coasting in the extracted program is
  // replaced by a hold at its mean speed (dp::hold_cruising) before the re-simulation.
  bool cruise_as_hold = true;
  // Transition table kept for the engine's life (the default), or built for each sweep and
  // freed after it: a line whose tables do not fit in memory together (dp::SectionLibrary
  // decides) then holds at most one table per sweep running. Results are bit for bit the
  // same; each sweep pays for its table.
  bool keep_transitions = true;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// Where a run starts: at rest at the departure stop, or mid-run (a restart) at a position and
// speed of the section.
struct StartState {
  double position_m = 0.0;
  double speed_ms = 0.0;
  bool at_departure() const { return position_m <= 0.0 && speed_ms <= 0.0; }
};

// The value function of a coarse run and the program extracted from it (before the cruise is
// held and braking holds coast, which depend on the re-simulation).
struct KeptForFineRun {
  ValueFunction value;
  physics::ControlProgram extracted;
};

struct LambdaRun {
  double lambda = 0.0;
  StartState start;
  physics::ControlProgram program;
  physics::SimulationResult sim;
  double cost_J = 0.0;  // energy cost by the objective, from the re-simulation
  // For a run re-simulated at a step other than the engine's fine one (a search's cheap
  // evaluation): what its fine run (SectionEngine::fine_run) needs besides, so that it costs no
  // second sweep or extraction. Empty for a fine run.
  std::shared_ptr<const KeptForFineRun> kept;
  // Where a cruise was held (EngineOptions::cruise_as_hold): how much dearer the held run is
  // than the grid's run as extracted, at this run's time prices (cost plus price times time),
  // as a share of the grid's; 0 when the held run is no dearer or nothing was held.
  double held_excess_share = 0.0;
};

class SectionEngine {
 public:
  SectionEngine(const physics::Train& train, const physics::Route& route,
                const EngineOptions& options);
  // The same over route with the speed envelope of envelope_route, a route that begins as route
  // does and runs on past its end: the envelope then does not brake to rest at route's end, and
  // a run may end moving (a journey's last timing point with a speed above 0; the last stage's
  // speeds are chosen by StagePrices::end_moving). With envelope_route == route, the engine is
  // the one above.
  SectionEngine(const physics::Train& train, const physics::Route& route,
                const EngineOptions& options, const physics::Route& envelope_route);
  // An engine over `route` that uses `twin`'s transition table instead of building its own:
  // route's track must equal twin's (physics::track_key), train and options too, so the table
  // would be built bit for bit the same. Many stops over identical track (a TTOBench track of
  // 20 003 stops 10 m apart) then build one table. Builds its own when twin holds none.
  SectionEngine(const physics::Route& route, const SectionEngine& twin);
  // The engine twin is, with its cruises left as the grid has them (options().cruise_as_hold
  // false) and its transition table shared: a cruise is held after the sweep, so the table is
  // the same. dp::solve_for_time searches on it where the held runs cost more than the grid's.
  struct GridCruises {};
  SectionEngine(const SectionEngine& twin, GridCruises);
  SectionEngine(const SectionEngine&) = delete;
  SectionEngine& operator=(const SectionEngine&) = delete;

  LambdaRun run(double lambda, const StartState& start = {}) const;
  // The same run re-simulated at resim_step_m instead of options().resim_step_m: a search's
  // cheap evaluation (RK4 at 0.5 m puts the running time within about a millisecond of the fine
  // run's); the result a user is given is always run(lambda) at the fine step.
  LambdaRun run(double lambda, const StartState& start, double resim_step_m) const;
  // The run for a price per stage and speed bands (dp/stage_prices.hpp): a journey's timing
  // points. Its lambda is the last stage's price.
  LambdaRun run(const StagePrices& prices, const StartState& start, double resim_step_m) const;
  // The run of `run`'s price (or stage prices) at the engine's fine step: bit for bit
  // run(run.lambda, run.start) (or the stage-priced run), without the sweep when `run` kept its
  // value function (a coarse run); `run` itself when it is already fine.
  LambdaRun fine_run(const LambdaRun& run) const;
  // A fresh backward sweep for lambda (cost-to-go and optimal control on the grid), e.g. for
  // policy tables.
  ValueFunction sweep(double lambda) const;
  ValueFunction sweep(const StagePrices& prices) const;
  // The table (built and kept on first use when the engine does not keep its tables).
  const TransitionTable& transitions() const;
  // Whether the engine holds a transition table now (not while it streams its tables).
  bool holds_transitions() const { return table_ != nullptr; }
  const physics::SpeedEnvelope& envelope() const { return envelope_; }
  // The integration settings of the DP transitions (to score controls consistently).
  physics::StepSettings dp_step() const { return {options_.grid.substep_m, 2}; }
  // Flat-out run: full traction, held on the envelope, braking for the stop. From the
  // departure it is simulated once per engine and kept (thread-safe).
  physics::SimulationResult min_time_run(const StartState& start = {}) const;
  physics::SimulationResult simulate(const physics::ControlProgram& program,
                                     const StartState& start = {}) const;
  physics::SimulationResult simulate(const physics::ControlProgram& program,
                                     const StartState& start, double step_m) const;
  // The run of `program` at the engine's re-simulation step, resumed from `earlier`, a run of
  // another program from the same start at the same step: bit for bit simulate(program,
  // start), without re-integrating the steps before the programs' first difference (see
  // physics::simulate with an earlier run; a full run when there is nothing to reuse).
  physics::SimulationResult resimulate(const physics::ControlProgram& program,
                                       const StartState& start,
                                       const physics::SimulationResult& earlier) const;
  // The same at another step (a full run unless `earlier` was made at that step).
  physics::SimulationResult resimulate(const physics::ControlProgram& program,
                                       const StartState& start, double step_m,
                                       const physics::SimulationResult& earlier) const;
  double energy_cost_J(const physics::SimulationResult& sim) const;

  const physics::Train& train() const { return train_; }
  const physics::Route& route() const { return route_; }
  const physics::Motion& motion() const { return motion_; }
  const StageGrid& grid() const { return grid_; }
  const EngineOptions& options() const { return options_; }
  // The re-simulation step of a search that asks for step_m: step_m where it is coarser than
  // the engine's fine step (a search's cheap evaluations), the fine step otherwise (0: fine).
  double search_step_m(double step_m) const {
    return step_m > options_.resim_step_m ? step_m : options_.resim_step_m;
  }
  // Whether a search asking for step_m runs coarse evaluations at all.
  bool searches_coarse(double step_m) const { return step_m > options_.resim_step_m; }

 private:
  // Extraction and re-simulation of the program a value function implies.
  LambdaRun run_from(ValueFunction value, const StartState& start, double resim_step_m) const;
  // The re-simulation of an extracted program (and its held cruise and coasting holds).
  LambdaRun run_program(const ValueFunction& value, physics::ControlProgram program,
                        const StartState& start, double resim_step_m) const;

  physics::Train train_;
  physics::Route route_;
  // Whether the speed envelope is route_'s own (not a longer envelope route's): only then can
  // another engine over an equal track share this one's table.
  bool own_envelope_ = true;
  EngineOptions options_;
  physics::SpeedEnvelope envelope_;
  physics::Motion motion_;
  StageGrid grid_;
  // The table a sweep uses: the kept one, or one built into local for this sweep only.
  const TransitionTable& table_for_sweep(std::unique_ptr<TransitionTable>& local) const;
  std::unique_ptr<TransitionTable> build_table() const;

  mutable std::shared_ptr<const TransitionTable> table_;
  mutable std::once_flag table_once_;
  mutable std::once_flag flat_out_once_;
  mutable physics::SimulationResult flat_out_;
  // The last extracted program's run (run_from), up to its second switch
  // (physics::resume_prefix): the next one resumes from it up to where the two programs first
  // differ (close prices extract programs that agree over a prefix, at least the start of the
  // traction phase). The result does not depend on which run it resumes from.
  mutable std::mutex resume_mutex_;
  mutable std::shared_ptr<const physics::SimulationResult> resume_base_;
};

}  // namespace ecorail::dp
