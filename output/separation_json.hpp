// The "separation" block of the timetable's energy JSON (docs/fleet.md): what the service
// simulated with safe separation found (service/service_simulator.hpp): the least speed and
// distance margins, where the cap binds at the planned timetable, each follower event and the
// service's traction work. It formats what the service room computed.
#pragma once

#include <nlohmann/json.hpp>

#include "service/service_simulator.hpp"

namespace ecorail::output {

nlohmann::json separation_json(const service::ServiceResult& result,
                               const service::ServiceOptions& options);

}  // namespace ecorail::output
