// Example 02: a journey over two sections with a dwell, the time split between them optimally.
// Solves A6 -> A8 in 220 s of running time with 45 s at A7, once with the optimal split (one
// time price for both sections) and once with the split proportional to distance, and prints
// what the optimal split saves. Exits non-zero if the optimal split costs more.
#include <cstdio>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "physics/units.hpp"

int main() {
  using namespace ecorail;
  const physics::Train train = data::default_train();
  const data::Line line = data::default_line();
  const std::vector<physics::Route> routes = {data::build_route(line, "A6", "A7", train),
                                              data::build_route(line, "A7", "A8", train)};
  dp::JourneyOptions options;
  options.measure_marginals = false;
  const auto optimal = dp::solve_journey(train, routes, {45.0}, 220.0, options);
  options.split = dp::Split::Proportional;
  const auto proportional = dp::solve_journey(train, routes, {45.0}, 220.0, options);

  for (const auto* sol : {&optimal, &proportional}) {
    std::printf("%-12s", sol == &optimal ? "optimal" : "proportional");
    for (const auto& s : sol->sections) {
      std::printf("  %7.2f s %9.1f kJ", s.run.sim.running_time_s,
                  units::J_to_kJ(s.run.sim.energy.traction_work_J));
    }
    std::printf("  total %9.1f kJ\n", units::J_to_kJ(sol->traction_work_J));
  }
  std::printf("the optimal split saves %.1f kJ\n",
              units::J_to_kJ(proportional.traction_work_J - optimal.traction_work_J));
  return optimal.traction_work_J <= proportional.traction_work_J ? 0 : 1;
}
