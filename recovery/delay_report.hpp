// What `ecorail delay` writes (docs/delays.md): the recovery as JSON (the keys the docs list) and
// its recovery sections as CSV, from a DelayRecoveryResult. The library fills them so that any
// front end (the command, the Python bindings) writes the same layout.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "recovery/delay_recovery.hpp"

namespace ecorail::recovery {

// train_number: the late train, 1-based; plan_name: "reference" or the plan file.
nlohmann::json delay_report_json(const DelayRecoveryResult& r, const Plan& plan, int train_number,
                                 const std::string& plan_name);
// One row per recovery section, the columns of the JSON's "sections".
void write_delay_sections_csv(std::ostream& out, const DelayRecoveryResult& r);

}  // namespace ecorail::recovery
