#!/bin/sh
# fct_delaunay throughput, single core, in process (points generated outside
# the timing): 1M uniform random points, 1M points on a jittered grid and
# 1M points on an exact grid (cocircular everywhere: the exact predicates
# decide every tie), beside the time to qsort the same 1M points by (u, v)
# measured in the same run.  Medians of RUNS runs.  Goal: 1M points < 2 s.
set -eu
: "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
N=${DELAUNAY_N:-1000000}
B="$FCT_BENCH/delaunay_bench"

echo "delaunay: $N points, medians of $RUNS runs"
printf '%-52s %8s %12s %10s\n' "what" "seconds" "M points/s" "x qsort"
ref=$("$B" qsort "$N" "$RUNS" | cut -d' ' -f1)
row() {
	set -- "$1" $("$B" "$2" "$N" "$RUNS")
	awk -v w="$1" -v t="$2" -v n="$N" -v r="$ref" 'BEGIN {
		printf "%-52s %8.4f %12.2f %10.2f\n", w, t, (t > 0 ? n / t / 1e6 : 0), (r > 0 ? t / r : 0) }'
}
awk -v t="$ref" -v n="$N" 'BEGIN { printf "%-52s %8.4f %12.2f %10.2f\n", "reference: qsort of the points by (u, v)", t, (t > 0 ? n / t / 1e6 : 0), 1 }'
row "fct_delaunay: uniform random in 4000 x 3000" uniform
row "fct_delaunay: grid jittered by <= 1/4 pixel" jgrid
row "fct_delaunay: exact integer grid (all cocircular)" grid
echo "goal: 1,000,000 points in under 2 s (aim 0.5-1 s) on one core"
