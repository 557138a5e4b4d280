"""The single-train API against the ecorail program: each result's to_dict() equals the
program's --json for the same inputs (wall-clock keys aside), arrays have the documented dtypes
and the program's CSV row count, and the README's figure comes out of ecorail.solve."""

import csv

import numpy as np
import pytest

import ecorail
from conftest import without_wall_times

FLOAT_ARRAYS = ["time_s", "position_m", "speed_ms", "accel_m_s2", "traction_N", "braking_N",
                "power_W", "km_post_m", "gradient_permille", "speed_limit_ms"]


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def assert_printed(value, text):
    """value rounds to text: within half a unit of text's last printed digit."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    assert abs(value - float(text)) <= 0.5 * 10.0 ** -decimals + 1e-9, (value, text)


def check_arrays(run, rows):
    for name in FLOAT_ARRAYS:
        a = getattr(run, name)
        assert isinstance(a, np.ndarray) and a.dtype == np.float64 and a.shape == (len(rows),), name
    assert run.section.dtype == np.int32 and run.section.shape == (len(rows),)
    assert run.regime.dtype.kind == "U" and run.regime.shape == (len(rows),)
    # Row by row the same table as the program's CSV (km/h and kN there), to its printed digits.
    for i, row in enumerate(rows):
        assert_printed(run.time_s[i], row["time_s"])
        assert_printed(run.position_m[i], row["distance_m"])
        assert_printed(run.speed_ms[i] * 3.6, row["speed_kmh"])
        assert_printed(run.traction_N[i] / 1000, row["traction_force_kN"])
        assert_printed(run.braking_N[i] / 1000, row["braking_force_kN"])
        assert_printed(run.power_W[i] / 1000, row["traction_power_kW"])
        assert run.regime[i] == row["regime"]


def test_readme_section_figure_and_cli_json(reference, run_cli, tmp_path):
    line, train = reference
    r = ecorail.solve(line, train, from_="A6", to="A7", time_s=110)
    cli = run_cli("solve", "--from", "A6", "--to", "A7", "--time", "110", "--quiet",
                  "--csv", tmp_path / "run.csv")
    assert f"{r.traction_energy_kJ:.1f}" == "34898.0"  # README, "Results on the reference problem"
    assert r.traction_energy_kJ == cli["traction_energy_kJ"]
    assert without_wall_times(r.to_dict()) == without_wall_times(cli)
    assert r.summary.termination == ecorail.Termination.CONVERGENCE
    assert r.summary.is_solution_usable
    assert r.summary.brief_report.startswith("ecorail") or "A6" in r.summary.brief_report
    assert "A6" in r.summary.full_report
    assert abs(r.running_time_s - 110) <= 1e-3
    check_arrays(r, csv_rows(tmp_path / "run.csv"))
    # Traction work is the integral of traction power over time (per-second samples: trapezoid
    # rule within 2 % of the re-simulated figure).
    assert np.trapz(r.power_W, r.time_s) / 1000 == pytest.approx(r.traction_energy_kJ, rel=0.02)


def test_journey_matches_cli(reference, run_cli, tmp_path):
    line, train = reference
    r = ecorail.solve(line, train, from_="A6", to="A8", time_s=220, dwell={"A7": 45})
    cli = run_cli("solve", "--from", "A6", "--to", "A8", "--time", "220", "--dwell", "A7=45",
                  "--quiet", "--csv", tmp_path / "run.csv")
    assert r.kind == "journey"
    assert without_wall_times(r.to_dict()) == without_wall_times(cli)
    assert f"{r.traction_energy_kJ:.1f}" == "67012.9"  # README
    rows = csv_rows(tmp_path / "run.csv")
    check_arrays(r, rows)
    assert set(r.section.tolist()) == {0, 1}
    assert "dwell" in set(r.regime.tolist())


def test_proportional_split_and_dwell_forms(reference, run_cli):
    line, train = reference
    cli = run_cli("solve", "--from", "A6", "--to", "A8", "--time", "220", "--dwell", "45",
                  "--split", "proportional", "--quiet")
    for dwell in (45, {"*": 45}, ["45"]):
        r = ecorail.solve(line, train, from_="A6", to="A8", time_s=220, dwell=dwell,
                          split="proportional")
        assert without_wall_times(r.to_dict()) == without_wall_times(cli)


def test_min_time_matches_cli(reference, run_cli, tmp_path):
    line, train = reference
    r = ecorail.min_time(line, train, from_="A6", to="A7")
    cli = run_cli("min-time", "--from", "A6", "--to", "A7", "--csv", tmp_path / "run.csv")
    assert r.to_dict() == cli
    assert r.running_time_s == cli["min_running_time_s"]
    check_arrays(r, csv_rows(tmp_path / "run.csv"))


def test_frontier_matches_cli(reference, run_cli):
    line, train = reference
    f = ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=100, tmax_s=103, step_s=1)
    cli = run_cli("frontier", "--from", "A6", "--to", "A7", "--tmin", "100", "--tmax", "103",
                  "--step", "1", "--no-cache", "--quiet")
    assert without_wall_times(f.to_dict()) == without_wall_times(cli)
    assert f.target_time_s.tolist() == [100.0, 101.0, 102.0, 103.0]
    for name in ("running_time_s", "traction_energy_kJ", "regen_energy_kJ", "cost_kJ",
                 "lambda_kJ_per_s"):
        a = getattr(f, name)
        assert a.dtype == np.float64 and a.shape == (4,), name
    assert f.traction_energy_kJ.tolist() == [p["traction_energy_kJ"] for p in cli["points"]]
    # Energy falls with running time on a frontier.
    assert np.all(np.diff(f.cost_kJ) < 0)


def test_timing_journey_matches_cli(ttobench_files, run_cli, tmp_path, monkeypatch):
    track, train_file, write_journey = ttobench_files
    journey = write_journey("free.json", "[[0,0,0,0,0],[1500,30,170,null,null],[3000,150,190,0,0]]")
    grid = ["--ds", "5", "--dv", "0.5"]
    cli = run_cli("solve", "--line", track, "--train", train_file, "--journey", journey, *grid,
                  "--quiet")
    monkeypatch.chdir(tmp_path)
    line, train = ecorail.Line.from_file(track), ecorail.Train.from_file(train_file)
    r = ecorail.journey(line, train, journey, ds_m=5, dv_kmh=0.5)
    assert r.kind == "timing journey"
    assert without_wall_times(r.to_dict()) == without_wall_times(cli)
    assert r.to_dict()["windows_met"] is True
    # A window no run can meet is a ValueError naming the window.
    bad = write_journey("bad.json", "[[0,0,0,0,0],[1500,0,20,null,null],[3000,150,190,0,0]]")
    with pytest.raises(ValueError, match=r"timing points\.values\[1\]"):
        ecorail.journey(line, train, bad, ds_m=5, dv_kmh=0.5)
    # Progress after each price evaluation: the same run with a callable; one that raises stops
    # the solve there and the interpreter goes on.
    calls = []
    again = ecorail.journey(line, train, journey, ds_m=5, dv_kmh=0.5,
                            progress=lambda stage, done, total: calls.append((stage, done)))
    assert without_wall_times(again.to_dict()) == without_wall_times(cli)
    assert calls and calls[0][1] == 1
    assert {stage for stage, _ in calls} <= {"price evaluation", "lambda evaluation",
                                             "cruise polish"}

    def stop(stage, done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        ecorail.journey(line, train, journey, ds_m=5, dv_kmh=0.5, progress=stop)


def test_policy_table_bytes_match_cli(reference, cli, tmp_path):
    import subprocess
    line, train = reference
    out = tmp_path / "a6a7.policy"
    subprocess.run([cli, "policy", "--from", "A6", "--to", "A7", "--time", "110",
                    "--lambda-ladder", "-5,0", "--out", str(out), "--quiet"], check=True,
                   capture_output=True)
    t = ecorail.policy_table(line, train, from_="A6", to="A7", time_s=110, ladder_s=[-5, 0])
    assert t.to_bytes() == out.read_bytes()
    assert [round(L["target_time_s"], 6) for L in t.layers] == [105.0, 110.0]
    # The nominal layer's plan runs in its time; advice at the start is to motor.
    assert t.layers[1]["planned_time_s"] == pytest.approx(110, abs=0.1)
    assert t.advise(0.0, 0.0)["control"] in ("max_traction", "MaxTraction", "full_traction")


def test_fit_envelope_matches_cli(source_dir, run_cli, tmp_path):
    points = f"{source_dir}/fitting/data/reference_traction_points.csv"
    cli = run_cli("fit-envelope", "--points", points, "--kind", "traction",
                  "--out", tmp_path / "fitted.toml")
    f = ecorail.fit_envelope(points, kind="traction")
    assert f.to_dict() == cli
    assert f.train.to_toml() == (tmp_path / "fitted.toml").read_text()


def test_calibrate_matches_cli(source_dir, run_cli, tmp_path):
    log = f"{source_dir}/data/contest/seed_profile_A6_A7_110s.csv"
    cli = run_cli("calibrate", "--log", log, "--method", "equation", "--quiet",
                  "--out", tmp_path / "cal.toml")
    c = ecorail.calibrate([log], method="equation")
    # Ceres' solve time and the calibration's total time are wall-clock figures.
    clock = ("solve_time_s", "total_time_s")
    assert without_wall_times(c.to_dict(), clock) == without_wall_times(cli, clock)
    assert c.train.to_toml() == (tmp_path / "cal.toml").read_text()
    assert c.summary.termination == ecorail.Termination.CONVERGENCE


def test_pass_through_matches_cli(reference, run_cli):
    line, train = reference
    cli = run_cli("solve", "--from", "A6", "--to", "A8", "--pass-through", "A7", "--time", "200",
                  "--quiet")
    r = ecorail.solve(line, train, from_="A6", to="A8", pass_through=["A7"], time_s=200)
    assert r.kind == "section"
    assert without_wall_times(r.to_dict()) == without_wall_times(cli)
