// EnergyLedger: the energy account of a run. Traction work is the work of the traction force at
// the wheel (what model.md calls traction energy); braking work is the work of the braking
// force; regenerated energy is the regenerative part of the braking work (all of it unless
// the train has a pneumatic brake) times the regeneration efficiency; traction
// input is the traction work divided by the traction efficiency (energy drawn from the line).
#pragma once

namespace ecorail::physics {

struct EnergyLedger {
  double traction_work_J = 0.0;
  double brake_work_J = 0.0;
  double regen_J = 0.0;
  double traction_input_J = 0.0;

  void add(double traction_work_J_, double brake_work_J_, double traction_efficiency,
           double regen_efficiency) {
    add(traction_work_J_, brake_work_J_, brake_work_J_, traction_efficiency, regen_efficiency);
  }
  // The same when only regen_brake_work_J of the braking work is regenerative (a train with a
  // pneumatic brake).
  void add(double traction_work_J_, double brake_work_J_, double regen_brake_work_J,
           double traction_efficiency, double regen_efficiency) {
    traction_work_J += traction_work_J_;
    brake_work_J += brake_work_J_;
    regen_J += regen_efficiency * regen_brake_work_J;
    traction_input_J += traction_work_J_ / traction_efficiency;
  }
  // The same with the energy drawn and fed back measured by the step (efficiency maps).
  void add_measured(double traction_work_J_, double brake_work_J_, double traction_input_J_,
                    double regen_J_) {
    traction_work_J += traction_work_J_;
    brake_work_J += brake_work_J_;
    regen_J += regen_J_;
    traction_input_J += traction_input_J_;
  }
  // Energy drawn from the supply less the energy fed back.
  double net_J() const { return traction_input_J - regen_J; }
};

}  // namespace ecorail::physics
