// The timing-point half of `ecorail solve`: --journey J.json (a TTOBench journey: time and speed
// windows at stops and passing points) solved on the --line track with the --train train by
// dp::solve_timing_journey. Windows no run can meet are input errors naming the window (exit 2);
// a run that misses a window in the re-simulation is never written (exit 1). JSON: the journey
// keys plus windows_met and windows (docs/outputs.md, docs/ttobench.md).
#pragma once

#include <string>

#include "cli/journey_solve.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"

namespace ecorail::cli {

void run_timing_journey(const ProblemOptions& problem, const std::string& journey_path,
                        const OutputOptions& outputs, bool full_report, bool quiet);

}  // namespace ecorail::cli
