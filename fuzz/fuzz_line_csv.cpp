// Line as four CSV tables: the first byte picks the table the input replaces (stations,
// gradients, speed limits, curves), the others come from the reference line; the line is
// validated and the routes between its first stations are built for the reference train.
#include <algorithm>
#include <string>

#include "data/csv_reader.hpp"
#include "data/embedded.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kNames[] = {"stations.csv", "gradients.csv", "speed_limits.csv",
                                       "curves.csv"};
  static const physics::Train train = data::default_train();
  const int which = data[0] % 4;
  const std::string_view text = fuzz::as_text(data + 1, size - 1);
  fuzz::refuse_cleanly([&] {
    auto table = [&](int k) {
      return k == which ? data::CsvTable::parse(text, kNames[k])
                        : data::CsvTable::parse(embedded::find(kNames[k]), kNames[k]);
    };
    const data::Line line = data::line_from_csv_tables(table(0), table(1), table(2), table(3));
    const std::size_t n = std::min<std::size_t>(line.stations.size(), 4);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      data::build_route(line, line.stations[i].name, line.stations[i + 1].name, train);
    }
  });
  return 0;
}
