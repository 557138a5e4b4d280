// The reference pattern of question 2.1 for the benchmarks: the default train on the default line
// A1 -> A14, 30 s dwells at the 12 intermediate stations and the optimal split of 2086 s from
// departure to arrival. Built once per program, outside every timing.
#pragma once

#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_library.hpp"
#include "fleet/fleet_pattern.hpp"

namespace ecorail::bench {

inline const fleet::PatternTrip& reference_pattern() {
  static const fleet::PatternTrip p = [] {
    const auto line = data::default_line();
    const auto train = data::default_train();
    const auto stops = data::stops_between(line, "A1", "A14");
    const dp::SectionLibrary lib(train, data::build_routes(line, stops, train), {});
    dp::JourneyOptions o;
    o.measure_marginals = false;
    return fleet::optimal_split_pattern(lib, std::vector<double>(12, 30.0), 2086.0, o);
  }();
  return p;
}

}  // namespace ecorail::bench
