#!/usr/bin/env bash
# `ecorail montecarlo` end to end on a small plan (A6 -> A9, four trains, written by
# `ecorail timetable evaluate --csv`): JSON, CSV and the three SVGs with the documented keys
# and sane values; the statistics JSON byte for byte the same for 1 thread, 2 threads, two
# shards merged and (when ecorail-montecarlo-mpi was built) `mpirun -np 2`; --adjust writes a
# plan that montecarlo reads back; a progress line on a terminal only; bad input exits 2 with
# one line and no file left behind.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
export XDG_CACHE_HOME="$work/xdg"
mkdir -p "$XDG_CACHE_HOME"
# Frontiers and section runs kept in the build tree between runs of this script.
cache=(--cache-dir "$(dirname "$ecorail")/test-cache/montecarlo-cli" --frontier-span 30
  --knot-step 5)

"$ecorail" timetable evaluate --from A6 --to A9 --trip-time 380 --trains 4 --span 600 \
  --headway 120:660 --csv plan.csv --quiet > /dev/null || { echo "FAIL: plan"; fail=1; }
run=(montecarlo --plan plan.csv --days 12 --seed 4 "${cache[@]}" --quiet)

"$ecorail" "${run[@]}" --threads 1 --json t1.json --csv t1.csv --svg-prefix p > t1.txt \
  || { echo "FAIL: montecarlo"; cat t1.txt; fail=1; }
for f in t1.json t1.csv p_lateness.svg p_energy.svg p_punctuality.svg; do
  [ -s "$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
grep -q "ecorail montecarlo days 0-11: punctuality" t1.txt || { echo "FAIL: report"; cat t1.txt; fail=1; }
grep -q "followers driven under the cap" t1.txt || { echo "FAIL: driven not said"; fail=1; }
# The fast mode says so in its report and its config.
"$ecorail" "${run[@]}" --followers shortcut --json fast.json > fast.txt \
  || { echo "FAIL: --followers shortcut"; fail=1; }
grep -q "followers in the fast mode" fast.txt || { echo "FAIL: fast mode not labelled"; fail=1; }
grep -q '"followers": "shortcut"' fast.json || { echo "FAIL: fast mode not in config"; fail=1; }
python3 - <<'PY' || fail=1
import csv, json
d = json.load(open("t1.json"))
for k in ["format", "config", "stations", "plan_energy", "statistics", "per_station",
          "lateness_histogram", "days"]:
    assert k in d, k
s = d["statistics"]
for k in ["punctuality", "mean_lateness_s", "p95_lateness_s", "recovery_time_s", "traction_kJ",
          "substation_kJ", "takeovers", "arrivals_taken_over", "primary_delays"]:
    assert set(s[k]) == {"mean", "ci95", "sd", "n"}, k
assert s["days"] == 12 and len(d["days"]) == 12
assert 0 < s["punctuality"]["mean"] <= 1 and s["punctuality"]["ci95"] > 0
assert s["arrivals"] + sum(x["arrivals_taken_over"] for x in d["days"]) == 12 * 4 * 3
assert s["traction_kJ"]["mean"] >= d["plan_energy"]["traction_kJ"] * 0.999
assert s["substation_kJ"]["mean"] <= s["traction_kJ"]["mean"]
assert [p["station"] for p in d["per_station"]] == ["A7", "A8", "A9"]
assert sum(d["lateness_histogram"]["counts"]) == s["arrivals"]
assert d["config"]["seed"] == 4 and d["config"]["recovery"] == "exact"
assert d["config"]["tail"] == "exponential:30"
# Followers driven by default: every day says how many were held up and how close they came.
assert d["config"]["followers"] == "driven"
assert all(x["followers_held_up"] >= 0 for x in d["days"])
assert all(x.get("min_follower_gap_m", 0.0) >= 0.0 for x in d["days"])
assert "followers_held_up" in s
rows = list(csv.DictReader(open("t1.csv")))
assert len(rows) == 12 and rows[0]["day"] == "0"
assert abs(float(rows[3]["substation_kJ"]) - d["days"][3]["substation_kJ"]) < 0.01
for f in ["p_lateness.svg", "p_energy.svg", "p_punctuality.svg"]:
    assert "<svg" in open(f).read(), f
PY

# Determinism: the same bytes for 2 threads, two shards merged, and mpirun -np 2.
"$ecorail" "${run[@]}" --threads 2 --json t2.json > /dev/null || { echo "FAIL: 2 threads"; fail=1; }
"$ecorail" "${run[@]}" --shard 1/2 --json s1.json > /dev/null || { echo "FAIL: shard 1"; fail=1; }
"$ecorail" "${run[@]}" --shard 2/2 --json s2.json > /dev/null || { echo "FAIL: shard 2"; fail=1; }
"$ecorail" montecarlo merge s2.json s1.json --json merged.json > /dev/null \
  || { echo "FAIL: merge"; fail=1; }
cmp -s t1.json t2.json || { echo "FAIL: 1 and 2 threads differ"; fail=1; }
cmp -s t1.json merged.json || { echo "FAIL: merged shards differ from the whole run"; fail=1; }
cmp -s s1.json t1.json && { echo "FAIL: a shard equals the whole run"; fail=1; }
mpi="$(dirname "$ecorail")/ecorail-montecarlo-mpi"
if [ -x "$mpi" ] && command -v mpirun > /dev/null; then
  mpirun --allow-run-as-root --oversubscribe -np 2 "$mpi" "${run[@]:1}" --threads 1 \
    --json mpi.json > mpi.txt 2>&1 || { echo "FAIL: mpirun"; cat mpi.txt; fail=1; }
  cmp -s t1.json mpi.json || { echo "FAIL: mpirun -np 2 differs from the whole run"; fail=1; }
else
  echo "SKIP: mpirun -np 2 (ecorail-montecarlo-mpi not built or mpirun missing)"
fi

# The rule on the same days (common random numbers) spends no less traction.
"$ecorail" "${run[@]}" --recovery rule --json rule.json > /dev/null || { echo "FAIL: rule"; fail=1; }
python3 - <<'PY' || fail=1
import json
e, r = json.load(open("t1.json")), json.load(open("rule.json"))
for a, b in zip(e["days"], r["days"]):
    assert a["primary_delays"] == b["primary_delays"]
    assert a["traction_kJ"] <= b["traction_kJ"] * (1 + 1e-9), (a["day"], a["traction_kJ"], b["traction_kJ"])
PY

# Punctual caps: at least the exact recovery's punctuality on the same days.
"$ecorail" "${run[@]}" --recovery exact-punctual --json capped.json > /dev/null \
  || { echo "FAIL: exact-punctual"; fail=1; }
python3 - <<'PY' || fail=1
import json
e, c = json.load(open("t1.json")), json.load(open("capped.json"))
assert c["config"]["recovery"] == "exact-punctual"
assert sum(d["punctual"] for d in c["days"]) >= sum(d["punctual"] for d in e["days"])
PY

# Plan adjustment: the chosen plan is a timetable CSV montecarlo reads; trips keep their ends
# (in the fast mode: driven followers would solve their runs again for every candidate plan).
"$ecorail" montecarlo --plan plan.csv --seed 4 "${cache[@]}" --quiet --adjust --search-days 6 \
  --followers shortcut \
  --thetas 0,1 --extra-dwells 0 --target 0.5 --adjusted-csv adj.csv --json adj.json > adj.txt \
  || { echo "FAIL: adjust"; cat adj.txt; fail=1; }
python3 - <<'PY' || fail=1
import csv, json
a = json.load(open("adj.json"))
assert len(a["candidates"]) == 2 and a["target_met"] is True
rows = list(csv.DictReader(open("adj.csv")))
base = list(csv.DictReader(open("plan.csv")))
assert len(rows) == len(base)
for x, y in zip(rows, base):
    if x["station"] in ("A6", "A9"):
        assert abs(float(x["arrival_s"]) - float(y["arrival_s"])) < 2e-3, (x, y)
PY
"$ecorail" montecarlo --plan adj.csv --days 4 "${cache[@]}" --quiet > /dev/null \
  || { echo "FAIL: the adjusted plan does not run"; fail=1; }

# A progress line on a terminal (faked with util-linux `script`), none with --quiet.
if command -v script > /dev/null; then
  tty_run="$ecorail montecarlo --plan plan.csv --days 12 --seed 4 ${cache[*]}"
  script -qec "$tty_run 2>&1 >/dev/null" /dev/null > tty.txt || { echo "FAIL: on a tty"; fail=1; }
  grep -q "ecorail montecarlo: " tty.txt || { echo "FAIL: no progress on a terminal"; cat -v tty.txt; fail=1; }
  script -qec "$tty_run --quiet 2>&1 >/dev/null" /dev/null > quiet.txt || { echo "FAIL: --quiet on a tty"; fail=1; }
  if grep -q "ecorail montecarlo:" quiet.txt; then echo "FAIL: progress despite --quiet"; fail=1; fi
else
  echo "SKIP: progress on a terminal (no util-linux script)"
fi

# Bad input: exit 2, one line, nothing written.
expect_error "--shard" "${run[@]}" --shard 3/2 --json x.json
expect_error "--shard" "${run[@]}" --shard 0/2 --json x.json
expect_error "--shard" "${run[@]}" --shard two --json x.json
expect_error "--days" montecarlo --plan plan.csv --days 0 --json x.json
expect_error "--followers" montecarlo --plan plan.csv --days 2 --followers fast --json x.json
expect_error "--tail" "${run[@]}" --tail gamma:3 --json x.json
expect_error "--recovery" "${run[@]}" --recovery fast --json x.json
expect_error "--plan/--reference" montecarlo --days 3 --json x.json
expect_error "nothere.csv" montecarlo --plan nothere.csv --days 3 --json x.json
expect_error "--svg-prefix" "${run[@]}" --svg-prefix nodir/p
expect_error "days" montecarlo merge s1.json --json x.json
expect_error "--early" "${run[@]}" --early -1 --json x.json
expect_error "--run-early" "${run[@]}" --run-early 11 --json x.json
# Off a terminal, one line per stage on stderr.
"$ecorail" montecarlo --plan plan.csv --days 2 --seed 4 "${cache[@]}" > /dev/null 2> stages.txt \
  || { echo "FAIL: stages run"; fail=1; }
grep -qx "ecorail montecarlo: day" stages.txt || { echo "FAIL: no stage line"; cat stages.txt; fail=1; }
[ "$(grep -c . stages.txt)" -le 4 ] || { echo "FAIL: more than a line per stage"; cat stages.txt; fail=1; }
# Messages name the flag, never the library's options field.
"$ecorail" "${run[@]}" --early -1 --json x.json 2> err.txt
grep -q "MonteCarloOptions\|early_s" err.txt && { echo "FAIL: internal name"; cat err.txt; fail=1; }
# A tampered shard (a day with more punctual arrivals than arrivals, traction -1e300 kJ) is
# refused naming that file, not merged into a punctuality above 1.
python3 - <<'PY'
import json
d = json.load(open("s1.json"))
d["days"][0]["punctual"] = d["days"][0]["arrivals"] + 5
d["days"][0]["traction_kJ"] = -1e300
json.dump(d, open("tampered.json", "w"))
PY
expect_error "tampered.json" montecarlo merge tampered.json s2.json --json x.json
# A shard that repeats another's days is refused naming it.
cp s1.json again.json
expect_error "again.json" montecarlo merge s1.json again.json s2.json --json x.json
# An empty shard is refused, not reported as "days 1-0" with zeros.
expect_error "--shard" montecarlo --plan plan.csv --days 3 --shard 5/10 "${cache[@]}" --json x.json
# Days whose records cannot fit in memory are refused before anything is allocated.
expect_error "--days" montecarlo --plan plan.csv --days 100000000 "${cache[@]}" --json x.json
exit $fail
