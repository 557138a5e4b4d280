#!/usr/bin/env bash
# Question 2.1 on the reference case in every energy model: the published headways (50 x 641 s
# then 49 x 650 s), the uniform timetable and the optimum, with the optimum's saving over both.
# Prints a Markdown table (the one in README.md and docs/fleet.md).
# Usage: scripts/fleet_reference_table.sh [ECORAIL] [extra optimise options...]
set -euo pipefail
ecorail=${1:-build/ecorail}
shift || true
here=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
models=("power-flow" "overlap --overlap ahead" "overlap --overlap either" "sections --sections-at 6971,14474")
i=0
for m in "${models[@]}"; do
  # shellcheck disable=SC2086
  "$ecorail" timetable evaluate --model $m --quiet --headways "$here/data/contest/published_headways_2_1.csv" --json "$tmp/$i.pub.json" > /dev/null
  # shellcheck disable=SC2086
  "$ecorail" timetable evaluate --model $m --quiet --uniform --json "$tmp/$i.uni.json" > /dev/null
  # shellcheck disable=SC2086
  "$ecorail" timetable optimise --model $m --quiet "$@" --json "$tmp/$i.opt.json" > /dev/null
  i=$((i + 1))
done
python3 - "$tmp" "${models[@]}" <<'PY'
import json, sys
d, models = sys.argv[1], sys.argv[2:]
print("| model | published 641/650 s: substation kJ | uniform: substation kJ | optimum: substation kJ (used regen kJ) | saving vs published | saving vs uniform | certificate |")
print("|---|---|---|---|---|---|---|")
for i, m in enumerate(models):
    pub, uni, opt = (json.load(open(f"{d}/{i}.{k}.json")) for k in ("pub", "uni", "opt"))
    s = opt["substation_energy_kJ"]
    cert = opt["summary"]["method"]
    if "gap_fraction_of_substation" in opt and not opt["summary"]["exact"]:
        cert += f"; bound {opt['bound_used_regen_kJ']:.1f} kJ used, gap {100*opt['gap_fraction_of_substation']:.2f} %"
    print(f"| {m} | {pub['substation_energy_kJ']:.1f} | {uni['substation_energy_kJ']:.1f} | {s:.1f} ({opt['used_regen_kJ']:.1f}) | "
          f"{pub['substation_energy_kJ']-s:.1f} kJ ({100*(pub['substation_energy_kJ']-s)/pub['substation_energy_kJ']:.2f} %) | "
          f"{uni['substation_energy_kJ']-s:.1f} kJ ({100*(uni['substation_energy_kJ']-s)/uni['substation_energy_kJ']:.2f} %) | {cert} |")
PY
