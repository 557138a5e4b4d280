// PowerSupply: the DC traction power supply of a line, as the load-flow solver (load_flow.hpp)
// needs it. Substations (rectifiers) sit at positions along the run, each a no-load voltage
// behind an internal resistance; a rectifier is unidirectional by default (a diode: it never
// takes current back) or reversible. The conductor (contact or third rail) and the return
// (running rails) have a resistance per km that may change along the line, given as segments
// from a position on. Every train on the line obeys the same limits: above max_train_voltage_V
// it curtails its regeneration (burns the rest in its braking resistors), below
// min_train_voltage_V it curtails its traction power, and it draws a constant auxiliary power
// (heating, air conditioning, compressors) the whole time it is on the line, dwells included.
// Positions are metres along the run from its first station, the coordinate of the trip.
#pragma once

#include <string>
#include <vector>

namespace ecorail::power {

struct Substation {
  std::string name;
  double position_m = 0.0;
  double no_load_voltage_V = 0.0;
  double internal_resistance_ohm = 0.0;  // > 0: the rectifier's regulation
  bool reversible = false;               // an inverter can take regenerated power back
};

// Resistances from from_m on (to the next segment's from_m, the last to the end of the line).
struct ConductorSegment {
  double from_m = 0.0;
  double conductor_ohm_per_km = 0.0;  // contact or third rail
  double return_ohm_per_km = 0.0;     // running rails
};

struct PowerSupply {
  std::string name;
  std::vector<Substation> substations;       // by increasing position
  std::vector<ConductorSegment> conductors;  // the first from 0, by increasing from_m
  double max_train_voltage_V = 0.0;          // regeneration curtailed above
  double min_train_voltage_V = 0.0;          // traction curtailed below
  double auxiliary_power_W = 0.0;            // per train on the line

  // One sentence naming the field and what was expected.
  bool IsValid(std::string* error) const;
  // Loop resistance (conductor + return) from position 0 to position_m (ohm); positions below
  // 0 extend the first segment. The resistance between two points is the difference, exactly 0
  // between equal positions or across zero-resistance segments.
  double loop_resistance_to_ohm(double position_m) const;
};

}  // namespace ecorail::power
