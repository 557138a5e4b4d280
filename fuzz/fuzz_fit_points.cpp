// Fit points (speed, force): parsed, and small sets within 100 km/h fitted with Ceres (both
// forms), where speeds of 1e300 once aborted inside Ceres. A fit may refuse its points (an
// InputError naming what they lack, e.g. too few distinct speeds, or std::invalid_argument);
// it must not crash.
#include <algorithm>
#include <stdexcept>

#include "fitting/envelope_fit.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<fitting::EnvelopePoint> points;
  try {
    points = fitting::parse_envelope_points(fuzz::as_text(data, size), "points.csv");
  } catch (const data::InputError&) {
    return 0;
  }
  const bool small =
      points.size() <= 64 &&
      std::all_of(points.begin(), points.end(), [](const auto& p) { return p.speed_kmh <= 100.0; });
  if (!small) return 0;  // the profile search is 0.05 km/h fine: keep each input fast
  try {
    fitting::fit_envelope(points, fitting::EnvelopeFitOptions{});
  } catch (const data::InputError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
