// The parameters calibration can estimate, in the units of docs/model.md: Davis coefficients A,
// B, C (N/kN with v in km/h), the rotating-mass factor, a scale on the gradient term (1 = the log
// feels the gradient it records), the mass (t) and a scale on the logged traction force. One
// fixed order indexes every parameter vector and covariance matrix of the fitting room; names are
// the JSON keys of `ecorail calibrate --json` and the words of `--fix`.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "physics/train.hpp"

namespace ecorail::fitting {

enum Param : int {
  kDavisA = 0,
  kDavisB,
  kDavisC,
  kRotatingMassFactor,
  kGradientScale,
  kMassT,
  kTractionScale,
  kParamCount
};

using ParamVector = std::array<double, kParamCount>;
using ParamFlags = std::array<bool, kParamCount>;
using ParamCovariance = std::array<double, kParamCount * kParamCount>;  // row-major

std::string_view param_name(int p);  // "davis_A", ...
std::string_view param_unit(int p);  // "N/kN", "N/kN/(km/h)", ...
std::optional<int> param_from_name(std::string_view name);
// "davis_A, rotating_mass_factor" for the set flags.
std::string param_list(const ParamFlags& which);

// Starting values from a train: its Davis coefficients, mass factor and mass, gradient scale 1,
// traction scale 1.
ParamVector params_from_train(const physics::Train& train);
// Default bounds: physical ranges wide enough never to bind on a sane train.
ParamVector default_lower_bounds(const physics::Train& base);
ParamVector default_upper_bounds(const physics::Train& base);

}  // namespace ecorail::fitting
