// Provenance of a result: which program (version, commit, build type), which line and train
// (names and content checksums, so two runs on the same name but different data are told
// apart), which grid and which options produced it. Every JSON report carries it under the key
// "provenance"; a frontier read back from the cache says so with "from_cache".
#pragma once

#include <nlohmann/json.hpp>

#include "data/line.hpp"
#include "physics/train.hpp"

namespace ecorail::output {

// {"program": {"name", "version", "commit", "build_type"}}: the same figures as
// `ecorail --version` (data/version.hpp).
nlohmann::json program_json();
// Checksums are written as 16 hex digits (JSON numbers cannot hold 64 bits exactly).
nlohmann::json provenance_json(const data::Line& line, const physics::Train& train,
                               const nlohmann::json& grid, const nlohmann::json& options);

}  // namespace ecorail::output
