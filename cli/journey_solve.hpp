// The journey half of `ecorail solve`: when --from and --to are not neighbours, the run stops
// at every station between them. --dwell A7=45 sets one stop's dwell, --dwell 30 every stop's
// that is not named; --split chooses the optimal (one lambda) or the proportional split.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "dp/regimes.hpp"

namespace ecorail::cli {

struct JourneyArgs {
  std::vector<std::string> dwells;  // "A7=45" or "30"
  std::string split = "optimal";    // a dp::split_name
  std::string marginals = "auto";   // on, off, auto (on up to 4 sections)
  // Shared with single-section solves: --min-regime-m/-s and --quiet.
  dp::MinRegimeOptions min_regime;
  bool quiet = false;
};

// Where the human report goes: stderr when an output is written to standard output ("-"), so
// that stdout carries only that output; stdout otherwise.
std::FILE* report_stream(const OutputOptions& outputs);
// "  warning: ..." lines, one per warning.
std::string warnings_text(const std::vector<std::string>& warnings);

// Dwell at each intermediate stop: parses the text and hands the meaning to dp::resolve_dwells.
// InputError for a malformed value; dp::DwellError for an unknown or non-intermediate station,
// or an intermediate stop without a dwell.
std::vector<double> parse_dwells(const std::vector<std::string>& values,
                                 const std::vector<std::string>& stops);

void run_journey(const ProblemOptions& problem, const JourneyArgs& journey,
                 const OutputOptions& outputs, double time_s, bool full_report,
                 const std::vector<std::string>& stops);

}  // namespace ecorail::cli
