"""A Monte Carlo summary: service days of the 2.1 reference plan under random delays, recovered
exactly and by the seed paper's rule, with 95 % confidence intervals.

    PYTHONPATH=build/python python3 examples/python/montecarlo_summary.py --days 20

Days are drawn from a counter-based generator keyed by the seed: the same days for any thread
count; energies in kJ (docs/delays.md)."""

import argparse

import numpy as np

import ecorail


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--cache-dir", default=None, help="frontier cache (default: the program's)")
    args = parser.parse_args()
    line, train = ecorail.Line.reference(), ecorail.Train.reference()
    print(f"{'recovery':>8} {'punctuality':>19} {'mean lateness s':>17} {'substation kJ/day':>28}")
    for policy in ("exact", "rule"):
        m = ecorail.montecarlo(line, train, days=args.days, seed=args.seed, recovery=policy,
                               cache_dir=args.cache_dir)
        p, late, sub = m.punctuality, m.mean_lateness_s, m.substation_energy_kJ
        # The summary's mean is the mean of the days' own figures.
        assert abs(sub["mean"] - np.mean(m.day_substation_kJ)) <= 1e-6 * sub["mean"]
        print(f"{policy:>8} {p['mean']:10.4f} +- {p['ci95_half_width']:.4f} "
              f"{late['mean']:8.3f} +- {late['ci95_half_width']:.3f} "
              f"{sub['mean']:16.1f} +- {sub['ci95_half_width']:9.1f}")


if __name__ == "__main__":
    main()
