"""Calling overhead of the Python module: the same solve through ecorail.solve (in process) and
through the ecorail program (a new process each time), interleaved in one run so machine load
hits both alike; also each Python call against the library's own solve wall time (solve_wall_s,
the part inside the library), which is the binding's overhead proper.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py build/ecorail [--rounds 15]

Prints the medians and the ratios python/program and python/library (docs/python.md)."""

import argparse
import statistics
import subprocess
import time

import ecorail


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program", help="path to the ecorail program")
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--time", type=float, default=110.0)
    args = parser.parse_args()
    line, train = ecorail.Line.reference(), ecorail.Train.reference()
    cmd = [args.program, "solve", "--from", "A6", "--to", "A7", "--time", str(args.time),
           "--threads", str(args.threads), "--quiet"]
    py_s, cli_s, lib_s = [], [], []
    # One warm-up of each (page cache, lazy imports), then interleaved rounds.
    subprocess.run(cmd, check=True, capture_output=True)
    ecorail.solve(line, train, from_="A6", to="A7", time_s=args.time, threads=args.threads)
    for _ in range(args.rounds):
        t0 = time.perf_counter()
        r = ecorail.solve(line, train, from_="A6", to="A7", time_s=args.time,
                          threads=args.threads)
        py_s.append(time.perf_counter() - t0)
        lib_s.append(r.to_dict()["solve_wall_s"])
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        cli_s.append(time.perf_counter() - t0)
    py, cli, lib = (statistics.median(x) for x in (py_s, cli_s, lib_s))
    print(f"A6 -> A7 in {args.time:g} s, threads {args.threads}, {args.rounds} interleaved rounds "
          f"(medians)")
    print(f"  python ecorail.solve    {py:8.4f} s")
    print(f"  program ecorail solve   {cli:8.4f} s (a new process each time)")
    print(f"  library solve_wall_s    {lib:8.4f} s (inside the python calls)")
    print(f"  ratio python/program    {py / cli:8.4f}")
    print(f"  ratio python/library    {py / lib:8.4f}")


if __name__ == "__main__":
    main()
