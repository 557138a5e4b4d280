# Sourced by the delay and Monte Carlo benchmarks: ensure_day_plan ECORAIL DAY.csv makes the 2.2
# day plan (240 trains, two peaks; timetable optimise with a 150 s time limit) when DAY.csv is
# missing or empty.
ensure_day_plan() {
  local bin=$1 day=$2
  [ -s "$day" ] && return 0
  echo "making the day plan $day (timetable optimise, 150 s time limit)" >&2
  "$bin" timetable optimise --trains 240 --peak 7200:12600 --peak 43200:50400 \
    --peak-headway 120:150 --offpeak-headway 300:660 --time-limit 150 --quiet --csv "$day" \
    > /dev/null
}
