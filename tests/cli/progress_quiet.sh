#!/usr/bin/env bash
# Progress lines go to stderr only when it is a terminal and --quiet is not given: a pipe or a
# file never sees them; a terminal (faked with util-linux `script`) does, with --quiet it does
# not.
source "$(dirname "$0")/lib/common.sh" "$@"

run=("$ecorail" frontier --from A6 --to A7 --tmax 100 --step 1 --no-cache)
"${run[@]}" > out.txt 2> err.txt || { echo "FAIL: frontier"; fail=1; }
if [ -s err.txt ]; then echo "FAIL: stderr not a terminal, yet:"; cat err.txt; fail=1; fi

if expect_tty_progress "${run[*]}" "ecorail frontier: point [0-9]*/[0-9]*" frontier; then
  # Policy ladders count layers; calibrations count the passes of each fit.
  script -qec "$ecorail policy --from A6 --to A7 --time 110 --out p.bin --lambda-ladder -5,0 2>&1 >/dev/null" \
    /dev/null > policy.txt || { echo "FAIL: policy on a tty"; fail=1; }
  grep -q "ecorail policy: layer 1/2" policy.txt || { echo "FAIL: no ladder progress"; cat -v policy.txt; fail=1; }
  data="$src/data/contest"
  script -qec "$ecorail calibrate --log $data/seed_profile_A6_A7_110s.csv --log $data/seed_profile_A6_A8_220s.csv --out c.toml 2>&1 >/dev/null" \
    /dev/null > calibrate.txt || { echo "FAIL: calibrate on a tty"; fail=1; }
  grep -q "ecorail calibrate: equation-error pass [0-9]/[0-9]" calibrate.txt &&
    grep -q "ecorail calibrate: output-error pass [0-9]/[0-9]" calibrate.txt ||
    { echo "FAIL: no calibration progress"; cat -v calibrate.txt; fail=1; }
  script -qec "$ecorail calibrate --quiet --log $data/seed_profile_A6_A7_110s.csv --log $data/seed_profile_A6_A8_220s.csv --out c2.toml 2>&1 >/dev/null" \
    /dev/null > calibrate_quiet.txt || { echo "FAIL: calibrate --quiet on a tty"; fail=1; }
  if grep -q "ecorail calibrate:" calibrate_quiet.txt; then echo "FAIL: calibration progress despite --quiet"; fail=1; fi
fi
exit $fail
