"""Fixtures of the Python module's tests: the ecorail program (ECORAIL_CLI), the source tree
(ECORAIL_SOURCE_DIR) and a way to run the program and read its JSON, so each test compares the
module with the program on the same inputs. ctest sets the variables (tests/CMakeLists.txt)."""

import json
import os
import subprocess

import pytest

import ecorail

CLI = os.environ.get("ECORAIL_CLI", "")
SOURCE_DIR = os.environ.get("ECORAIL_SOURCE_DIR", "")


def without_wall_times(value, also=()):
    """A report without its wall-clock figures (keys *_wall_s, and the keys named in also): the
    only keys two runs on the same inputs may differ in."""
    if isinstance(value, dict):
        return {k: without_wall_times(v, also) for k, v in value.items()
                if not k.endswith("_wall_s") and k not in also}
    if isinstance(value, list):
        return [without_wall_times(v, also) for v in value]
    return value


@pytest.fixture(scope="session")
def cli():
    if not (CLI and os.access(CLI, os.X_OK)):
        pytest.fail("ECORAIL_CLI must name the ecorail program (set by ctest)")
    return CLI


@pytest.fixture(scope="session")
def source_dir():
    if not (SOURCE_DIR and os.path.isdir(SOURCE_DIR)):
        pytest.fail("ECORAIL_SOURCE_DIR must name the source tree (set by ctest)")
    return SOURCE_DIR


@pytest.fixture
def run_cli(cli, tmp_path):
    """run_cli(args..., json_flag='--json') -> the JSON the program wrote (cwd: tmp_path)."""

    def run(*args, json_flag="--json", extra_files=()):
        out = tmp_path / "cli_out.json"
        cmd = [cli, *map(str, args)]
        if json_flag:
            cmd += [json_flag, str(out)]
        proc = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True)
        assert proc.returncode == 0, f"{cmd} failed: {proc.stderr}"
        return json.loads(out.read_text()) if json_flag else proc

    return run


@pytest.fixture(scope="session")
def reference():
    return ecorail.Line.reference(), ecorail.Train.reference()


FLAT_TRACK = """{"metadata": {"id": "flat_3km", "library version": "TTOBench v1.4"},
 "stops": {"unit": "m", "values": [0, 3000]},
 "speed limits": {"units": {"position": "m", "velocity": "km/h"}, "values": [[0, 80]]},
 "gradients": {"units": {"position": "m", "slope": "permil"}, "values": [[0, 0]]}}"""

HAND_TRAIN = """{"metadata": {"id": "hand_train", "library version": "TTOBench v1.4"},
 "mass": {"unit": "t", "value": 200}, "rho": {"unit": "%", "value": 5},
 "max traction power": {"unit": "kW", "value": 2000}, "max reg braking power": {"unit": "kW", "value": 2000},
 "max traction force": {"unit": "kN", "value": 200}, "max reg braking force": {"unit": "kN", "value": 150},
 "max pn braking force": {"unit": "kN", "value": 50}, "max speed": {"unit": "km/h", "value": 100},
 "rolling resistance r0": {"unit": "kN", "value": 2}, "rolling resistance r1": {"unit": "kN/(km/h)", "value": 0.02},
 "rolling resistance r2": {"unit": "kN/(km/h)^2", "value": 0.0005},
 "efficiency traction": {"unit": "%", "value": 90}, "efficiency reg brake": {"unit": "%", "value": 80}}"""


def journey_text(values):
    return """{"metadata": {"id": "flat_3km_J", "library version": "TTOBench v1.5", "associated track": "flat_3km"},
 "timing points": {"units": {"position": "m", "lower time constraint": "s", "upper time constraint": "s",
   "lower speed constraint": "km/h", "upper speed constraint": "km/h"},
   "values": %s}}""" % values


@pytest.fixture
def ttobench_files(tmp_path):
    """(track, train, journey writer) in tmp_path, named by relative paths as the program is run
    from tmp_path: the same labels reach both reports' provenance."""
    (tmp_path / "track.json").write_text(FLAT_TRACK)
    (tmp_path / "train.json").write_text(HAND_TRAIN)

    def write_journey(name, values):
        (tmp_path / name).write_text(journey_text(values))
        return name

    return "track.json", "train.json", write_journey


@pytest.fixture(scope="session")
def cache_dir():
    """The frontier cache of the delay and Monte Carlo tests: one directory in the build tree."""
    base = os.environ.get("ECORAIL_BINARY_DIR")
    if not base:
        pytest.fail("ECORAIL_BINARY_DIR must name the build tree (set by ctest)")
    path = os.path.join(base, "test-cache", "python")
    os.makedirs(path, exist_ok=True)
    return path
