#!/usr/bin/env bash
# No output of a run replaces one of its inputs, whatever its spelling (./f, d/../f, a hard
# link): every command and every kind of input, each refused with one error naming the input's
# flag, exit 2, the input unchanged (checksum) and nothing written. Inputs are compared by file
# identity (device and inode); a file a loader reads without a flag of its own (a line
# directory's stations.csv) is guarded too.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

# refused NEEDLE FILE ARGS...: expect_error, and FILE's bytes unchanged.
refused() {
  local needle="$1" file="$2"
  shift 2
  local before after
  before=$(md5sum < "$file")
  expect_error "$needle" "$@"
  after=$(md5sum < "$file")
  [ "$before" = "$after" ] || { echo "FAIL: input $file changed by: $*"; fail=1; }
}

data="$src/data/contest"
cp "$data/train.toml" train.toml
cp "$data/power_supply.toml" ps.toml
mkdir sub line
cp "$data"/{stations,gradients,speed_limits,curves}.csv line/
printf 'headway_s\n200\n200\n200\n200\n200\n' > h.csv
ln h.csv h-link.csv  # a hard link: the same file under another name
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)

# An output that names an input of the same run.
refused "--headways" h.csv timetable evaluate "${small[@]}" --headways h.csv --csv h.csv
refused "--headways" h.csv timetable evaluate "${small[@]}" --headways h.csv --csv ./h.csv
refused "--headways" h.csv timetable evaluate "${small[@]}" --headways h.csv --csv sub/../h.csv
refused "--headways" h.csv timetable evaluate "${small[@]}" --headways h.csv --json h-link.csv
refused "--power-supply" ps.toml timetable evaluate "${small[@]}" --model network \
  --power-supply ps.toml --json ps.toml
cp h.csv p.csv
refused "--plan" p.csv delay --plan p.csv --train 2 --station A9 --delay 60 --csv p.csv
refused "--plan" p.csv montecarlo --plan p.csv --days 2 --adjust --adjusted-csv p.csv
refused "--plan" p.csv montecarlo --plan p.csv --days 2 --json ./p.csv

# export with the track and the train swapped: each output is the other's input.
source "$src/tests/cli/lib/ttobench_fixtures.sh"
flat_track track.json T '[0, 1000, 2000]' 80
hand_train tr.json
refused "(--train)" tr.json export --line track.json --train tr.json \
  --ttobench-track tr.json --ttobench-train track.json
refused "(--line)" track.json export --line track.json --train tr.json \
  --ttobench-track t2.json --ttobench-train track.json

# Every other command and input.
refused "--train" train.toml solve --from A6 --to A7 --time 110 --train train.toml --json train.toml
refused "--train" train.toml min-time --from A6 --to A7 --train train.toml --csv ./train.toml
refused "--train" train.toml frontier --from A6 --to A7 --train train.toml --csv train.toml
refused "--train" train.toml policy --from A6 --to A7 --time 110 --train train.toml --out train.toml
refused "--train" train.toml calibrate --log "$data/seed_profile_A6_A7_110s.csv" --train train.toml \
  --out train.toml
cp "$data/seed_profile_A6_A7_110s.csv" log.csv
refused "--log" log.csv calibrate --log log.csv --json log.csv
printf 'speed_kmh,force_kN\n0,300\n20,300\n40,300\n60,200\n80,150\n' > points.csv
refused "--points" points.csv fit-envelope --points points.csv --kind traction --json points.csv
refused "--train" train.toml fit-envelope --points points.csv --kind traction --train train.toml \
  --out train.toml
printf '{}\n' > shard.json
refused "shards" shard.json montecarlo merge shard.json --json shard.json
# A file of a line directory (read by the loader, with no flag of its own), written after the run.
refused "input of this run" line/stations.csv solve --from A6 --to A7 --time 110 --line line \
  --csv line/stations.csv

# The same names as outputs of a run that reads other inputs are fine.
"$ecorail" min-time --from A6 --to A7 --csv h2.csv > /dev/null || { echo "FAIL: min-time --csv"; fail=1; }
exit "$fail"
