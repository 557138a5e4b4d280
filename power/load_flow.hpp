// LoadFlow: the DC load flow of a line at one instant. Nodes are the substations and the trains
// on the line, sorted by position; nodes with no resistance between them (the same position, or
// a zero-resistance stretch) form one bus at one voltage. A bus of trains draws a constant power
// P = traction input + auxiliaries - regenerated power (negative: it feeds the line), so its
// current is P / V; a substation is its no-load voltage behind its internal resistance, through
// a diode unless reversible (a unidirectional rectifier never takes current back); branches
// between buses are the loop (conductor + return) resistance between them. The nodal equations
// (Kirchhoff's current law at every bus) are solved by Newton's method on the chain: each linear
// solve is tridiagonal, O(n), and the diode terms enter as a semismooth max(0, U0 - V). Voltage
// limits are an active set around Newton: a bus of braking trains whose voltage would exceed the
// trains' maximum is held at the maximum and its regeneration curtailed by what the line cannot
// take (burnt on board), a bus of accelerating trains below the minimum is held at the minimum
// and its traction curtailed; a hold is released when the curtailment it needs turns negative.
// When Newton finds no solution at full demand (no operating point), the bus the diverging
// iterate points to is curtailed and the solve repeated, and the summary says so: the result
// is never a silent wrong answer. docs/power_network.md has the equations and a worked example.
#pragma once

#include <string>
#include <vector>

#include "dp/termination.hpp"
#include "power/power_supply.hpp"

namespace ecorail::power {

using dp::Termination;

// One train at the instant. Powers are electrical, at the pantograph.
struct TrainLoad {
  double position_m = 0.0;
  double traction_W = 0.0;   // traction input (wheel power / traction efficiency); curtailable
  double auxiliary_W = 0.0;  // never curtailed
  double regen_W = 0.0;      // regenerated power offered; curtailable
};

struct LoadFlowOptions {
  double voltage_tolerance_V = 1e-9;  // Newton stops when no bus voltage moves more
  int max_newton_iterations = 60;
  int max_active_set_iterations = 100;
  bool IsValid(std::string* error) const;
};

struct LoadFlowSummary {
  Termination termination = Termination::FAILURE;
  int newton_iterations = 0;      // over every active-set pass
  int active_set_iterations = 0;  // Newton solves
  int regen_curtailed_buses = 0;
  int traction_curtailed_buses = 0;
  bool no_solution_at_full_demand = false;  // Newton diverged before a curtailment was imposed
  bool voltage_limit_violated = false;  // a train outside its limits with nothing left to curtail
  std::string message;
  bool IsSolutionUsable() const { return is_usable(termination); }
  std::string BriefReport() const;
  std::string FullReport() const;
};

// A node of the solved line, for plots of the voltage along it.
struct LoadFlowNode {
  double position_m = 0.0;
  double voltage_V = 0.0;
  int substation = -1;  // index in the supply, or -1
  int train = -1;       // index in the loads, or -1
};

struct LoadFlowResult {
  LoadFlowSummary summary;
  std::vector<double> substation_power_W;    // at the terminals (negative: reversible, taking)
  std::vector<double> substation_current_A;  // out of the substation
  std::vector<double> substation_voltage_V;  // at the terminals
  std::vector<double> train_voltage_V;       // per load, in the loads' order
  std::vector<double> train_curtailed_regen_W;
  std::vector<double> train_curtailed_traction_W;
  std::vector<LoadFlowNode> nodes;  // by position; filled when asked for
  double substation_W = 0.0;        // sum over substations
  double line_losses_W = 0.0;       // in the conductor and return between buses
  double traction_W = 0.0;          // delivered traction input (after curtailment)
  double auxiliary_W = 0.0;
  double regen_W = 0.0;            // offered by braking trains
  double used_regen_W = 0.0;       // regen_W - curtailed_regen_W: what entered the line
  double curtailed_regen_W = 0.0;  // burnt on board
  double curtailed_traction_W = 0.0;
  double min_train_voltage_V = 0.0;  // 0 when no train
  double max_train_voltage_V = 0.0;
  // substation + used regen - traction - auxiliaries - line losses: zero up to rounding.
  double balance_residual_W() const {
    return substation_W + used_regen_W - traction_W - auxiliary_W - line_losses_W;
  }
};

class LoadFlow {
 public:
  explicit LoadFlow(const PowerSupply& supply, const LoadFlowOptions& options = {});

  const PowerSupply& supply() const { return supply_; }
  // Solves the instant with `count` trains (any order). Keeps a workspace: use one LoadFlow per
  // thread. with_nodes fills result->nodes.
  void solve(const TrainLoad* trains, int count, LoadFlowResult* result, bool with_nodes = false);

 private:
  enum class Mode { Free, HoldHigh, HoldLow, NoRegen, NoTraction };
  struct Bus {
    double r_ohm = 0.0;                  // loop resistance from position 0 (the bus's coordinate)
    int sub_begin = 0, sub_end = 0;      // substations in the bus
    int train_begin = 0, train_end = 0;  // into order_
    double traction_W = 0.0, auxiliary_W = 0.0, regen_W = 0.0;
    Mode mode = Mode::Free;
    bool released = false;  // a hold was released: Newton no longer imposes one on its own
    double voltage_V = 0.0;
  };
  double bus_power_W(const Bus& b) const;  // the demand of a bus not held
  double bus_net_current_A(int i) const;   // out of bus i into branches and substations
  double substation_current_A(int s, double voltage_V) const;
  double residual_A(int i) const;  // KCL at a bus not held
  bool newton(int* iterations);

  PowerSupply supply_;
  LoadFlowOptions options_;
  std::vector<double> sub_r_ohm_, sub_g_S_;
  // Workspace.
  std::vector<int> order_;
  std::vector<char> conducting_;  // per substation: the diode's state in the active set
  bool semismooth_ = true;        // the strategy of the current attempt
  std::vector<Bus> buses_;
  std::vector<double> g_;  // branch conductance between bus i and i+1
  std::vector<double> f_, diag_, lower_, upper_, step_, trial_, cprime_;
};

}  // namespace ecorail::power
