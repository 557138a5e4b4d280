// The extension module ecorail._ecorail; the package ecorail (python/ecorail/__init__.py)
// re-exports it. Each binding file binds one part of the library.
#include "data/version.hpp"
#include "python/src/common.hpp"

PYBIND11_MODULE(_ecorail, m) {
  using namespace ecorail::python;
  m.doc() =
      "ecorail: energy-optimal driving of metro trains (DP over position and speed, every "
      "figure from a forward re-simulation). Units are in the names: _kJ, _s, _m, _kmh, _ms "
      "(m/s), _N, _W.";
  m.attr("__version__") = std::string(ecorail::data::version());
  bind_common(m);
  bind_model(m);
  bind_solve(m);
  bind_policy(m);
  bind_fitting(m);
  bind_timetable(m);
  bind_delay(m);
}
