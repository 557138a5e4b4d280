#!/usr/bin/env bash
# The many-train commands under random input (tests/cli/lib/many_train_fuzz.py): random plans
# and delays, perturbed plans, tampered Monte Carlo shards and mutated power-supply files give a
# result within its physical ranges or one clear error; never a crash, a half-written output or
# a modified input. SEED=n runs another draw.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
export XDG_CACHE_HOME="$work/xdg"
mkdir -p "$XDG_CACHE_HOME"
ECORAIL_SOURCE_DIR="$src" python3 "$src/tests/cli/lib/many_train_fuzz.py" "$ecorail" \
  "$(dirname "$ecorail")/test-cache/many-train-fuzz" "${SEED:-1}" || fail=1
exit $fail
