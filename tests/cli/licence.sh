#!/usr/bin/env bash
# The repository's licence: LICENSE at the top is BSD 3-Clause (copyright the ecorail authors);
# every data file derived from TTOBench (its metadata names the TTOBench library version) has
# TTOBench's BSD 2-Clause notice in a LICENSE beside it; the README names both.
# Usage: bash licence.sh <path-to-ecorail> <source-dir>
set -uo pipefail
src="$2"
fail=0

lic="$src/LICENSE"
if [ ! -f "$lic" ]; then
  echo "FAIL: no LICENSE at the top of the repository"; fail=1
else
  head -1 "$lic" | grep -qx "BSD 3-Clause License" || { echo "FAIL: LICENSE is not BSD 3-Clause"; fail=1; }
  grep -q "Copyright (c) [0-9]*, the ecorail authors" "$lic" ||
    { echo "FAIL: LICENSE lacks the copyright of the ecorail authors"; fail=1; }
  grep -q "Neither the name of the copyright holder" "$lic" ||
    { echo "FAIL: LICENSE lacks the third clause"; fail=1; }
fi

derived=$(cd "$src" && git ls-files 2>/dev/null | grep -v '^tests/' |
  xargs grep -l '"library version": *"TTOBench' 2>/dev/null)
[ -n "$derived" ] || { echo "FAIL: no TTOBench-derived data file found (expected data/ttobench/)"; fail=1; }
for f in $derived; do
  notice="$src/$(dirname "$f")/LICENSE"
  if [ ! -f "$notice" ]; then
    echo "FAIL: $f is derived from TTOBench but has no LICENSE beside it"; fail=1
  else
    head -1 "$notice" | grep -qx "BSD 2-Clause License" ||
      { echo "FAIL: $notice is not TTOBench's BSD 2-Clause notice"; fail=1; }
    grep -q "^Copyright (c) 2022" "$notice" || { echo "FAIL: $notice lacks TTOBench's copyright"; fail=1; }
  fi
done

grep -q "BSD 3-Clause" "$src/README.md" || { echo "FAIL: README does not name the BSD 3-Clause licence"; fail=1; }
grep -q "data/ttobench/LICENSE" "$src/README.md" ||
  { echo "FAIL: README does not name the TTOBench notice"; fail=1; }
[ "$fail" -eq 0 ] && echo "licence: ok"
exit "$fail"
