"""The energy-time frontier of one section, plotted with matplotlib when it is installed
(python3-matplotlib; otherwise the points are printed and no plot is written).

    PYTHONPATH=build/python python3 examples/python/frontier_plot.py --out frontier.png

Each point is the least traction input energy (kJ) for a running time (s), from a forward
re-simulation; the slope is the time price lambda (kJ/s)."""

import argparse

import ecorail


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from", dest="from_", default="A6")
    parser.add_argument("--to", default="A7")
    parser.add_argument("--tmax-above-min", type=float, default=30.0,
                        help="last running time, s above the flat-out time")
    parser.add_argument("--step", type=float, default=2.0, help="time step, s")
    parser.add_argument("--out", default="", help="plot file (.png or .svg)")
    args = parser.parse_args()
    line, train = ecorail.Line.reference(), ecorail.Train.reference()
    flat_out = ecorail.min_time(line, train, from_=args.from_, to=args.to)
    f = ecorail.frontier(line, train, from_=args.from_, to=args.to,
                         tmax_s=flat_out.running_time_s + args.tmax_above_min, step_s=args.step)
    print(f"{args.from_} -> {args.to}: flat out {f.min_time_s:.2f} s, {len(f.target_time_s)} "
          f"points, monotone {f.monotone}, convex {f.convex}")
    for t, e, lam in zip(f.running_time_s, f.cost_kJ, f.lambda_kJ_per_s):
        print(f"  {t:8.2f} s  {e:10.1f} kJ  lambda {lam:8.3f} kJ/s")
    if not args.out:
        return
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (Debian: python3-matplotlib): no plot written")
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(f.running_time_s, f.cost_kJ, "o-", ms=3)
    ax.set_xlabel("running time (s)")
    ax.set_ylabel("traction input energy (kJ)")
    ax.set_title(f"Energy-time frontier {args.from_} -> {args.to}")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
