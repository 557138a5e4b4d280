#!/usr/bin/env bash
# The three plans of question 3.2 on the same days (common random numbers), as a table:
#   (a) the plan with the seed paper's rule, (b) the plan with exact recovery,
#   (c) the adjusted plan with exact recovery.
# Usage: scripts/montecarlo_compare.sh ECORAIL PLAN.csv ADJUSTED.csv RUN_EARLY_S [DAYS] [SEED]
#        [extra montecarlo options...]
# Writes a.json, b.json, c.json (and the plots a_*.svg, b_*.svg, c_*.svg) in the current
# directory and prints a Markdown table: mean +- 95 % confidence half-width over the days.
set -euo pipefail
ecorail="$1"; plan="$2"; adjusted="$3"; run_early="$4"; days="${5:-1000}"; seed="${6:-1}"
shift $(( $# < 6 ? $# : 6 ))
common=(--days "$days" --seed "$seed" --quiet "$@")
"$ecorail" montecarlo --plan "$plan" --recovery rule "${common[@]}" --json a.json --svg-prefix a
"$ecorail" montecarlo --plan "$plan" --recovery exact "${common[@]}" --json b.json --svg-prefix b
"$ecorail" montecarlo --plan "$adjusted" --recovery exact --run-early "$run_early" \
  "${common[@]}" --json c.json --svg-prefix c
python3 - <<'PY'
import json
rows = [("(a) 2.2 plan, rule", "a.json"), ("(b) 2.2 plan, exact", "b.json"),
        ("(c) adjusted plan, exact", "c.json")]
def f(e, scale=1.0, digits=2):
    return f"{e['mean'] * scale:.{digits}f} +- {e['ci95'] * scale:.{digits}f}"
print("| plan | days | punctuality % | mean lateness s | p95 lateness s | recovery time s |"
      " traction GJ | substation GJ | plan substation GJ | taken over / day |")
print("|---|---|---|---|---|---|---|---|---|---|")
for name, path in rows:
    d = json.load(open(path))
    s = d["statistics"]
    print(f"| {name} | {s['days']} | {f(s['punctuality'], 100, 3)} | {f(s['mean_lateness_s'], 1, 3)} |"
          f" {f(s['p95_lateness_s'])} | {f(s['recovery_time_s'])} | {f(s['traction_kJ'], 1e-6, 4)} |"
          f" {f(s['substation_kJ'], 1e-6, 4)} | {d['plan_energy']['substation_kJ'] * 1e-6:.4f} |"
          f" {f(s['takeovers'])} |")
a, b, c = (json.load(open(p))["days"] for p in ("a.json", "b.json", "c.json"))
import math
def paired(x, y, key):
    diff = [u[key] - v[key] for u, v in zip(x, y)]
    n = len(diff); m = sum(diff) / n
    sd = math.sqrt(sum((t - m) ** 2 for t in diff) / (n - 1)) if n > 1 else 0.0
    return m, 1.96 * sd / math.sqrt(n) if n > 1 else 0.0
for label, x, y in [("(a) - (b)", a, b), ("(c) - (b)", c, b)]:
    m, h = paired(x, y, "substation_kJ")
    mt, ht = paired(x, y, "traction_kJ")
    print(f"\n{label} per day, paired on the same days: substation {m * 1e-3:.1f} +- {h * 1e-3:.1f} MJ,"
          f" traction {mt * 1e-3:.1f} +- {ht * 1e-3:.1f} MJ")
PY
