#!/bin/sh
# areaflow speed: a 1M-vertex range mesh (mkscene's room, 1280x800, Kinect
# noise at 0.0015 z^2, meshed at every pixel) smoothed for 5 iterations with
# the default window, crease strength included, on 1 thread and on every
# processor; beside Taubin x5 and the time to read and write the mesh
# (meshconv).  Goal: < 3 s.  Then the distance to the exact scene at step 4.
set -eu
: "${FCT_BIN:=build/bin}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir af
mkscene -q --size 1280x800 --fx 1050 --noise kinect-gauss:0.0015 -o "$dir/room"
dm2mesh -q --camera "$dir/room/view00.camera" --pose "$dir/room/view00.pose" -o "$dir/r.ply" "$dir/room/view00.depth.pfm"
# figure KEY args...: median over RUNS of an areaflow -v figure.
figure() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		areaflow -v "$@" "$dir/r.ply" 2>&1 >/dev/null | sed -n "s/^areaflow: $key=//p"
		i=$((i + 1))
	done | median
}
nv=$(meshconv -v "$dir/r.ply" 2>&1 >/dev/null | sed -n 's/^meshconv: vertices=//p')
echo "areaflow: mkscene room 1280x800, kinect-gauss:0.0015, $nv vertices; $(nproc) processors; medians of $RUNS runs"
a1=$(figure smooth_s --iterations 5 --threads 1)
a2=$(figure smooth_s --iterations 5 --threads 2)
an=$(figure smooth_s --iterations 5)
nc=$(figure smooth_s --iterations 5 --no-crease --threads 1)
tb=$(figure smooth_s --iterations 5 --method taubin --threads 1)
mc=$("$FCT_BENCH/timeit" "$RUNS" "meshconv '$dir/r.ply' >/dev/null")
# The window record serves the geodesic vote (--guide off); the guide, on by
# itself on this mesh, votes over rings and records nothing.
ids=$(areaflow -v --guide off --iterations 5 "$dir/r.ply" 2>&1 >/dev/null | sed -n 's/^areaflow: window_ids=//p')
printf '%-52s %10s %12s %12s\n' "what" "seconds" "/ taubin x5" "/ meshconv"
row() { printf '%-52s %10.3f %12.2f %12.2f\n' "$1" "$2" "$(echo "$2 $tb" | awk '{ print $1 / $2 }')" "$(echo "$2 $mc" | awk '{ print $1 / $2 }')"; }
row "areaflow x5, crease, 1 thread (smoothing only)" "$a1"
row "areaflow x5, crease, 2 threads (smoothing only)" "$a2"
row "areaflow x5, crease, all threads (smoothing only)" "$an"
row "areaflow x5 --no-crease, 1 thread" "$nc"
row "reference: taubin x5, 1 thread" "$tb"
row "reference: meshconv read+write" "$mc"
echo "window record (--guide off): $ids face ids, $(echo "$ids $nv" | awk '{ printf "%.1f per vertex, %.0f bytes per vertex with the 6 of the index", $1 / $2, 4 * $1 / $2 + 6 }')"
echo "goal: areaflow x5 with crease < 3 s"
echo
dm2mesh -q --step 4 --camera "$dir/room/view00.camera" --pose "$dir/room/view00.pose" -o "$dir/r4.ply" "$dir/room/view00.depth.pfm"
d() { meshdist "$1" "$dir/room/scene.ply" | awk '$1 == "mean" { printf "%.6f", $2 }'; }
echo "distance to the exact room (mean, metres), the same view at step 4:"
echo "  raw $(d "$dir/r4.ply")"
for m in "areaflow" "areaflow --no-crease" "laplacian" "taubin"; do
	set -- $m
	case $1 in areaflow) shift; o="$*" ;; *) o="--method $1" ;; esac
	areaflow $o --iterations 5 -o "$dir/o.ply" "$dir/r4.ply"
	echo "  $m x5 $(d "$dir/o.ply")"
done
