// Can these logs tell the free parameters apart? Checked before any fit, so a log that cannot
// identify them is an InputError naming the parameters rather than a fit that quietly returns
// its starting values. Two tests: enough used intervals for the number of free parameters, and
// the rank of the equation-error Jacobian at the starting values (columns scaled to unit
// length): a direction the data cannot see (singular value below 1e-7 of the largest) names the
// parameters that move along it, with the reason when it is a known one (no rows of known
// force, so the mass factor trades against the resistance scale; no gradient; a narrow speed
// range; mass against traction scale without braking forces).
#pragma once

#include <string>
#include <vector>

#include "fitting/log_prep.hpp"
#include "fitting/motion_model.hpp"
#include "fitting/parameters.hpp"

namespace ecorail::fitting {

struct IdentifiabilityOptions {
  int min_intervals = 20;
  int min_intervals_per_parameter = 5;
  double rank_tolerance = 1e-7;
};

// Throws data::InputError naming the logs and the parameters that cannot be identified.
void check_identifiable(const PreparedData& data, const ModelConstants& constants,
                        const ParamVector& start, const ParamFlags& fixed,
                        const IdentifiabilityOptions& options);

}  // namespace ecorail::fitting
