#include "service/pattern_service.hpp"

namespace ecorail::service {

const char* follower_mode_name(FollowerMode mode) {
  switch (mode) {
    case FollowerMode::Supervised:
      return "supervise";
    case FollowerMode::Reoptimised:
      return "reoptimise";
    case FollowerMode::Wait:
      return "wait";
  }
  return "reoptimise";
}

std::optional<FollowerMode> follower_mode_from_name(const std::string& name) {
  for (FollowerMode m : {FollowerMode::Supervised, FollowerMode::Reoptimised, FollowerMode::Wait})
    if (name == follower_mode_name(m)) return m;
  return std::nullopt;
}

ServicePlan plan_from_running_times(const dp::SectionLibrary& library,
                                    const std::vector<double>& running_times_s,
                                    std::vector<double> dwells_s) {
  std::vector<physics::ControlProgram> programs;
  for (std::size_t i = 0; i < library.size(); ++i)
    programs.push_back(library.solve(i, running_times_s.at(i)).search.run.program);
  return plan_from_programs(library, std::move(programs), std::move(dwells_s));
}

}  // namespace ecorail::service
