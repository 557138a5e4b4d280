# Sourced by the TTOBench bench scripts (bench/ttobench_*.sh): sets `here` (the source tree),
# `ttobench` (TTOBench's data: ../shared/data/ttobench beside the tree, or TTOBENCH=DIR) and
# `out_dir` (a scratch directory removed on exit).
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ttobench=${TTOBENCH:-$here/../shared/data/ttobench}
out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT
