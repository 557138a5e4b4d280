// JSON views of fitting results, as written by `ecorail calibrate --json` and
// `ecorail fit-envelope --json` (keys documented in docs/calibration.md). Standard errors of
// fixed parameters are null.
#pragma once

#include <nlohmann/json.hpp>

#include "fitting/calibration.hpp"
#include "fitting/envelope_fit.hpp"

namespace ecorail::fitting {

nlohmann::json calibration_to_json(const Summary& summary);
nlohmann::json envelope_fit_to_json(const EnvelopeFitResult& result, EnvelopeKind kind,
                                    EnvelopeForm written);

}  // namespace ecorail::fitting
