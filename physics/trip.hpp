// Trip: one train's timed run over a line. A trip is the re-simulated trajectory of every
// section of a run laid end to end on a clock: it departs its first station at a clock time,
// runs each section as re-simulated, dwells at every intermediate stop, and arrives at the last.
// It answers the questions the many-train work asks of a run: where the train is and what it
// does at a clock time (state_at), when it passes a position (time_at), when it arrives at and
// leaves each stop, and how much traction, braking and regenerated power it draws or feeds on any
// uniform time grid (power_bins). Inside a simulation step the applied force is the step's mean
// force and the acceleration is constant (the simulator's own step model), so a bin holds the
// exact integral of that power model over the bin and the bins add up to the trip's energy
// ledger. The trajectory is shared between copies: a trip shifted to another departure time
// (shifted) costs no re-simulation and no copy of the trajectory.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "physics/energy_ledger.hpp"
#include "physics/route.hpp"
#include "physics/simulator.hpp"

namespace ecorail::physics {

// Where the train is and what it does at one instant. Force and regime are those of the
// simulation step holding the instant (traction positive, braking negative).
struct TripState {
  double t_s = 0.0;         // clock time
  double position_m = 0.0;  // from the trip's first station along the run
  double speed_ms = 0.0;
  double accel_m_s2 = 0.0;
  double force_N = 0.0;
  Regime regime = Regime::Coast;
  int section = 0;        // index of the section being run (or just arrived at, when dwelling)
  bool dwelling = false;  // standing at an intermediate stop
  bool before_departure = false;
  bool after_arrival = false;
};

// A stop of the trip: its position along the run and its clock times. The first stop has no
// arrival (arrival = departure), the last no departure (departure = arrival).
struct TripStop {
  std::string station;
  double position_m = 0.0;
  double arrival_s = 0.0;
  double departure_s = 0.0;
  double dwell_s = 0.0;
};

// Power on a uniform time grid: bin k covers [start_s + k step_s, start_s + (k+1) step_s) and
// holds the mean power over the bin (energy in the bin / step), so energy_J(k) = power * step.
struct PowerBins {
  double start_s = 0.0;
  double step_s = 1.0;
  std::vector<double> traction_W;  // traction power at the wheel (u v, u > 0)
  std::vector<double> braking_W;   // braking power at the wheel (-u v, u < 0)
  std::vector<double> regen_W;     // regenerated electrical power (regen efficiency x braking)
};

// One section of a run as re-simulated, with the dwell at its arrival stop (0 for the last).
struct TripSection {
  const Route* route = nullptr;
  const SimulationResult* sim = nullptr;
  double dwell_after_s = 0.0;
};

class Trip {
 public:
  Trip() = default;
  // Lays the sections end to end from the departure clock time. Every section but the first
  // starts at rest at its route's start (the first may start mid-run: a restart);
  // regen_efficiency converts braking into regenerated power. The routes and traces are copied.
  Trip(const std::vector<TripSection>& sections, double departure_s, double regen_efficiency);

  // The same run departing at another clock time: shares the trajectory, costs nothing.
  Trip shifted(double departure_s) const;

  bool empty() const { return data_ == nullptr; }
  double departure_s() const { return offset_s_; }
  double arrival_s() const;
  double length_m() const;
  double running_time_s() const;        // excluding dwells
  std::vector<TripStop> stops() const;  // in this trip's clock times
  TripStop stop(std::size_t k) const;
  std::size_t section_count() const;
  const Route& route(std::size_t section) const;
  double section_start_m(std::size_t section) const;  // position of the section's first stop
  const EnergyLedger& ledger() const;
  double regen_efficiency() const;

  // State at clock time t (before departure: at rest at the first stop; after arrival: at rest
  // at the last stop, each flagged).
  TripState state_at(double t_s) const;
  // First clock time at which the train reaches position s along the run (at a stop: the
  // arrival). Throws std::out_of_range outside [0, length].
  double time_at(double position_m) const;
  // The same time, bit for bit, searching from sample *hint (and leaving there the sample
  // found): cheaper when successive positions lie close together, as along a run.
  double time_at(double position_m, std::size_t* hint) const;
  // Power bins of `count` bins of `step_s` from clock time `start_s`; the trip outside the grid
  // is not counted, so bins covering the whole trip add up to the ledger.
  PowerBins power_bins(double start_s, double step_s, std::size_t count) const;
  // Bins from the departure (rounded down to a multiple of step_s) to past the arrival.
  PowerBins power_bins(double step_s) const;

  // The trajectory as samples on the trip's own time axis (t from 0 at departure): at each
  // sample the state at its end, and the force and regime of the step that ends there.
  struct Sample {
    double t_s = 0.0;
    double s_m = 0.0;  // along the run
    double v_ms = 0.0;
    double accel_m_s2 = 0.0;
    double force_N = 0.0;
    Regime regime = Regime::Coast;
    int section = 0;
    bool dwelling = false;  // the step ending here is a dwell (the train stands)
  };
  const std::vector<Sample>& samples() const;

 private:
  struct Data;
  // time_at between samples index - 1 and index (index: the first sample at or past it).
  double time_between(std::size_t index, double position_m) const;
  std::shared_ptr<const Data> data_;
  double offset_s_ = 0.0;  // clock time of the departure
};

}  // namespace ecorail::physics
