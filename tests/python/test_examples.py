"""The Python examples (examples/python/) run as a user runs them, and print what they claim:
the frontier plot (a PNG when matplotlib is installed), the headway sweep (traction per train
the README's 596547.6 kJ at every headway) and the Monte Carlo summary."""

import os
import re
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def run_example(name, *args, cwd):
    env = dict(os.environ)
    proc = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "examples", "python", name),
                           *map(str, args)], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=900)
    assert proc.returncode == 0, f"{name}: {proc.stderr}"
    return proc.stdout


def test_frontier_plot(tmp_path):
    out = run_example("frontier_plot.py", "--tmax-above-min", "6", "--step", "2", "--out",
                      tmp_path / "frontier.png", cwd=tmp_path)
    assert re.search(r"A6 -> A7: flat out 85\.4\d s, 4 points, monotone True", out), out
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        assert "no plot written" in out
        return
    png = (tmp_path / "frontier.png").read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 5000


def test_headway_sweep(tmp_path):
    out = run_example("headway_sweep.py", "--headways", "300,600", cwd=tmp_path)
    rows = [l.split() for l in out.splitlines() if re.match(r"\s+\d+\s+\d+\s", l)]
    assert [(r[0], r[1]) for r in rows] == [("300", "214"), ("600", "107")]
    assert "traction per train 596547.6 kJ at every headway" in out  # README's per-train figure


def test_montecarlo_summary(tmp_path):
    base = os.environ.get("ECORAIL_BINARY_DIR")
    if not base:
        pytest.fail("ECORAIL_BINARY_DIR must name the build tree (set by ctest)")
    cache = os.path.join(base, "test-cache", "python")
    out = run_example("montecarlo_summary.py", "--days", "4", "--cache-dir", cache, cwd=tmp_path)
    lines = [l.split() for l in out.splitlines()[1:]]
    assert [l[0] for l in lines] == ["exact", "rule"]
    for l in lines:
        assert 0.0 <= float(l[1]) <= 1.0  # punctuality
