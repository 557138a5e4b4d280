"""Fleets from Python against the ecorail program on the reference line:
ecorail.timetable.evaluate/optimise (energy document of --json, pattern search too, peak windows,
the proven gap) and Fleet.separation (its "separation" block). The delay and Monte Carlo tests
are in test_delays.py (two files, so that ctest runs them side by side)."""

import numpy as np
import pytest

import ecorail
from conftest import without_wall_times


def test_timetable_evaluate_matches_cli(reference, run_cli):
    line, train = reference
    cli = run_cli("timetable", "evaluate", "--uniform", "--model", "overlap", "--overlap",
                  "either", "--quiet")
    r = ecorail.timetable.evaluate(line, train, model="overlap", overlap="either")
    assert without_wall_times(r.to_dict()) == without_wall_times(cli)
    assert r.departures_s.dtype == np.int32 and r.departures_s.shape == (100,)
    assert r.departures_s[0] == 0 and r.departures_s[-1] == 63900
    assert r.headways_s.shape == (99,) and np.all((r.headways_s >= 120) & (r.headways_s <= 660))
    assert r.substation_energy_kJ == pytest.approx(
        r.traction_energy_kJ - r.used_regen_kJ, rel=1e-12)
    assert f"{r.substation_energy_kJ:.1f}" == "55837973.2"  # README, overlap --overlap either


def test_power_flow_bins_add_up_to_the_energies(reference):
    line, train = reference
    r = ecorail.timetable.evaluate(line, train, headways_s=[641] * 50 + [650] * 49)
    assert f"{r.substation_energy_kJ:.1f}" == "56238700.8"  # README, published headways
    step = r.power_time_s[1] - r.power_time_s[0]
    assert step == pytest.approx(0.01)
    # Per-bin power integrates to the totals (an independent sum over 6.6 million bins).
    assert np.sum(r.traction_power_W) * step / 1e3 == pytest.approx(r.traction_energy_kJ,
                                                                      rel=1e-6)
    assert np.sum(r.used_regen_power_W) * step / 1e3 == pytest.approx(r.used_regen_kJ, rel=1e-6)
    assert np.all(r.used_regen_power_W <= r.regen_power_W + 1e-6)


def test_timetable_optimise_matches_cli(reference, run_cli):
    line, train = reference
    cli = run_cli("timetable", "optimise", "--model", "overlap", "--overlap", "either",
                  "--quiet")
    r = ecorail.timetable.optimise(line, train, model="overlap", overlap="either")
    # The optimiser's wall time, also quoted in its brief report, is a clock figure.
    clock = ("wall_s", "brief_report")
    assert without_wall_times(r.to_dict(), clock) == without_wall_times(cli, clock)
    assert r.to_dict()["summary"]["brief_report"].startswith("CONVERGENCE")
    assert r.summary.termination == ecorail.Termination.CONVERGENCE
    assert f"{r.substation_energy_kJ:.1f}" == "54177502.3"  # README: the exact chain DP


def test_optimise_from_a_given_timetable(reference, run_cli, tmp_path):
    # A timetable to start from (headways_s / departures_s, `--headways`): the program's
    # document, and a result that never uses less than the timetable, although the search
    # alone (no annealing) ends lower.
    line, train = reference
    fleet = ecorail.timetable.Fleet(line, train)
    searched = fleet.optimise(trains=12, span_s=6000, moves=20000, restarts=4)
    alone = fleet.optimise(trains=12, span_s=6000, restarts=0)
    headways = searched.to_dict()["headways_s"]
    given = fleet.optimise(trains=12, span_s=6000, restarts=0, headways_s=headways)
    assert alone.to_dict()["used_regen_kJ"] < searched.to_dict()["used_regen_kJ"] - 1e-6
    assert given.to_dict()["used_regen_kJ"] >= searched.to_dict()["used_regen_kJ"] - 1e-6
    summary = given.to_dict()["summary"]
    assert summary["given_start_used_regen_kJ"] == pytest.approx(
        searched.to_dict()["used_regen_kJ"], abs=1e-6)
    csv = tmp_path / "start.csv"
    csv.write_text("headway_s\n" + "".join(f"{h}\n" for h in headways))
    cli = run_cli("timetable", "optimise", "--trains", "12", "--span", "6000", "--restarts", "0",
                  "--headways", csv, "--quiet")
    clock = ("wall_s", "brief_report")
    assert without_wall_times(given.to_dict(), clock) == without_wall_times(cli, clock)
    departures = searched.to_dict()["departures_s"]
    by_departures = fleet.optimise(trains=12, span_s=6000, restarts=0, departures_s=departures)
    assert by_departures.to_dict()["departures_s"] == given.to_dict()["departures_s"]
    with pytest.raises(ValueError, match="^headways_s: expected pattern=False"):
        fleet.optimise(trains=12, span_s=6000, headways_s=headways, pattern=True)
    with pytest.raises(ValueError, match="headways_s"):
        fleet.optimise(trains=12, span_s=6000, headways_s=headways[:-1])


def test_timetable_bad_values(reference):
    line, train = reference
    with pytest.raises(ValueError, match="model"):
        ecorail.timetable.evaluate(line, train, model="magic")
    with pytest.raises(ValueError, match="sections_at_m"):
        ecorail.timetable.evaluate(line, train, model="sections")
    with pytest.raises(ValueError, match="headway"):
        ecorail.timetable.evaluate(line, train, headway_s=(120.5, 660))
    with pytest.raises(ValueError, match="sections_at_m"):
        ecorail.timetable.evaluate(line, train, sections_at_m=[5000.0])  # power-flow has none
    with pytest.raises(ValueError, match="^sections_at_m: supply-section boundaries inside"):
        ecorail.timetable.evaluate(line, train, model="sections", sections_at_m=[1e7])


def test_peak_windows_match_cli(reference, run_cli):
    line, train = reference
    peaks = ["--peak", "7200:12600", "--peak", "43200:50400"]
    cli = run_cli("timetable", "evaluate", "--model", "overlap", "--overlap", "either",
                  "--trains", "240", *peaks, "--uniform", "--quiet")
    fleet = ecorail.timetable.Fleet(line, train, model="overlap", overlap="either")
    r = fleet.evaluate(trains=240, peaks=[(7200, 12600), (43200, 50400)])
    assert r.to_dict() == cli
    assert r.departures_s.shape == (240,)
    # The same fleet object evaluates another problem on the same sections and pattern.
    day = fleet.evaluate()
    assert day.departures_s.shape == (100,)
    assert day.traction_energy_kJ / 100 == pytest.approx(r.traction_energy_kJ / 240, rel=1e-12)
    # The separation check on the same fleet: the "separation" block of the program's JSON.
    cli = run_cli("timetable", "evaluate", "--model", "overlap", "--overlap", "either",
                  "--trains", "3", "--span", "300", "--uniform", "--separation", "--follower",
                  "supervise", "--quiet")
    s = fleet.separation(trains=3, span_s=300, follower="supervise")
    assert s.to_dict() == cli["separation"]
    assert s.min_distance_margin_m == cli["separation"]["min_distance_margin_m"]
    with pytest.raises(ValueError, match="follower"):
        fleet.separation(trains=3, span_s=300, follower="fast")
    # Progress after each train; a progress callable that raises stops the run there, and the
    # Fleet answers as before afterwards.
    calls = []
    again = fleet.separation(trains=3, span_s=300, follower="supervise",
                             progress=lambda stage, done, total: calls.append((stage, done, total)))
    assert calls == [("service", 1, 3), ("service", 2, 3), ("service", 3, 3)]
    assert again.to_dict() == s.to_dict()

    def stop(stage, done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        fleet.separation(trains=3, span_s=300, follower="supervise", progress=stop)
    assert fleet.separation(trains=3, span_s=300, follower="supervise").to_dict() == s.to_dict()


def test_optimise_gap_matches_cli(reference, run_cli):
    line, train = reference
    small = ("--trains", "12", "--span", "6000", "--moves", "20000")
    cli = run_cli("timetable", "optimise", *small, "--gap", "0.5", "--quiet")
    fleet = ecorail.timetable.Fleet(line, train)
    r = fleet.optimise(trains=12, span_s=6000, moves=20000, gap=0.5)
    clock = ("wall_s", "brief_report")
    assert without_wall_times(r.to_dict(), clock) == without_wall_times(cli, clock)
    gap = r.to_dict()["summary"]["gap_fraction_of_substation"]
    assert 1e-4 < gap <= 0.5
    assert r.summary.termination == ecorail.Termination.CONVERGENCE
    # The same search held to the default gap (1e-4) has not proven it: a result, flagged.
    strict = fleet.optimise(trains=12, span_s=6000, moves=20000)
    assert strict.summary.termination == ecorail.Termination.NO_CONVERGENCE
    # A search stopped by its budget is a result (as Ceres' NO_CONVERGENCE): usable.
    assert strict.summary.is_solution_usable
    assert strict.to_dict()["summary"]["gap_fraction_of_substation"] > 1e-4
    # Further rounds (--rounds): the program's document, and never worse than none.
    more = fleet.optimise(trains=12, span_s=6000, moves=2000, rounds=1)
    cli_more = run_cli("timetable", "optimise", "--trains", "12", "--span", "6000", "--moves",
                       "2000", "--rounds", "1", "--quiet")
    assert without_wall_times(more.to_dict(), clock) == without_wall_times(cli_more, clock)
    none = fleet.optimise(trains=12, span_s=6000, moves=2000)
    assert more.substation_energy_kJ <= none.substation_energy_kJ + 1e-6
    with pytest.raises(ValueError, match="rounds"):
        fleet.optimise(trains=12, span_s=6000, rounds=-1)
    # A Fleet's study, taken for another problem, gives the free function's document.
    other = fleet.evaluate(trains=20, span_s=6000, headway_s=(120, 660))
    alone = ecorail.timetable.evaluate(line, train, trains=20, span_s=6000)
    assert other.to_dict() == alone.to_dict()
    # The pattern search (a short one): never worse than the headways alone, a result when
    # stopped by its time limit, and the Fleet keeps its own pattern.
    found = fleet.optimise(trains=12, span_s=6000, moves=2000, restarts=1, time_limit_s=2,
                           pattern=True)
    assert found.summary.is_solution_usable
    search = found.to_dict()["pattern_search"]
    assert found.substation_energy_kJ <= search["headways_only_substation_energy_kJ"] + 1e-6
    assert fleet.evaluate(trains=20, span_s=6000).to_dict() == alone.to_dict()
    with pytest.raises(ValueError, match="per_train_patterns"):
        ecorail.timetable.optimise(line, train, model="overlap", trains=12, span_s=6000,
                                   per_train_patterns=True)  # refused before any work
