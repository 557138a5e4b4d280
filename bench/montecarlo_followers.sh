#!/usr/bin/env bash
# The fast mode of the Monte Carlo's followers against the driven followers (question 3.2), paired
# by day: `ecorail montecarlo` run twice on the same plan, seed and days, with --followers
# shortcut (departures at least the separation apart, nothing re-simulated) and --followers
# driven (the default: the follower model of `ecorail delay`), and the per-day differences of
# punctuality, mean lateness, traction and substation energy with their 95 % confidence
# intervals (Student's t over the days, as the program's own statistics). Prints a Markdown
# table and each run's /usr/bin/time line (wall, user CPU, memory; the wall includes making the
# frontiers, section runs and the followers' runs, cached between runs except the last).
# Usage:
#
#   bash bench/montecarlo_followers.sh [ECORAIL] [DAY.csv] [DAYS] [SEED] [EXTRA FLAGS...]
#
# ECORAIL defaults to build/ecorail, DAY.csv to ecorail-day.csv in the temporary directory; when
# it does not exist it is made first (the 2.2 day: `timetable optimise --trains 240` with the
# peaks of docs/peak_day.md and a 150 s time limit, a few minutes). DAYS defaults to 100, SEED
# to 1; extra flags go to both montecarlo runs (e.g. --threads 2).
set -euo pipefail

bin=${1:-build/ecorail}
day=${2:-${TMPDIR:-/tmp}/ecorail-day.csv}
days=${3:-100}
seed=${4:-1}
shift $(($# < 4 ? $# : 4))
# shellcheck source=bench/day_plan.sh
. "$(dirname "$0")/day_plan.sh"
ensure_day_plan "$bin" "$day"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for mode in shortcut driven; do
  /usr/bin/time -f "$mode: %e s wall, %U s user, %M KB" "$bin" montecarlo --plan "$day" \
    --days "$days" --seed "$seed" --followers "$mode" --quiet --json "$out/$mode.json" "$@" \
    > "$out/$mode.txt" 2> "$out/$mode.time"
  tail -1 "$out/$mode.time"
done
python3 - "$out/shortcut.json" "$out/driven.json" <<'PY'
import json, math, sys

def t975(dof):
    table = [0.0, 12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201,
             2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069,
             2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]
    if dof <= 30:
        return table[dof]
    z, v = 1.959963984540054, float(dof)
    return (z + (z**3 + z) / (4 * v) + (5 * z**5 + 16 * z**3 + 3 * z) / (96 * v * v)
            + (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / (384 * v**3))

def est(xs):
    n = len(xs)
    m = sum(xs) / n
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1)) if n > 1 else 0.0
    return m, (t975(n - 1) * sd / math.sqrt(n) if n > 1 else 0.0)

fast, drv = (json.load(open(f)) for f in sys.argv[1:3])
assert fast["config"]["followers"] == "shortcut" and drv["config"]["followers"] == "driven"
fd, dd = fast["days"], drv["days"]
assert [d["day"] for d in fd] == [d["day"] for d in dd]
rows = [
    ("punctuality %", lambda d: 100.0 * d["punctual"] / d["arrivals"]),
    ("mean lateness s", lambda d: d["lateness_sum_s"] / d["arrivals"]),
    ("traction MJ/day", lambda d: d["traction_kJ"] / 1e3),
    ("substation MJ/day", lambda d: d["substation_kJ"] / 1e3),
]
print(f"{len(fd)} days, seed {fast['config']['seed']}, plan {fast['config']['plan']}, "
      f"{fast['config']['trains']} trains, recovery {fast['config']['recovery']}; "
      f"fast mode separation {fast['config']['separation_s']} s")
print("| quantity | fast mode (shortcut) | driven followers | fast - driven, paired by day |")
print("|---|---|---|---|")
for name, f in rows:
    a, b = [f(d) for d in fd], [f(d) for d in dd]
    ma, ca = est(a)
    mb, cb = est(b)
    md, cd = est([x - y for x, y in zip(a, b)])
    print(f"| {name} | {ma:.4f} +- {ca:.4f} | {mb:.4f} +- {cb:.4f} | {md:+.4f} +- {cd:.4f} |")
held = [d.get("followers_held_up", 0) for d in dd]
knock_f = [d["knock_on_delays"] for d in fd]
knock_d = [d["knock_on_delays"] for d in dd]
gaps = [d["min_follower_gap_m"] for d in dd if "min_follower_gap_m" in d]
margins = [d["min_follower_margin_m"] for d in dd if "min_follower_margin_m" in d]
m, c = est(held)
print(f"driven: {m:.2f} +- {c:.2f} trains held up a day; departures held: fast mode "
      f"{est(knock_f)[0]:.2f} a day, driven {est(knock_d)[0]:.2f} a day; least gap of a held-up "
      f"follower {min(gaps) if gaps else float('nan'):.2f} m, least margin beyond its braking "
      f"distance {min(margins) if margins else float('nan'):.3f} m")
PY
