from ._ecorail import (Calibration, EnvelopeFit, Frontier, Line, PolicyTable, Run, SolveError,
                       Summary, Termination, Train, __version__, calibrate, fit_envelope,
                       frontier, journey, min_time, policy_table, solve)
