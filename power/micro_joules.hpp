// Energies summed as integers: micro-joules per time bin. Every fleet balance (the power-flow
// balance of energy/ and the DC network's of power/) keeps its bins and totals in this unit, so
// any sequence of incremental moves gives exactly the totals of a fresh evaluation.
#pragma once

#include <cstdint>

namespace ecorail::power {

using MicroJoules = std::int64_t;
inline constexpr double kMicroJoulesPerJoule = 1e6;
inline double to_joules(MicroJoules e) {
  return static_cast<double>(e) / kMicroJoulesPerJoule;
}

}  // namespace ecorail::power
