"""ecorail: energy-optimal driving of metro trains, from Python.

The library's solvers (a dynamic program over position and speed priced by a Lagrange multiplier
on running time; every figure from a forward re-simulation at a 5 cm step) with the program's
defaults. Units are in the names: _kJ, _s, _m, _kmh, _ms (m/s), _N, _W.

    >>> import ecorail
    >>> r = ecorail.solve(ecorail.Line.reference(), ecorail.Train.reference(),
    ...                   from_="A6", to="A7", time_s=110)
    >>> r.traction_energy_kJ, r.speed_ms.shape

Results: ecorail.Run (solve, min_time, journey), ecorail.Frontier, ecorail.PolicyTable,
ecorail.EnvelopeFit, ecorail.Calibration; each has to_dict() equal to the program's --json.
Bad input raises ValueError naming the argument; a result that misses its stop or time raises
ecorail.SolveError; Ctrl-C stops a solve between stages with KeyboardInterrupt.
See docs/python.md.
"""

import os as _os
import sys as _sys
import sysconfig as _sysconfig

# numpy for an interpreter without it (e.g. a CPython built from source next to Debian's): the
# module is built for Debian's python3, whose numpy is a Debian package. When numpy cannot be
# imported and Debian's numpy was built for this interpreter's ABI (same extension suffix), its
# dist-packages directory is appended to sys.path (after the interpreter's own directories, so
# anything the interpreter has itself wins). Nothing is changed otherwise. docs/python.md.
_DEBIAN_DIST_PACKAGES = "/usr/lib/python3/dist-packages"


def _debian_numpy_matches():
    core = _os.path.join(_DEBIAN_DIST_PACKAGES, "numpy", "core")
    suffix = _sysconfig.get_config_var("EXT_SUFFIX") or ""
    try:
        return any(name.startswith("_multiarray_umath") and name.endswith(suffix)
                   for name in _os.listdir(core))
    except OSError:
        return False


try:
    import numpy as _numpy  # noqa: F401
except ImportError:
    if _debian_numpy_matches() and _DEBIAN_DIST_PACKAGES not in _sys.path:
        _sys.path.append(_DEBIAN_DIST_PACKAGES)
        import numpy as _numpy  # noqa: F401

from ._ecorail import (  # noqa: E402,F401
    Calibration,
    EnvelopeFit,
    Frontier,
    Line,
    MonteCarloResult,
    PolicyTable,
    Run,
    SolveError,
    Summary,
    Termination,
    Train,
    __version__,
    calibrate,
    delay,
    fit_envelope,
    frontier,
    journey,
    min_time,
    montecarlo,
    policy_table,
    solve,
    timetable,
)

# The submodules import as modules too: `import ecorail.timetable`, `from ecorail.delay import
# recover`.
_sys.modules[__name__ + ".timetable"] = timetable
_sys.modules[__name__ + ".delay"] = delay

__all__ = [
    "Calibration", "EnvelopeFit", "Frontier", "Line", "MonteCarloResult", "PolicyTable", "Run",
    "SolveError", "Summary", "Termination", "Train", "calibrate", "delay", "fit_envelope",
    "frontier", "journey", "min_time", "montecarlo", "policy_table", "solve", "timetable",
]
