#!/usr/bin/env bash
# The sanitizer job and the fuzz smoke run of CI (docs/reliability.md), after the README's build
# and tests.
#   ci (default)  one clang build in build-san: AddressSanitizer + UndefinedBehaviorSanitizer on
#                 the rooms it needs, the library also with libFuzzer's coverage
#                 (fuzzer-no-link), so the same build runs the tests of ASAN_TESTS (default: data
#                 physics fitting) and every fuzz harness for FUZZ_SECONDS (default 3) on its seed
#                 corpus. Each test program and harness links only the rooms it includes
#                 (cmake/EcorailRooms.cmake), so this build compiles physics, data, dp, fitting,
#                 policy and power, not the fleet, service, recovery and output rooms: their code
#                 runs in the main tests, and under ASan with ASAN_TESTS="... output" (or policy,
#                 dp, ...), which builds what those need. ASAN_GTEST_FILTER picks the cases
#                 (default: all but five calibrations of 5-25 s each under ASan, which the main
#                 tests run; a Ceres calibration with a Huber loss stays). This keeps CI inside
#                 its budget.
#   asan          GCC, AddressSanitizer + UBSan (-O1 -g) in build-asan, tests of ASAN_TESTS: the
#                 build where Eigen's allocation met Debian's Ceres (docs/reliability.md)
#   fuzz          clang, the fuzz harnesses only in build-fuzz (for deep runs: fuzz/run.sh)
# Usage: bash scripts/sanitize-and-fuzz-smoke.sh [ci|asan|fuzz]
# Exits non-zero on the first sanitizer report, failing test or fuzzer crash.
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-ci}"
jobs="${JOBS:-2}"
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
common=(-DECORAIL_BUILD_BENCHMARKS=OFF -DECORAIL_BUILD_EXAMPLES=OFF "${launcher[@]}")
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# Leaks are not checked: glog (through Ceres) and libgomp keep allocations until exit.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
default_rooms="data physics fitting"
# Line tables are all a sanitizer report needs (file:line in every frame) and cost a quarter less
# compile time than full -g in the CI build; the asan mode keeps -g for a debugger.
lines="-gline-tables-only"
slow="-CalibrationLongLog.*:CalibrationPublished.*:CalibrationSynthetic.*"
slow+=":CalibrationOptions.NotchColumnsReadThroughTheBaseEnvelopes"
slow+=":CalibrationOptions.RecoversATractionScale"

if [ "$what" = ci ]; then
  rooms="${ASAN_TESTS:-$default_rooms}"
  targets=(ecorail_fuzzers)
  for r in $rooms; do targets+=("test_$r"); done
  CC=clang CXX=clang++ cmake -S . -B build-san -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 $lines $san" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 $lines $san" \
    -DCMAKE_EXE_LINKER_FLAGS="$san" -DECORAIL_BUILD_FUZZERS=ON "${common[@]}" > /dev/null
  cmake --build build-san -j"$jobs" --target "${targets[@]}"
  for r in $rooms; do
    echo "== ASan+UBSan (clang): test_$r"
    build-san/tests/test_"$r" --gtest_brief=1 --gtest_filter="${ASAN_GTEST_FILTER:-$slow}"
  done
  # A fixed libFuzzer seed: CI explores the same inputs on every run, so a red CI is a change's
  # doing and reproducible; deep runs (mode fuzz, fuzz/run.sh) draw a new seed each time.
  FUZZ_FLAGS="${FUZZ_FLAGS:--seed=1}" bash fuzz/run.sh build-san "${FUZZ_SECONDS:-3}"
fi

if [ "$what" = asan ]; then
  rooms="${ASAN_TESTS:-$default_rooms}"
  targets=(ecorail)
  for r in $rooms; do targets+=("test_$r"); done
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g $san" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g $san" \
    -DCMAKE_EXE_LINKER_FLAGS="$san" "${common[@]}" > /dev/null
  cmake --build build-asan -j"$jobs" --target "${targets[@]}"
  for r in $rooms; do
    echo "== ASan+UBSan: test_$r"
    build-asan/tests/test_"$r" --gtest_brief=1
  done
fi

if [ "$what" = fuzz ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DECORAIL_BUILD_FUZZERS=ON -DECORAIL_BUILD_TESTS=OFF "${common[@]}" > /dev/null
  cmake --build build-fuzz -j"$jobs" --target ecorail_fuzzers
  bash fuzz/run.sh build-fuzz "${FUZZ_SECONDS:-5}"
fi
