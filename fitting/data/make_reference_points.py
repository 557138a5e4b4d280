#!/usr/bin/env python3
"""Samples the reference train's traction and braking envelopes (docs/model.md) every 0.5 km/h
from 0 to 80 km/h with 0.3 % Gaussian noise (fixed seed), as a digitised manufacturer's curve
would come. Writes reference_traction_points.csv and reference_braking_points.csv beside this
script; `ecorail fit-envelope` should recover the breakpoints 51.5 and 77 km/h from them."""
import os
import random


def traction(v):
    if v <= 51.5:
        return 203.0
    return -0.002032 * v**3 + 0.4928 * v**2 - 42.13 * v + 1343.0


def braking(v):
    if v <= 77.0:
        return 166.0
    return 0.1343 * v**2 - 25.07 * v + 1300.0


def write(name, f, seed):
    rng = random.Random(seed)
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, name), "w") as out:
        out.write("speed_kmh,force_kN\n")
        for i in range(161):
            v = 0.5 * i
            out.write(f"{v:.1f},{f(v) * (1.0 + 0.003 * rng.gauss(0.0, 1.0)):.3f}\n")


if __name__ == "__main__":
    write("reference_traction_points.csv", traction, 1)
    write("reference_braking_points.csv", braking, 2)
