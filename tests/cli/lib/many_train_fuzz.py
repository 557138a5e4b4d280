"""Property harness of the many-train commands (run by tests/cli/many_train_fuzz.sh).

Random inputs from a fixed seed, so a failure is reproducible: plans written by `timetable
evaluate` and then perturbed, primary delays on them (`delay`), power-supply files mutated field
by field (`timetable evaluate --model network`) and Monte Carlo shards mutated before `montecarlo
merge`. Whatever the input, these must hold:
  - no crash: the exit code is 0, 1 (a flagged failure, said on stderr) or 2 (bad input, one
    line on stderr), never a signal;
  - nothing half-written: a run that does not exit 0 leaves no output file;
  - no input modified: every input file has the same SHA-256 before and after the run;
  - results in their physical ranges: followers never closer than the braking distance and
    never arriving before the train ahead; merged punctuality in [0, 1], lateness and energies
    finite and non-negative, substation energy at most the traction energy; the network day's
    energies non-negative and its train voltages ordered.
Usage: python3 many_train_fuzz.py ECORAIL CACHE_DIR [SEED]
"""

import csv
import hashlib
import json
import math
import os
import random
import subprocess
import sys

ecorail, cache_dir = sys.argv[1], sys.argv[2]
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
src = os.environ["ECORAIL_SOURCE_DIR"]
failures = []
exits = {}


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def run(args, inputs, outputs, what):
    """Runs ecorail, checks the exit code, stderr, outputs and input checksums; returns the code."""
    for out in outputs:
        if os.path.exists(out):
            os.remove(out)
    before = {p: sha256(p) for p in inputs}
    proc = subprocess.run([ecorail] + args, capture_output=True, text=True)
    code = proc.returncode
    exits[code] = exits.get(code, 0) + 1
    for p in inputs:
        if sha256(p) != before[p]:
            failures.append(f"{what}: input {p} modified")
    if code not in (0, 1, 2):
        failures.append(f"{what}: exit {code} (a crash?): {' '.join(args)}\n{proc.stderr[-2000:]}")
        return code
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    if code == 2 and len(lines) != 1:
        failures.append(f"{what}: exit 2 with {len(lines)} lines of error: {' '.join(args)}\n"
                        f"{proc.stderr[-2000:]}")
    if code == 1 and not lines:
        failures.append(f"{what}: exit 1 without a word on stderr: {' '.join(args)}")
    if code != 0:
        left = [o for o in outputs if os.path.exists(o)]
        if left:
            failures.append(f"{what}: exit {code} left {left}: {' '.join(args)}")
    else:
        missing = [o for o in outputs if not os.path.exists(o)]
        if missing:
            failures.append(f"{what}: exit 0 without {missing}: {' '.join(args)}")
    return code


def finite_nonnegative(x):
    return isinstance(x, (int, float)) and math.isfinite(x) and x >= 0


rng = random.Random(seed)
cache = ["--cache-dir", cache_dir, "--frontier-span", "30"]

# --- Random plans and delays: the driven knock-on chain keeps its separation and order. ---
for case in range(4):
    trains = rng.randint(2, 5)
    span = rng.choice([240, 360, 480, 600, 900])
    trip = rng.choice([370, 380, 400, 420])
    plan = f"plan{case}.csv"
    code = run(["timetable", "evaluate", "--from", "A6", "--to", "A9", "--trip-time", str(trip),
                "--trains", str(trains), "--span", str(span), "--headway", "60:900", "--csv", plan,
                "--quiet"], [], [plan], f"plan {case}")
    if code != 0:
        continue
    rows = list(csv.DictReader(open(plan)))
    arrival = {}
    for r in rows:
        arrival.setdefault(int(r["train"]), {})[r["station"]] = float(r["arrival_s"])
    for trial in range(2):
        train = rng.randint(1, trains - 1)
        station = rng.choice(["A6", "A7", "A8"])
        delay = rng.choice([5, 30, 120, 600, 3000])
        followers = rng.randint(1, 3)
        what = f"delay plan {case} train {train} at {station} +{delay} s, {followers} followers"
        code = run(["delay", "--plan", plan, "--train", str(train), "--station", station,
                    "--delay", str(delay), "--followers", str(followers), "--json", "d.json",
                    "--quiet"] + cache, [plan], ["d.json"], what)
        if code != 0:
            continue
        d = json.load(open("d.json"))
        for f in d["followers"]:
            # Both are null for a follower that is never on the line with the train ahead.
            gap, margin = f["min_gap_m"], f["min_distance_margin_m"]
            if (gap is None) != (margin is None) or (gap is not None and min(gap, margin) < -0.01):
                failures.append(f"{what}: follower {f['train']} inside the braking distance: {f}")
        lateness = {t["train"]: t["lateness_s"] for t in d["trains"]}
        for j, st in enumerate(d["stations"][1:], start=1):
            order = sorted(lateness)
            times = [arrival[k][st] + lateness[k][j] for k in order]
            if any(a >= b for a, b in zip(times, times[1:])):
                failures.append(f"{what}: arrivals at {st} out of order: {list(zip(order, times))}")
    # A perturbed plan: either refused as bad input or run with the same invariants.
    bad = f"bad{case}.csv"
    lines = open(plan).read().splitlines()
    k = rng.randrange(1, len(lines))
    fields = lines[k].split(",")
    j = rng.choice([3, 4, 7])
    fields[j] = rng.choice(["-5", "nan", "1e300", "", "x", str(float(fields[j]) - 400)])
    lines[k] = ",".join(fields)
    open(bad, "w").write("\n".join(lines) + "\n")
    run(["delay", "--plan", bad, "--train", "1", "--station", "A7", "--delay", "30", "--json",
         "b.json", "--quiet"] + cache, [bad], ["b.json"], f"perturbed plan {case} row {k}")

# --- Monte Carlo shards, valid and tampered: merged statistics stay in their ranges. ---
mc = ["montecarlo", "--plan", "plan0.csv", "--days", "4", "--seed", str(seed), "--quiet",
      "--knot-step", "5"] + cache
shards = []
if os.path.exists("plan0.csv"):
    for i in (1, 2):
        if run(mc + ["--shard", f"{i}/2", "--json", f"s{i}.json"], ["plan0.csv"], [f"s{i}.json"],
               f"shard {i}") == 0:
            shards.append(f"s{i}.json")


def check_merged(path, what):
    s = json.load(open(path))["statistics"]
    p = s["punctuality"]["mean"]
    if not (0 <= p <= 1):
        failures.append(f"{what}: punctuality {p}")
    for key in ["mean_lateness_s", "p95_lateness_s", "traction_kJ", "substation_kJ"]:
        if not finite_nonnegative(s[key]["mean"]):
            failures.append(f"{what}: {key} {s[key]['mean']}")
    if s["substation_kJ"]["mean"] > s["traction_kJ"]["mean"] * (1 + 1e-9):
        failures.append(f"{what}: substation above traction")


if len(shards) == 2:
    if run(["montecarlo", "merge"] + shards + ["--json", "m.json"], shards, ["m.json"],
           "merge") == 0:
        check_merged("m.json", "merge")
    base = json.load(open("s1.json"))
    for trial in range(12):
        d = json.loads(json.dumps(base))
        day = rng.randrange(len(d["days"]))
        key = rng.choice(sorted(d["days"][day]))
        d["days"][day][key] = rng.choice([-1, 0, 1e300, 10**12, 0.5, None, "x", [], -1e-9])
        if rng.random() < 0.3:
            d["checksum"] = rng.choice(["", "0", d["checksum"], 17])
        text = json.dumps(d)
        if rng.random() < 0.2:
            text = text[: rng.randrange(1, len(text))]
        open("t.json", "w").write(text)
        what = f"tampered shard: day {day} {key}"
        if run(["montecarlo", "merge", "t.json", "s2.json", "--json", "m.json"],
               ["t.json", "s2.json"], ["m.json"], what) == 0:
            check_merged("m.json", what)

# --- Power-supply files mutated field by field. ---
supply = os.path.join(src, "data", "contest", "power_supply.toml")
small = ["timetable", "evaluate", "--from", "A6", "--to", "A9", "--trains", "4", "--span", "600",
         "--headway", "150:250", "--trip-time", "480", "--model", "network", "--quiet"]
lines = open(supply).read().splitlines()
values = [i for i, ln in enumerate(lines) if "=" in ln and not ln.lstrip().startswith("#")]
for trial in range(8):
    mutated = list(lines)
    i = rng.choice(values)
    name, _, _ = mutated[i].partition("=")
    kind = rng.randrange(4)
    if kind == 0:
        mutated[i] = name + "= " + rng.choice(["-1.0", "0.0", "1e308", "nan", "inf", '"x"', "[",
                                               "-0.0", "1e-300"])
    elif kind == 1:
        del mutated[i]
    elif kind == 2:
        mutated.insert(i, "unknown_key = 1.0")
    else:
        mutated = "\n".join(mutated)[: rng.randrange(1, len("\n".join(mutated)))].splitlines()
    open("supply.toml", "w").write("\n".join(mutated) + "\n")
    what = f"supply mutation {trial} (kind {kind}, line {i + 1})"
    if run(small + ["--power-supply", "supply.toml", "--json", "n.json"], ["supply.toml"],
           ["n.json"], what) == 0:
        n = json.load(open("n.json"))
        for key in ["substation_energy_kJ", "used_regen_kJ", "curtailed_regen_kJ",
                    "line_losses_kJ", "traction_input_kJ"]:
            if not finite_nonnegative(n[key]):
                failures.append(f"{what}: {key} {n[key]}")
        if not n["min_train_voltage_V"] <= n["max_train_voltage_V"]:
            failures.append(f"{what}: train voltages out of order")
        if n["used_regen_kJ"] > n["regen_energy_kJ"] * (1 + 1e-9):
            failures.append(f"{what}: more regenerated energy used than regenerated")

for f in failures:
    print("FAIL:", f)
print(f"many_train_fuzz (seed {seed}): runs by exit code {dict(sorted(exits.items()))}, "
      f"{len(failures)} failures")
sys.exit(1 if failures else 0)
