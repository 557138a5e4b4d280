// Dwells of a multi-stop run by stop name: the rule that turns "45 s at A7, 30 s at every other
// stop" into one dwell per intermediate stop, in the order of travel, for solve_journey. A dwell
// named for a station that is not an intermediate stop of the run, a negative dwell, or an
// intermediate stop left without a dwell is a DwellError (a journey never gets a silent default
// dwell). The text form ("A7=45", "30") is the command line's business; this is what it means.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/error.hpp"

namespace ecorail::dp {

// A dwell request that does not fit the run; what() says what was expected.
class DwellError : public std::invalid_argument, public Error {
 public:
  explicit DwellError(const std::string& what)
      : std::invalid_argument(what), Error(ErrorKind::kDwell) {}
};

struct DwellSpec {
  std::vector<std::pair<std::string, double>> by_stop_s;  // (station, dwell in s)
  std::optional<double> every_stop_s;                     // for every stop not named
};

// One dwell per intermediate stop of `stops` (first and last excluded), in order.
std::vector<double> resolve_dwells(const DwellSpec& spec, const std::vector<std::string>& stops);

}  // namespace ecorail::dp
