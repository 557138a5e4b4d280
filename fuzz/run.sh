#!/usr/bin/env bash
# Runs every fuzz harness of BUILD for SECONDS each on a corpus seeded from the shipped data
# (data/contest, data/contest/power_supply.toml, fitting/data, fuzz/seeds, and the TTOBench files of
# ../shared/data/ttobench when present). The corpus lives in BUILD/fuzz-corpus/<harness> and grows
# between runs; crashes are written to BUILD/fuzz-crashes/. Prints one line per harness with its
# executions and exits non-zero if any harness fails.
#   bash fuzz/run.sh build-fuzz 5            # CI smoke run (part of the README's test command)
#   bash fuzz/run.sh build-fuzz 600          # a deep run: 10 minutes per harness
# Extra libFuzzer flags can be passed in FUZZ_FLAGS (e.g. FUZZ_FLAGS="-jobs=2 -workers=2").
set -uo pipefail
build="${1:?usage: fuzz/run.sh BUILD_DIR SECONDS}"
seconds="${2:-5}"
src="$(cd "$(dirname "$0")/.." && pwd)"
corpus="$build/fuzz-corpus"
crashes="$build/fuzz-crashes"
mkdir -p "$crashes"

seed() {  # seed HARNESS FILE [PREFIX_BYTE]: copy FILE into the harness's corpus
  local dir="$corpus/$1"
  mkdir -p "$dir"
  [ -f "$2" ] || return 0
  if [ -n "${3:-}" ]; then
    { printf "\\x$(printf %02x "$3")"; cat "$2"; } > "$dir/seed_${3}_$(basename "$2")"
  else
    cp "$2" "$dir/seed_$(basename "$2")"
  fi
}
k=0
for t in stations gradients speed_limits curves; do
  seed fuzz_line_csv "$src/data/contest/$t.csv" "$k"
  k=$((k + 1))
done
seed fuzz_line_toml "$src/fuzz/seeds/line_toml/two_stations.toml"
seed fuzz_train_toml "$src/data/contest/train.toml"
for f in "$src"/fuzz/seeds/train_toml/*.toml; do seed fuzz_train_toml "$f"; done
for f in "$src"/data/contest/seed_profile_*.csv "$src"/fuzz/seeds/log/*.csv; do seed fuzz_log "$f"; done
for f in "$src"/fitting/data/*.csv "$src"/fuzz/seeds/fit_points/*.csv; do seed fuzz_fit_points "$f"; done
for f in "$src"/fuzz/seeds/policy/*.bin; do seed fuzz_policy "$f"; done
seed fuzz_csv "$src/data/contest/published_headways_2_1.csv"
seed fuzz_csv "$src/data/contest/stations.csv"
seed fuzz_power_supply "$src/data/contest/power_supply.toml"
shared="$src/../shared/data/ttobench"
for f in "$shared"/tracks/00_reference.json "$shared"/tracks/00_var_gradient_plus_5.json; do
  seed fuzz_ttobench "$f" 0
done
for f in "$shared"/trains/*.json; do seed fuzz_ttobench "$f" 1; done
for f in "$src"/fuzz/seeds/ttobench/*; do seed fuzz_ttobench "$f"; done

failed=0
for exe in "$build"/fuzz/fuzz_*; do
  [ -x "$exe" ] || continue
  name=$(basename "$exe")
  mkdir -p "$corpus/$name"
  log="$build/fuzz-$name.log"
  # shellcheck disable=SC2086
  "$exe" "$corpus/$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$crashes/$name-" ${FUZZ_FLAGS:-} \
    > "$log" 2>&1
  code=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  if [ "$code" -ne 0 ]; then
    echo "fuzz: $name FAILED (exit $code) after ${runs:-?} runs; see $log"
    grep -m5 -E "ERROR|runtime error|terminate|Assertion|deadly signal" "$log"
    failed=1
  else
    echo "fuzz: $name ok, ${runs:-?} runs in ${seconds} s, corpus $(ls "$corpus/$name" | wc -l)"
  fi
done
exit "$failed"
