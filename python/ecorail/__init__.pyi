from ._ecorail import (Calibration, EnvelopeFit, Frontier, Line, MonteCarloResult, PolicyTable,
                       Run, SolveError, Summary, Termination, Train, __version__, calibrate,
                       delay, fit_envelope, frontier, journey, min_time, montecarlo,
                       policy_table, solve, timetable)
