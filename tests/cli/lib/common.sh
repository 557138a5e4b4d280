# Shared set-up for the end-to-end scripts in tests/cli (sourced, not run by ctest).
# Usage at the top of a script:  source "$(dirname "$0")/lib/common.sh" "$@"
# Sets $ecorail and $src, moves into a fresh work directory removed at exit (kept with KEEP=1),
# and provides expect_error.
ecorail="$1"
src="$2"
work=$(mktemp -d)
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0

# expect_error "needle" args...: ecorail must exit with code 2, print exactly one line on
# stderr containing the needle, and leave no new file behind (nothing half-written).
expect_error() {
  local needle="$1"
  shift
  local before
  before=$(ls -A | sort)
  "$ecorail" "$@" > stdout.txt 2> stderr.txt
  local code=$?
  local after
  after=$(ls -A | sort)
  if [ "$code" -ne 2 ]; then
    echo "FAIL: exit $code (want 2): $*"; cat stderr.txt; fail=1
  elif ! grep -qF -- "$needle" stderr.txt; then
    echo "FAIL: message lacks '$needle': $*"; cat stderr.txt; fail=1
  elif [ "$(grep -c . stderr.txt)" -ne 1 ]; then
    echo "FAIL: more than one line of error: $*"; cat stderr.txt; fail=1
  fi
  local added
  added=$(comm -13 <(echo "$before") <(echo "$after") | grep -v -e '^stdout.txt$' -e '^stderr.txt$')
  if [ -n "$added" ]; then
    echo "FAIL: files left behind ($added): $*"; fail=1
    rm -f $added
  fi
}

# expect_tty_progress "command line" "pattern" label: run on a terminal (faked with util-linux
# `script`), stderr must show a progress line matching the pattern; with --quiet added, no line
# starting "ecorail <command>:". Returns 1 (after a note) when `script` is missing.
expect_tty_progress() {
  local cmd="$1" pattern="$2" label="$3"
  command -v script > /dev/null || { echo "note: util-linux script is missing; $label skipped"; return 1; }
  local name
  name=$(echo "$cmd" | awk '{print $2}')
  script -qec "$cmd 2>&1 >/dev/null" /dev/null > "tty_$label.txt" || { echo "FAIL: $label on a tty"; fail=1; }
  grep -q "$pattern" "tty_$label.txt" ||
    { echo "FAIL: no progress of $label on a terminal"; cat -v "tty_$label.txt"; fail=1; }
  script -qec "$cmd --quiet 2>&1 >/dev/null" /dev/null > "tty_quiet_$label.txt" ||
    { echo "FAIL: $label --quiet on a tty"; fail=1; }
  if grep -q "ecorail $name:" "tty_quiet_$label.txt"; then echo "FAIL: progress of $label despite --quiet"; fail=1; fi
  return 0
}
