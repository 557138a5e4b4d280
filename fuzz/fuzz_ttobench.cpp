// TTOBench JSON (tracks and trains): the first byte picks track or train; the rest is the file.
// A track that loads has its first routes built for the reference train.
#include <algorithm>
#include <string>

#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data/ttobench_io.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const physics::Train reference = data::default_train();
  const std::string text(fuzz::as_text(data + 1, size - 1));
  fuzz::refuse_cleanly([&] {
    if (data[0] % 2 == 0) {
      const data::Line line = data::line_from_ttobench(text, "track.json");
      const std::size_t n = std::min<std::size_t>(line.stations.size(), 3);
      for (std::size_t i = 0; i + 1 < n; ++i) {
        data::build_route(line, line.stations[i].name, line.stations[i + 1].name, reference);
      }
    } else {
      data::train_from_ttobench(text, "train.json");
    }
  });
  return 0;
}
