#!/bin/sh
# meshshot throughput: a 1M-triangle curved grid (gen_grid 708: 501,264
# vertices, 999,698 triangles, binary PLY) drawn at 1024x768 in a fitted
# front and oblique view, beside meshconv reading and writing the same mesh
# to /dev/null, in the same run.  Goal: the whole picture in under 1 s.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir shot
T="$FCT_BENCH/timeit $RUNS"
"$FCT_BENCH/gen_grid" 708 >"$dir/grid.ply"
echo "meshshot: gen_grid 708 (999,698 triangles) at 1024x768; medians of $RUNS runs"
printf '%-52s %10s\n' "what" "seconds"
t=$($T "meshconv '$dir/grid.ply' >/dev/null"); printf '%-52s %10.3f\n' "reference: meshconv read+write > /dev/null" "$t"
t=$($T "meshshot -s 1024x768 --view front -o '$dir/f.png' '$dir/grid.ply'"); printf '%-52s %10.3f\n' "meshshot: front view, shaded" "$t"
t=$($T "meshshot -s 1024x768 --view oblique -o '$dir/o.png' '$dir/grid.ply'"); printf '%-52s %10.3f\n' "meshshot: oblique view, shaded" "$t"
t=$($T "meshshot -s 1024x768 --view oblique --smooth -o '$dir/s.png' '$dir/grid.ply'"); printf '%-52s %10.3f\n' "meshshot: oblique view, smooth" "$t"
echo "goal: < 1 s per picture"
