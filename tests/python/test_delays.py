"""Delays and Monte Carlo days from Python against the ecorail program on the reference line:
ecorail.delay.recover (the README's figures of question 3.1, and the program's --json) and
ecorail.montecarlo (the program's --json), on the reference plan and on a timetable CSV given as
a path or as an ecorail.delay.Plan. Their frontier cache is one directory in the build tree
(the fixture cache_dir, conftest.py), which the examples' test reads after them."""

import numpy as np
import pytest

import ecorail
from conftest import without_wall_times


def test_delay_recover_matches_readme_and_cli(reference, run_cli, cache_dir):
    line, train = reference
    cli = run_cli("delay", "--reference", "--train", "37", "--station", "A9", "--delay", "30",
                  "--cache-dir", cache_dir)
    r = ecorail.delay.recover(line, train, train_number=37, station="A9", delay_s=30,
                              cache_dir=cache_dir)
    assert r.back_on_time_at == "A11" and r.recovered
    # README, "Delays (question 3.1)".
    assert (f"{r.recovery_energy_kJ:.1f}", f"{r.rule_energy_kJ:.1f}",
            f"{r.plan_energy_kJ:.1f}") == ("103531.6", "126687.6", "77375.5")
    summary = cli["summary"] if "summary" in cli else cli
    assert r.recovery_energy_kJ == pytest.approx(summary["recovery_energy_kJ"], abs=1e-9)
    # to_dict() is the program's --json, provenance included (wall-clock figures aside).
    clock = ("wall_s", "brief_report")
    assert without_wall_times(r.to_dict(), clock) == without_wall_times(cli, clock)
    assert r.to_dict()["provenance"]["options"]["plan"] == "reference"
    assert [s["from"] for s in r.sections] == ["A9", "A10"]
    with pytest.raises(ValueError, match="station"):
        ecorail.delay.recover(line, train, train_number=37, station="A14", delay_s=30,
                              cache_dir=cache_dir)


def test_montecarlo_matches_cli(reference, run_cli, cache_dir):
    line, train = reference
    # The fast mode on the whole line (driven followers solve their runs at every start; they
    # are compared on a small plan below).
    cli = run_cli("montecarlo", "--reference", "--days", "3", "--seed", "3", "--cache-dir",
                  cache_dir, "--quiet", "--followers", "shortcut")
    one = ecorail.montecarlo(line, train, days=3, seed=3, cache_dir=cache_dir, threads=1,
                             followers="shortcut")
    two = ecorail.montecarlo(line, train, days=3, seed=3, cache_dir=cache_dir, threads=2,
                             followers="shortcut")
    assert one.to_dict() == cli
    assert two.to_dict() == cli  # the same days for any thread count (3 days on 2 threads)
    assert one.day_substation_kJ.shape == (3,)
    assert one.substation_energy_kJ["mean"] == pytest.approx(np.mean(one.day_substation_kJ),
                                                             rel=1e-12)
    assert 0.0 <= one.punctuality["mean"] <= 1.0
    assert cli["config"]["followers"] == "shortcut"
    with pytest.raises(ValueError, match="^followers"):
        ecorail.montecarlo(line, train, days=2, followers="fast", cache_dir=cache_dir)


def test_delay_and_montecarlo_on_a_plan_csv(reference, run_cli, cache_dir, tmp_path,
                                             monkeypatch):
    line, train = reference
    # Three trains A6 -> A9, 300 s apart: the timetable CSV `--plan` reads (as tests/cli/delay.sh).
    run_cli("timetable", "evaluate", "--from", "A6", "--to", "A9", "--trip-time", "380",
            "--trains", "3", "--span", "600", "--headway", "120:660", "--csv", "plan.csv",
            "--quiet", json_flag=None)
    monkeypatch.chdir(tmp_path)  # the plan named as the program is given it: "plan.csv"
    args = ("--train", "2", "--station", "A7", "--delay", "10", "--cache-dir", cache_dir)
    cli = run_cli("delay", "--plan", "plan.csv", *args)
    by_path = ecorail.delay.recover(line, train, train_number=2, station="A7", delay_s=10,
                                    plan="plan.csv", cache_dir=cache_dir)
    clock = ("wall_s", "brief_report")
    assert without_wall_times(by_path.to_dict(), clock) == without_wall_times(cli, clock)
    # The same plan as an object (arrays read back from the file) gives the same document.
    p = ecorail.delay.Plan.from_csv("plan.csv")
    assert p.trains == 3 and p.arrival_s.shape == (3, len(p.stations))
    assert p.arrival_s.dtype == np.float64
    assert np.all(np.diff(p.departure_s[:, 0]) == 300.0)
    same = ecorail.delay.Plan(p.stations, p.arrival_s, p.departure_s, name="plan.csv")
    by_object = ecorail.delay.recover(line, train, train_number=2, station="A7", delay_s=10,
                                      plan=same, cache_dir=cache_dir)
    assert without_wall_times(by_object.to_dict(), clock) == without_wall_times(cli, clock)
    with pytest.raises(ValueError, match="train_number"):
        ecorail.delay.recover(line, train, train_number=4, station="A7", delay_s=10,
                              plan=p, cache_dir=cache_dir)
    with pytest.raises(ValueError, match="arrival_s/departure_s"):
        ecorail.delay.Plan(p.stations, p.arrival_s[::-1], p.departure_s[::-1])
    mc_cli = run_cli("montecarlo", "--plan", "plan.csv", "--days", "4", "--seed", "2",
                     "--cache-dir", cache_dir, "--quiet")
    mc = ecorail.montecarlo(line, train, plan="plan.csv", days=4, seed=2, cache_dir=cache_dir,
                            threads=1)
    assert mc.to_dict() == mc_cli
    assert mc_cli["config"]["followers"] == "driven"  # the default, in both
    assert mc.summary.termination == ecorail.Termination.CONVERGENCE
    assert mc.summary.is_solution_usable
