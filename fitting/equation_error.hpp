// Equation-error formulation: for every used interval between two rows, the measured mean
// acceleration (v1 - v0) / dt against the model's acceleration averaged over the two rows
// (trapezoid rule), one residual per interval. Fast and linear in the Davis coefficients; it
// reads the noise of two speeds into each residual, so its standard errors are conservative for
// the slowly varying regressors. A corrupted row shows as two large residuals of opposite sign
// on its two intervals: the rows reported as discounted are chosen greedily as the fewest rows
// whose correction explains the discounted intervals, which names the row, not its neighbours.
#pragma once

#include <memory>

#include "fitting/formulation.hpp"

namespace ecorail::fitting {

std::unique_ptr<Formulation> make_equation_error(const PreparedData& data,
                                                 const ModelConstants& constants);

// Residual of one interval (measured minus modelled mean acceleration, m/s^2) at params; also the
// Jacobian row (d residual / d param) when jacobian is not null. Used by the identifiability
// check, which needs the equation-error Jacobian before any fit.
double equation_error_residual(const PreparedRow& a, const PreparedRow& b,
                               const ModelConstants& constants, const ParamVector& params,
                               double* jacobian);

}  // namespace ecorail::fitting
