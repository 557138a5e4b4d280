#!/usr/bin/env bash
# The installed package works from another project: `cmake --install` of this build tree into
# a fresh prefix, then examples/consumer (find_package(ecorail), ecorail::core) configured,
# built and run against it; its flat-out A6 -> A7 time must be the program's own min-time.
source "$(dirname "$0")/lib/common.sh" "$@"

build=$(dirname "$ecorail")
cmake --install "$build" --prefix "$work/prefix" > install.log 2>&1 ||
  { echo "FAIL: cmake --install"; tail -20 install.log; exit 1; }
[ -f "$work/prefix/lib/cmake/ecorail/ecorailConfig.cmake" ] ||
  [ -f "$work/prefix/lib64/cmake/ecorail/ecorailConfig.cmake" ] ||
  { echo "FAIL: no ecorailConfig.cmake installed"; exit 1; }
cmake -S "$src/examples/consumer" -B consumer -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" > configure.log 2>&1 ||
  { echo "FAIL: consumer configure"; tail -20 configure.log; exit 1; }
cmake --build consumer -j2 > build.log 2>&1 || { echo "FAIL: consumer build"; tail -30 build.log; exit 1; }
out=$(consumer/consumer) || { echo "FAIL: consumer run: $out"; exit 1; }
consumer_s=$(echo "$out" | sed -n 's/.*flat out: \([0-9.]*\) s.*/\1/p')
program_s=$("$ecorail" min-time --from A6 --to A7 | sed -n 's/.*minimum running time \([0-9.]*\) s.*/\1/p')
if [ -z "$consumer_s" ] || [ "$consumer_s" != "$program_s" ]; then
  echo "FAIL: consumer says '$out', the program $program_s s"; fail=1
fi
exit $fail
