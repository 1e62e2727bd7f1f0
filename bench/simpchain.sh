#!/bin/sh
# simpchain on large labelled meshes, single core: views of mkscene's room
# meshed like dm2mesh and labelled with the true patches (bench/gen_chain) at
# 640x480 with mild Kinect-class noise and 2048x1536 without, the 640x480 view with
# strong noise (dm2mesh's jump cuts shred it into thousands of holes: many
# chains and crossing checks), and two interleaved combs: two patches of a
# 1000x200 grid whose one boundary runs round 250 teeth 2 cells wide and 180
# long, narrower than the tolerance (3.4 cells); and one polygon of 100000
# points along y = exp(40 x) (every point but a few in one cell of any
# uniform grid).  Beside each, meshconv passing
# the same file through (read + write, the floor of any stage) in the same
# run.  Medians of RUNS runs: simpchain's CPU seconds (-v cpu_s), meshconv's
# whole command.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
T="$FCT_BENCH/timeit $RUNS"
. bench/lib.sh
bench_dir simpchain

cpu() {
	i=0
	while [ $i -lt "$RUNS" ]; do
		simpchain -v "$1" 2>&1 >/dev/null | sed -n 's/^simpchain: cpu_s=//p'
		i=$((i + 1))
	done | median
}
fig() { sed -n "s/^simpchain: $1=//p" "$dir/fig"; }
row() { printf '%-34s %9s %9s %8s %8s %8s %8s %8s\n' "$@"; }

"$FCT_BENCH/gen_chain" -k 0.0005 -s 640x480 >"$dir/v640.ply"
"$FCT_BENCH/gen_chain" -k 0 -s 2048x1536 >"$dir/v2048.ply"
"$FCT_BENCH/gen_chain" -k 0.0015 -s 640x480 >"$dir/shred.ply"
awk 'BEGIN {
	nx = 1000; ny = 200
	print "ply\nformat ascii 1.0\nelement vertex " (nx + 1) * (ny + 1)
	print "property float x\nproperty float y\nproperty float z"
	print "element face " 2 * nx * ny "\nproperty list uchar int vertex_indices\nproperty int patch"
	print "element plane 2\nproperty double nx\nproperty double ny\nproperty double nz\nproperty double d"
	print "end_header"
	for (j = 0; j <= ny; j++) for (i = 0; i <= nx; i++) print i, j, 0
	for (j = 0; j < ny; j++) for (i = 0; i < nx; i++) {
		a = j * (nx + 1) + i; l = (j >= 190 || (j >= 10 && i % 4 < 2)) ? 0 : 1
		print 3, a, a + 1, a + nx + 2, l; print 3, a, a + nx + 2, a + nx + 1, l
	}
	print "0 0 1 0"; print "0 0 1 0" }' | meshconv >"$dir/comb.ply"

awk -v n=100000 'BEGIN {
	print "ply\nformat ascii 1.0\nelement vertex " n + 1 "\nproperty double x\nproperty double y\nproperty double z"
	print "element face 1\nproperty list int int vertex_indices\nproperty int patch\nend_header"
	for (i = 0; i < n; i++) { x = i / n; print x, exp(40 * x), 0 }
	print 0, exp(40), 0
	line = n + 1; for (i = 0; i <= n; i++) line = line " " i; print line, 0 }' | meshconv >"$dir/expo.ply"

echo "simpchain: labelled meshes (bench/gen_chain views of mkscene's room; a comb), default threshold 3; medians of $RUNS runs"
row "input" "faces" "simpchain" "meshconv" "kept" "chains" "x-points" "x-left"
for f in v640 v2048 shred comb expo; do
	simpchain -v "$dir/$f.ply" 2>"$dir/fig" >/dev/null
	row "$f" "$(fig faces_in)" "$(cpu "$dir/$f.ply")" "$($T "meshconv '$dir/$f.ply' >/dev/null")" \
		"$(fig vertices_kept)" "$(($(fig chains) + $(fig loops)))" "$(fig crossing_points)" \
		"$(($(fig crossings_left) + $(fig crossings_left_image)))"
done
echo "simpchain: CPU seconds of the whole run (read, extract, simplify, check, write); meshconv: wall seconds;"
echo "kept: vertices in the wireframe; x-points: points kept only to prevent crossings; x-left: crossings inherited from the input"
