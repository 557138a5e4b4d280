#!/usr/bin/env bash
# Command-line errors name the one flag at fault and say "expected" once: integers are read
# strictly (a seed of 2^64 is refused, not clamped to 2^64 - 1; -1 for an unsigned flag, 0x10
# and 1e3 for an integer are refused), a library option refused by its IsValid is reported on
# the flag that set it (not as "invalid options: t_min_s must ..."), a ladder rung the engine
# cannot solve blames --lambda-ladder (not --time), a missing station names --from or --to
# alone.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

# one_flag NEEDLE ARGS...: expect_error, and the message names one flag and says "expected" once.
one_flag() {
  expect_error "$@"
  [ "$(grep -o expected stderr.txt | wc -l)" -le 1 ] ||
    { echo "FAIL: 'expected' more than once: ${*:2}"; cat stderr.txt; fail=1; }
  ! grep -q "field '--[a-z-]*/--" stderr.txt ||
    { echo "FAIL: several flags named at once: ${*:2}"; cat stderr.txt; fail=1; }
  ! grep -q "Options::" stderr.txt || { echo "FAIL: internal names: ${*:2}"; cat stderr.txt; fail=1; }
}

one_flag "--seed" timetable optimise --seed 18446744073709551616
one_flag "--seed" timetable optimise --seed -1
one_flag "--threads" solve --from A6 --to A7 --time 110 --threads 0x10
one_flag "--threads" solve --from A6 --to A7 --time 110 --threads 1e3
one_flag "--threads" solve --from A6 --to A7 --time 110 --threads 99999999999999999999
one_flag "--lambda-ladder" policy --from A6 --to A7 --time 110 --lambda-ladder 0,1e308 --out p.bin
one_flag "--braking" timetable evaluate --trains 2 --span 645 --separation --braking 11
one_flag "--train-length" timetable evaluate --trains 2 --span 645 --separation --train-length 5000
one_flag "--tmin" frontier --from A6 --to A7 --tmin -5
one_flag "--min-regime-m" solve --from A6 --to A7 --time 110 --min-regime-m -1
one_flag "--from" frontier --to A7
one_flag "--to" policy --from A6 --time 110 --out p.bin

# A leading zero is decimal, not octal: --trains 010 is ten trains.
"$ecorail" timetable evaluate --from A6 --to A9 --trains 010 --span 1800 --headway 150:250 \
  --trip-time 480 --csv tt.csv > /dev/null 2> err.txt || { echo "FAIL: --trains 010"; cat err.txt; fail=1; }
[ -f tt.csv ] && [ "$(cut -d, -f1 tt.csv | sort -u | grep -c '^[0-9]')" -eq 10 ] ||
  { echo "FAIL: --trains 010 is not ten trains"; fail=1; }
# The search's options are refused on the one flag at fault, "expected" said once.
for bad_flag in "--rounds -1" "--restarts 5000" "--gap 2" "--anneal-step 0.3"; do
  set -- $bad_flag
  expect_error "field '$1': expected" timetable optimise --trains 6 --span 1500 "$1" "$2" --json o.json
  grep -q "expected.*expected\|/--" stderr.txt && { echo "FAIL: $bad_flag: $(cat stderr.txt)"; fail=1; }
done
exit "$fail"
