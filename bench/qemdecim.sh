#!/bin/sh
# qemdecim: quadric edge-collapse decimation of about a million triangles to
# 1%, single core: a curved height field (bench/gen_grid 708: 999,698
# triangles), the furnished mkscene room seen at 1000x500 without noise
# (dm2mesh: about 990,000 triangles) and with Kinect-like noise (-c: its
# tears may close).  CPU seconds of the decimation alone (qemdecim -v
# decimate_cpu_s) and of the whole run, beside meshconv passing the same
# file through (read + write, the floor of any stage) in the same run;
# medians of RUNS runs.  For the rooms, the mean distance from the model to
# the true surface (meshdist -s to scene.ply), beside the input's.
# Goal: 1M triangles to 1% in a few seconds.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
T="$FCT_BENCH/timeit $RUNS"
. bench/lib.sh
bench_dir qem

# figure KEY ARGS...: median over RUNS of qemdecim -v's KEY.
figure() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		qemdecim -v "$@" 2>&1 >/dev/null | sed -n "s/^qemdecim: $key=//p"
		i=$((i + 1))
	done | median
}
row() { printf '%-58s %10s %10s\n' "$1" "$2" "$3"; }

"$FCT_BENCH/gen_grid" 708 >"$dir/grid.ply"
mkscene --size 1000x500 -o "$dir/room" >/dev/null
mkscene --size 1000x500 --noise kinect-gauss:0.0015 -o "$dir/noisy" >/dev/null
for s in room noisy; do
	dm2mesh --camera "$dir/$s/view00.camera" --pose "$dir/$s/view00.pose" -o "$dir/$s.ply" "$dir/$s/view00.depth.pfm"
done

echo "qemdecim: about 1M triangles to 1%, one core; medians of $RUNS runs"
row "what" "seconds" "M tri/s"
for case in "grid:" "room:" "noisy:-c"; do
	name=${case%%:*}
	opt=${case#*:}
	faces=$(meshinfo "$dir/$name.ply" | sed -n 's/^faces: //p')
	# shellcheck disable=SC2086
	cpu=$(figure decimate_cpu_s $opt -r 0.01 "$dir/$name.ply")
	# shellcheck disable=SC2086
	whole=$(figure cpu_s $opt -r 0.01 "$dir/$name.ply")
	rate=$(awk -v f="$faces" -v t="$cpu" 'BEGIN { printf "%.2f", (t > 0 ? f / t / 1e6 : 0) }')
	row "qemdecim $name ($faces tri): decimation CPU" "$cpu" "$rate"
	row "qemdecim $name: whole run CPU (read, decimate, write)" "$whole" ""
	row "reference: meshconv of the same file (whole run, wall)" "$($T "meshconv '$dir/$name.ply' >/dev/null")" ""
done
for case in "room:" "noisy:-c"; do
	name=${case%%:*}
	opt=${case#*:}
	# shellcheck disable=SC2086
	qemdecim $opt -r 0.01 -o "$dir/$name.d.ply" "$dir/$name.ply" 2>/dev/null
	in=$(meshdist -s 200000 "$dir/$name.ply" "$dir/$name/scene.ply" | sed -n 's/^mean //p')
	out=$(meshdist -s 200000 "$dir/$name.d.ply" "$dir/$name/scene.ply" | sed -n 's/^mean //p')
	printf '%-58s %10.3g %10.3g\n' "$name: mean distance to the truth (m), input / 1% model" "$in" "$out"
done
echo "goal: 1M triangles to 1% in a few seconds of CPU"
