// The service of a timetable whose trains all run one pattern (`ecorail timetable ...
// --separation`, ecorail.timetable.Fleet.separation): the plan is each section's energy-optimal
// control for the pattern's running time (the section library's solve), simulated; and the
// names of the follower modes as the program's --follower flag and the JSON spell them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dp/section_library.hpp"
#include "service/service_simulator.hpp"

namespace ecorail::service {

// "supervise", "reoptimise", "wait".
const char* follower_mode_name(FollowerMode mode);
std::optional<FollowerMode> follower_mode_from_name(const std::string& name);

// The plan of the pattern: running_times_s per section, dwells_s per intermediate stop.
ServicePlan plan_from_running_times(const dp::SectionLibrary& library,
                                    const std::vector<double>& running_times_s,
                                    std::vector<double> dwells_s);

}  // namespace ecorail::service
