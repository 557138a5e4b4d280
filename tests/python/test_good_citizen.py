"""The module as a good citizen of the interpreter: bad values raise ValueError naming the
argument (the library's IsValid sentence for options), the GIL is released during a solve,
threads do not change results, Ctrl-C (KeyboardInterrupt) stops a long solve between stages and
leaves the interpreter usable, a progress callback that raises stops the solve with its error,
and help() is readable."""

import _thread
import threading
import time

import pytest

import ecorail
from conftest import without_wall_times


@pytest.mark.parametrize("kwargs, field", [
    ({"ds_m": -1.0}, "ds_m"),
    ({"dv_kmh": 50.0}, "dv_kmh"),
    ({"threads": 5000}, "threads"),
    ({"objective": "speed"}, "objective"),
    ({"cruise": "fast"}, "cruise"),
    ({"time_s": 60.0}, "time_s"),
    ({"time_s": -5.0}, "time_s"),
    ({"min_regime_m": -3.0}, "min_length_m"),
])
def test_bad_options_raise_value_error_naming_the_field(reference, kwargs, field):
    line, train = reference
    args = {"from_": "A6", "to": "A7", "time_s": 110.0}
    args.update(kwargs)
    with pytest.raises(ValueError, match=field):
        ecorail.solve(line, train, **args)


def test_time_below_minimum_names_the_minimum(reference):
    line, train = reference
    with pytest.raises(ValueError, match=r"minimum running time of 85\.47 s for A6 -> A7"):
        ecorail.solve(line, train, from_="A6", to="A7", time_s=60)


def test_bad_stations_and_dwells(reference):
    line, train = reference
    with pytest.raises(ValueError, match="ZZ"):
        ecorail.solve(line, train, from_="ZZ", to="A7", time_s=110)
    with pytest.raises(ValueError, match="dwell"):
        ecorail.solve(line, train, from_="A6", to="A8", time_s=220)  # A7 has no dwell
    with pytest.raises(ValueError, match="dwell"):
        ecorail.solve(line, train, from_="A6", to="A8", time_s=220, dwell={"A7": -1})
    with pytest.raises(ValueError, match="pass_through"):
        ecorail.solve(line, train, from_="A6", to="A7", time_s=110, pass_through=["A9"])
    with pytest.raises(ValueError, match="split"):
        ecorail.solve(line, train, from_="A6", to="A8", time_s=220, dwell=30, split="even")
    with pytest.raises(ValueError, match="step_s"):
        ecorail.frontier(line, train, from_="A6", to="A7", step_s=0)
    with pytest.raises(ValueError, match="tmin_s"):
        ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=50, tmax_s=100)


def test_bad_files_raise_value_error_naming_the_file(tmp_path):
    missing = tmp_path / "none.toml"
    with pytest.raises(ValueError, match="none.toml"):
        ecorail.Line.from_file(missing)
    bad = tmp_path / "bad.toml"
    bad.write_text("[train]\nmass_t = 'heavy'\n")
    with pytest.raises(ValueError, match="bad.toml"):
        ecorail.Train.from_file(bad)
    with pytest.raises(ValueError, match="kind"):
        ecorail.fit_envelope(bad, kind="sideways")
    with pytest.raises(ValueError, match="loss_scale"):
        ecorail.calibrate([bad], loss_scale=0)


def test_threads_do_not_change_the_result(reference):
    line, train = reference
    one = ecorail.solve(line, train, from_="A6", to="A7", time_s=110, threads=1).to_dict()
    two = ecorail.solve(line, train, from_="A6", to="A7", time_s=110, threads=2).to_dict()
    assert one.pop("threads") == 1 and two.pop("threads") == 2
    assert without_wall_times(one) == without_wall_times(two)


def test_gil_is_released_during_a_solve(reference):
    """While another thread solves, this one keeps running Python: with the GIL held for the
    whole solve the loop below would not advance until the solve ends."""
    line, train = reference
    done = threading.Event()
    result = {}

    # 31 running times: about 0.4 s on an idle machine (5 took 50 ms, less than the wait below,
    # so the loop never ran: the solve must outlast the wait by far).
    def work():
        result["run"] = ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=100,
                                         tmax_s=130, threads=1)
        done.set()

    t = threading.Thread(target=work)
    ticks_during = 0
    t.start()
    time.sleep(0.05)  # the worker is inside the library by now
    while not done.is_set():
        ticks_during += 1
        time.sleep(0.001)
    t.join()
    assert len(result["run"].target_time_s) == 31
    assert ticks_during >= 20, f"main thread advanced only {ticks_during} times during the solve"


def test_keyboard_interrupt_stops_a_long_solve_and_the_interpreter_stays_usable(reference):
    line, train = reference
    # A frontier of 81 points takes 2.6 s on the idle 2-core machine (61 took 1.2 s: too near the
    # 0.5 s after which Ctrl-C arrives on a faster machine); only the first 0.5 s of it runs.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=100, tmax_s=180, threads=1)
    finally:
        timer.cancel()
    stopped_after = time.monotonic() - start
    full = time.monotonic()
    ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=100, tmax_s=104, threads=1)
    five_points = time.monotonic() - full
    # Stopped between points: well before the 81 points were done.
    assert stopped_after < 0.5 + 4 * five_points
    # The interpreter and the module still work, with the same answer as ever.
    r = ecorail.solve(line, train, from_="A6", to="A7", time_s=110)
    assert f"{r.traction_energy_kJ:.1f}" == "34898.0"


def test_a_progress_callback_that_raises_stops_the_solve(reference):
    line, train = reference
    calls = []

    def progress(stage, done, total):
        calls.append((stage, done, total))
        if len(calls) == 2:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        ecorail.frontier(line, train, from_="A6", to="A7", tmin_s=100, tmax_s=130,
                         progress=progress)
    assert len(calls) == 2 and calls[0][0] in ("point", "lambda evaluation")


def test_help_and_docstrings_name_units():
    doc = ecorail.solve.__doc__
    assert "time_s" in doc and "from_" in doc and "ValueError" in doc
    assert "kJ" in ecorail.Run.traction_energy_kJ.__doc__
    assert "m/s" in ecorail.Run.speed_ms.__doc__
    assert ecorail.__doc__ and "docs/python.md" in ecorail.__doc__


def test_type_stubs_name_every_public_name():
    """The .pyi stubs editors read name every public class and function of the module, and the
    members of its classes."""
    import ast
    import inspect
    import os

    stub = os.path.join(os.path.dirname(ecorail.__file__), "_ecorail.pyi")
    tree = ast.parse(open(stub).read())
    top = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    public = {n for n in dir(ecorail._ecorail) if not n.startswith("_")}
    assert public <= top, public - top
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for name in public:
        obj = getattr(ecorail._ecorail, name)
        if inspect.isclass(obj) and name in classes and not issubclass(obj, BaseException):
            stubbed = {m.name for m in classes[name].body if isinstance(m, ast.FunctionDef)}
            stubbed |= {m.target.id for m in classes[name].body if isinstance(m, ast.AnnAssign)}
            members = {m for m in vars(obj) if not m.startswith("_")}
            if issubclass(obj, __import__("enum").Enum) or hasattr(obj, "__members__"):
                continue
            assert members <= stubbed, (name, members - stubbed)


def test_another_cpython_of_the_same_version_imports_the_module():
    """docs/python.md: another CPython 3.X on PATH loads the extension and, without numpy of its
    own, gets Debian's numpy when that was built for its extension suffix."""
    import os
    import shutil
    import subprocess
    import sys

    other = shutil.which("python3")
    if not other or os.path.realpath(other) == os.path.realpath(sys.executable):
        pytest.skip("no other python3 on PATH")
    probe = subprocess.run([other, "-c", "import sys; print(sys.version_info[:2])"],
                           capture_output=True, text=True)
    if probe.stdout.strip() != str(tuple(sys.version_info[:2])):
        pytest.skip(f"{other} is another minor version ({probe.stdout.strip()})")
    code = ("import ecorail, numpy; r = ecorail.solve(ecorail.Line.reference(), "
            "ecorail.Train.reference(), from_='A6', to='A7', time_s=110); "
            "assert isinstance(r.speed_ms, numpy.ndarray); print(f'{r.traction_energy_kJ:.1f}')")
    proc = subprocess.run([other, "-c", code], capture_output=True, text=True,
                          env=dict(os.environ))
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "34898.0"
