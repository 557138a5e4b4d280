#!/usr/bin/env bash
# OpenMP's waiting threads yield their core by default (cli/wait_policy.hpp), in the process the
# user started: libgomp's own report of its settings (OMP_DISPLAY_ENV=VERBOSE, printed once per
# process when libgomp starts) must appear once, with the passive spin count 0; a user's
# OMP_WAIT_POLICY stands. Under valgrind (when installed) the program runs as it is: a program
# that re-executes itself is refused by valgrind ("You cannot run ... directly"), and memcheck
# must find no error in a small run.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

OMP_DISPLAY_ENV=VERBOSE "$ecorail" min-time --from A6 --to A7 > out.txt 2> env.txt ||
  { echo "FAIL: min-time"; cat env.txt; fail=1; }
n=$(grep -c "GOMP_SPINCOUNT" env.txt)
[ "$n" -eq 1 ] || { echo "FAIL: libgomp started $n times (want 1: no re-execution)"; fail=1; }
grep -q "OMP_WAIT_POLICY = 'PASSIVE'" env.txt || { echo "FAIL: wait policy not passive"; fail=1; }
grep -q "GOMP_SPINCOUNT = '0'" env.txt ||
  { echo "FAIL: waiting threads spin:"; grep GOMP_SPINCOUNT env.txt; fail=1; }

OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=VERBOSE "$ecorail" min-time --from A6 --to A7 \
  > /dev/null 2> env.txt || { echo "FAIL: min-time with OMP_WAIT_POLICY=active"; fail=1; }
grep -q "OMP_WAIT_POLICY = 'ACTIVE'" env.txt || { echo "FAIL: the user's policy was replaced"; fail=1; }

if command -v valgrind > /dev/null; then
  valgrind --tool=memcheck --error-exitcode=99 --leak-check=no -q \
    "$ecorail" min-time --from A6 --to A7 > vg.txt 2> vg_err.txt
  code=$?
  [ "$code" -eq 0 ] || { echo "FAIL: valgrind memcheck exit $code"; cat vg_err.txt; fail=1; }
  cmp -s out.txt vg.txt || { echo "FAIL: output differs under valgrind"; fail=1; }
else
  echo "valgrind not installed: the memcheck part is skipped"
fi
exit "$fail"
