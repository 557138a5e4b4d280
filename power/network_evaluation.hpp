// The network model's full account of one timetable: every bin of the day solved by the DC load
// flow with the trains on the line (power/load_flow.hpp), and everything the outputs report:
// per substation its energy, peak power and peak current; the line losses; traction input
// (electrical, after the traction efficiency and any curtailment), auxiliaries, regenerated
// energy offered, used (entered the line) and curtailed (burnt on board); traction curtailed at
// the minimum voltage; the lowest and highest train voltage; the number of instants with each
// kind of curtailment or with no solution at full demand; and the worst relative error of the
// energy balance over all instants (substation + used regen = traction + auxiliaries + losses).
// Energies are summed as integer micro-joules per bin, so the totals do not depend on the
// thread count. Also: the substations' power over a window and the load flow at one instant
// (for the plots).
#pragma once

#include <string>
#include <vector>

#include "power/load_flow.hpp"
#include "power/network_profile.hpp"

namespace ecorail::power {

// What the network model needs besides the departures.
struct NetworkSetup {
  const NetworkProfile* profile = nullptr;
  const PowerSupply* supply = nullptr;
  double traction_efficiency = 1.0;
  double horizon_s = 0.0;  // no train runs past it
  int threads = 0;         // 0: OpenMP's default
};

struct SubstationEnergy {
  std::string name;
  double position_m = 0.0;
  double energy_J = 0.0;        // at the terminals (negative: a reversible one took energy back)
  double peak_power_W = 0.0;    // largest output
  double peak_current_A = 0.0;  // largest output current
};

struct NetworkEvaluation {
  double time_step_s = 0.0;
  std::vector<SubstationEnergy> substations;
  double substation_J = 0.0;
  double line_losses_J = 0.0;
  double traction_wheel_J = 0.0;  // at the wheel, as the trips ran
  double traction_input_J = 0.0;  // electrical, delivered (after curtailment)
  double auxiliary_J = 0.0;
  double regen_J = 0.0;               // offered by braking trains
  double used_regen_J = 0.0;          // entered the line
  double curtailed_regen_J = 0.0;     // burnt on board
  double curtailed_traction_J = 0.0;  // not delivered below the minimum voltage
  double min_train_voltage_V = 0.0;
  double max_train_voltage_V = 0.0;
  long instants = 0;
  long regen_curtailed_instants = 0;
  long traction_curtailed_instants = 0;
  long no_solution_instants = 0;  // no operating point at full demand (curtailed to one)
  long unsolved_instants = 0;     // load flow not CONVERGENCE: the evaluation is not usable
  double max_balance_error_fraction = 0.0;         // worst |residual| / (traction + aux + regen)
  std::vector<double> train_curtailed_regen_J;     // per train
  std::vector<double> train_curtailed_traction_J;  // per train
};

// regeneration = false: every train burns its regenerated power (the baseline without reuse).
NetworkEvaluation evaluate_network(const NetworkSetup& setup, const std::vector<int>& departures_s,
                                   bool regeneration = true);

// Power of every substation at every bin of [from_s, to_s) (W).
struct SubstationTrace {
  double start_s = 0.0, step_s = 0.0;
  std::vector<std::string> names;
  std::vector<std::vector<double>> power_W;  // [substation][bin]
};
SubstationTrace substation_trace(const NetworkSetup& setup, const std::vector<int>& departures_s,
                                 double from_s, double to_s);

// The load flow at clock time t_s (the bin holding it), with its nodes along the line; trains
// receives the train number of each load.
LoadFlowResult load_flow_at(const NetworkSetup& setup, const std::vector<int>& departures_s,
                            double t_s, std::vector<int>* trains);

}  // namespace ecorail::power
