// The section-library options of tests that need whole journeys in a second: a coarse grid
// (ds_m x 0.5 km/h, sub-steps of 5 m) and a memory budget (0: every table kept; a budget below
// one table: every table streamed).
#pragma once

#include "dp/section_library.hpp"

namespace ecorail::dp::test {

inline SectionLibraryOptions coarse_library(double ds_m, double memory_budget_bytes) {
  SectionLibraryOptions o;
  o.engine.grid.ds_m = ds_m;
  o.engine.grid.dv_kmh = 0.5;
  o.engine.grid.substep_m = 5.0;
  o.memory_budget_bytes = memory_budget_bytes;
  return o;
}

}  // namespace ecorail::dp::test
