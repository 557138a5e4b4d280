#!/usr/bin/env bash
# Outputs under faults: a full disk and a read-only file system give one line naming
# the output and the cause, a non-zero exit and no file (no truncated SVG with exit 0, no raw
# libxlsxwriter or gnuplot text); /dev/full is never replaced; a run killed with SIGKILL while
# it writes leaves no temporary file (outputs are anonymous O_TMPFILE files until committed), no
# partial output and no gnuplot behind it, and its plot directory is removed by the next plot.
# The file-system parts need root (mount -t tmpfs); they are skipped, and said so, without it.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
trap 'umount "$work/full" 2> /dev/null; umount "$work/ro" 2> /dev/null; rm -rf "$work"' EXIT

run=(solve --from A6 --to A7 --time 110)

# One line, a non-zero exit, the output named, nothing left in the directory but what was there.
expect_fault() {
  local dir="$1" needle="$2"
  shift 2
  local before
  before=$(ls -A "$dir" | sort)
  "$ecorail" "$@" > /dev/null 2> err.txt
  local code=$?
  if [ "$code" -eq 0 ]; then
    echo "FAIL: exit 0 on a fault: $*"; fail=1
  elif [ "$(grep -c . err.txt)" -ne 1 ] || ! grep -qF -- "$needle" err.txt; then
    echo "FAIL: want one line with '$needle': $*"; cat err.txt; fail=1
  fi
  if [ "$(ls -A "$dir" | sort)" != "$before" ]; then
    echo "FAIL: files left in $dir: $(ls -A "$dir" | tr '\n' ' ')"; fail=1
  fi
}

mkdir full ro
if mount -t tmpfs -o size=64k tmpfs full 2> /dev/null; then
  dd if=/dev/zero of=full/fill bs=4k count=64 2> /dev/null  # fills it: "No space left"
  expect_fault full "full/a.csv" "${run[@]}" --csv full/a.csv
  expect_fault full "full/a.json" "${run[@]}" --json full/a.json
  expect_fault full "full/a.xlsx" "${run[@]}" --xlsx full/a.xlsx
  if command -v gnuplot > /dev/null; then
    expect_fault full "full/a.svg" "${run[@]}" --plot full/a.svg
  fi
  mount -t tmpfs -o size=64k,ro tmpfs ro
  expect_fault ro "'ro' is not writable" "${run[@]}" --csv ro/a.csv --json ok.json
  [ ! -e ok.json ] || { echo "FAIL: ok.json written though ro/a.csv failed"; fail=1; }
else
  echo "output_faults: not root (no tmpfs mount): full-disk and read-only checks skipped"
fi

# /dev/full is a device: refused, never replaced by a file.
"$ecorail" "${run[@]}" --json /dev/full > /dev/null 2>&1
[ -c /dev/full ] || { echo "FAIL: /dev/full is no longer a device"; fail=1; }

# SIGKILL while writing: kill at spread times around the end of a run with four outputs.
mkdir k
args=(solve --from A6 --to A7 --time 110 --csv k/a.csv --json k/a.json --xlsx k/a.xlsx)
command -v gnuplot > /dev/null && args+=(--plot k/a.svg)
start=$(date +%s%N)
"$ecorail" "${args[@]}" > /dev/null 2>&1 || { echo "FAIL: the run itself failed"; fail=1; }
full_ms=$((($(date +%s%N) - start) / 1000000))
for frac in 70 85 92 96 98 100 102; do
  rm -f k/*
  "$ecorail" "${args[@]}" > /dev/null 2>&1 &
  pid=$!
  sleep "$(awk -v t="$full_ms" -v f="$frac" 'BEGIN { printf "%.3f", t * f / 100000 }')"
  kill -9 "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  sleep 0.2
  if ls -A k | grep -q "tmp"; then
    echo "FAIL: temporary files after SIGKILL at ${frac} %: $(ls -A k | tr '\n' ' ')"; fail=1
  fi
  [ ! -e k/a.json ] || python3 -c "import json,sys; json.load(open('k/a.json'))" ||
    { echo "FAIL: partial JSON after SIGKILL at ${frac} %"; fail=1; }
  [ ! -e k/a.svg ] || grep -q "</svg>" k/a.svg ||
    { echo "FAIL: partial SVG after SIGKILL at ${frac} %"; fail=1; }
  for p in /proc/[0-9]*; do
    if readlink "$p/cwd" 2> /dev/null | grep -q "ecorail-plot-$pid-"; then
      echo "FAIL: gnuplot of killed $pid still running"; fail=1
    fi
  done
  last=$pid
done
# The next plot removes the directories of killed runs.
if command -v gnuplot > /dev/null; then
  "$ecorail" "${run[@]}" --plot k/b.svg > /dev/null 2>&1
  if ls -d "${TMPDIR:-/tmp}"/ecorail-plot-"$last"-* > /dev/null 2>&1; then
    echo "FAIL: plot directory of killed run $last left behind"; fail=1
  fi
fi

[ "$fail" -eq 0 ] && echo "output_faults: ok (full run ${full_ms} ms)"
exit "$fail"
