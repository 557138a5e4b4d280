// Line as one TOML file: parsed, validated, routes between its first stations built.
#include <algorithm>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const physics::Train train = data::default_train();
  fuzz::refuse_cleanly([&] {
    const data::Line line = data::line_from_toml_text(fuzz::as_text(data, size), "line.toml");
    const std::size_t n = std::min<std::size_t>(line.stations.size(), 4);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      data::build_route(line, line.stations[i].name, line.stations[i + 1].name, train);
    }
  });
  return 0;
}
