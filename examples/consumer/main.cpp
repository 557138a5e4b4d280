// The smallest program on the installed ecorail library: the flat-out run of A6 -> A7 on the
// embedded reference line. Prints its running time; exits non-zero if the run does not come to
// rest at A7.
#include <cmath>
#include <cstdio>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_engine.hpp"

int main() {
  using namespace ecorail;
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
  dp::EngineOptions options;
  options.grid.ds_m = 50.0;  // coarse: only the flat-out run is used
  options.grid.dv_kmh = 2.0;
  const dp::SectionEngine engine(train, route, options);
  const physics::SimulationResult run = engine.min_time_run();
  std::printf("A6 -> A7 flat out: %.3f s, stop error %.3f m\n", run.running_time_s,
              run.stop_error_m);
  return run.stopped_early || std::abs(run.stop_error_m) > 0.5 ? 1 : 0;
}
