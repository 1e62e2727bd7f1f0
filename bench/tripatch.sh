#!/bin/sh
# tripatch on long boundaries, single core: one patch whose boundary is a
# 100000-vertex zig-zag strip, one whose straight side has two vertices
# facing a 100000-vertex zig-zag (the greedy fan: every vertex's diagonal
# is long), and a random star-shaped polygon of 100000 vertices; greedy
# (default) beside --cdt, beside meshconv passing the same file through
# (read + write, the floor of any stage) in the same run.  Medians of RUNS
# runs, seconds of the whole command.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
N=${TRIPATCH_N:-100000}
T="$FCT_BENCH/timeit $RUNS"
. bench/lib.sh
bench_dir tripatch

# kind 0: zig-zag strip; 1: two-vertex base under a zig-zag; 2: random star.
gen() {
	awk -v n="$N" -v kind="$1" 'BEGIN {
		srand(7)
		print "ply\nformat ascii 1.0\nelement vertex " n "\nproperty float x\nproperty float y\nproperty float z"
		print "element edge " n "\nproperty int vertex1\nproperty int vertex2\nproperty int patch1\nproperty int patch2"
		print "element plane 1\nproperty double nx\nproperty double ny\nproperty double nz\nproperty double d"
		print "end_header"
		if (kind == 0) {
			m = n / 2
			for (i = 0; i < m; i++) print i, (i % 2) * 0.3, 0
			for (i = m - 1; i >= 0; i--) print i + 0.25, 2 + (i % 2) * 0.3, 0
		} else if (kind == 1) {
			print 0, 0, 0; print n - 2, 0, 0
			for (i = n - 3; i >= 0; i--) print i + 0.5, 5 + (i % 2) * 0.3 + 0.001 * sin(0.7 * i), 0
		} else {
			for (i = 0; i < n; i++) {
				th = 2 * 3.14159265358979 * (i + 0.8 * rand()) / n; r = 500 + 500 * rand()
				print r * cos(th), r * sin(th), 0
			}
		}
		for (i = 0; i < n; i++) print i, (i + 1) % n, 0, -1
		print 0, 0, 1, 0 }' | meshconv >"$dir/$1.ply"
}

echo "tripatch: one patch of $N boundary vertices, medians of $RUNS runs"
printf '%-58s %8s %10s\n' "what" "seconds" "x meshconv"
for k in 0 1 2; do
	gen $k
	case $k in
	0) what="zig-zag strip" ;;
	1) what="2-vertex side facing a zig-zag" ;;
	*) what="random star" ;;
	esac
	ref=$($T "meshconv '$dir/$k.ply' >/dev/null")
	g=$($T "tripatch '$dir/$k.ply' >/dev/null")
	c=$($T "tripatch --cdt '$dir/$k.ply' >/dev/null")
	cand=$(tripatch -v "$dir/$k.ply" 2>&1 >/dev/null | sed -n 's/^tripatch: candidates=//p')
	awk -v w="$what" -v r="$ref" -v g="$g" -v c="$c" -v cand="$cand" -v n="$N" 'BEGIN {
		printf "%-58s %8.4f %10.2f\n", "reference: meshconv, " w, r, 1
		printf "%-58s %8.4f %10.2f\n", "tripatch (greedy, " sprintf("%.1f", cand / n) " candidates/vertex), " w, g, (r > 0 ? g / r : 0)
		printf "%-58s %8.4f %10.2f\n", "tripatch --cdt, " w, c, (r > 0 ? c / r : 0) }'
done
echo "goal: 100,000 boundary vertices in about a second either way, O(n) memory"
