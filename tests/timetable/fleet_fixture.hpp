// A small fleet for the timetable tests: the reference train on A6 -> A9 (three sections,
// 30 s dwells), its pattern trip with the optimal split of a given trip time, built once per
// test program.
#pragma once

#include <memory>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "timetable/fleet_pattern.hpp"
#include "timetable/fleet_problem.hpp"

namespace ecorail::timetable::testing {

inline const dp::SectionLibrary& small_library() {
  static const std::unique_ptr<dp::SectionLibrary> lib = [] {
    const auto line = data::default_line();
    const auto train = data::default_train();
    const auto stops = data::stops_between(line, "A6", "A9");
    return std::make_unique<dp::SectionLibrary>(train, data::build_routes(line, stops, train),
                                                dp::SectionLibraryOptions{});
  }();
  return *lib;
}

// Trip time 480 s: 420 s running over A6 -> A9 (flat out about 360 s) and two 30 s dwells.
inline const PatternTrip& small_pattern() {
  static const PatternTrip pattern = [] {
    dp::JourneyOptions o;
    o.measure_marginals = false;
    return optimal_split_pattern(small_library(), {30.0, 30.0}, 480.0, o);
  }();
  return pattern;
}

// A fleet of the small pattern: trains, headway range and span.
inline FleetProblem small_fleet(int trains, int headway_min_s, int headway_max_s, int span_s) {
  FleetProblem p;
  p.trains = trains;
  p.headway_min_s = headway_min_s;
  p.headway_max_s = headway_max_s;
  p.span_s = span_s;
  return p;
}

}  // namespace ecorail::timetable::testing
