#!/bin/sh
# dm2mesh: depth maps and sparse points to meshes, CPU seconds (dm2mesh -v
# cpu_s, medians), beside references measured in the same run: decoding the
# same PNG (imginfo) and reading and writing a mesh of the same size
# (meshconv).  Goals: 640x480 under 0.015 s CPU, 4096x3072 under 0.5 s,
# 1M sparse points under 2 s.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir dm
T="$FCT_BENCH/timeit $RUNS"

# figure KEY ARGS...: median over RUNS of dm2mesh -v's KEY.
figure() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		dm2mesh -v "$@" 2>&1 >/dev/null | sed -n "s/^dm2mesh: $key=//p"
		i=$((i + 1))
	done | median
}
row() { printf '%-56s %10s %12s\n' "$1" "$2" "$3"; }

"$FCT_BENCH/gen_depth" 640 480 >"$dir/d640.png"
"$FCT_BENCH/gen_depth" 4096 3072 >"$dir/d4k.png"
"$FCT_BENCH/gen_depth" -p 1000000 >"$dir/pts.txt"
K640=512,512,319.5,239.5 K4k=3276.8,3276.8,2047.5,1535.5

echo "dm2mesh: synthetic depth maps (bench/gen_depth: a wall with a box, 1 mm noise, 2% holes), the real 7-Scenes and TUM frames of samples/ (-K 7scenes and -K tum imply the kinect noise model: sigma per vertex and the noise term of the jump test; numeric -K none), 1M random sparse points; medians of $RUNS runs"
row "what" "seconds" "M faces/s"
for case in "640x480 -K $K640 $dir/d640.png" "7-Scenes -K 7scenes samples/7scenes/frame-000000.depth.png" \
	"TUM 640x480 -K tum samples/tum/TUM_depth.png" \
	"TUM no model -K 525,525,319.5,239.5 --depth-scale 5000 samples/tum/TUM_depth.png" \
	"640x480/5 -K $K640 --step 5 $dir/d640.png" "4096x3072 -K $K4k $dir/d4k.png"; do
	name=${case%% -*}
	args=${case#"$name" }
	# shellcheck disable=SC2086
	cpu=$(figure cpu_s $args)
	# shellcheck disable=SC2086
	faces=$(dm2mesh -v $args 2>&1 >/dev/null | sed -n 's/^dm2mesh: faces=//p')
	row "dm2mesh $name: CPU, read + mesh + write binary PLY" "$cpu" "$(awk -v f="$faces" -v t="$cpu" 'BEGIN { printf "%.1f", (t > 0 ? f / t / 1e6 : 0) }')"
done
dm2mesh -K "$K640" -o "$dir/m640.ply" "$dir/d640.png"
dm2mesh -K "$K4k" -o "$dir/m4k.ply" "$dir/d4k.png"
row "reference: decode the 640x480 PNG (imginfo, whole run)" "$($T "imginfo '$dir/d640.png' >/dev/null")" ""
row "reference: meshconv the 640x480 output (whole run)" "$($T "meshconv '$dir/m640.ply' >/dev/null")" ""
row "reference: decode the 7-Scenes PNG (imginfo, whole run)" "$($T "imginfo samples/7scenes/frame-000000.depth.png >/dev/null")" ""
row "reference: decode the 4096x3072 PNG (imginfo, whole run)" "$($T "imginfo '$dir/d4k.png' >/dev/null")" ""
row "reference: meshconv the 4096x3072 output (whole run)" "$($T "meshconv '$dir/m4k.ply' >/dev/null")" ""
cpu=$(figure cpu_s --points -K 525,525,319.5,239.5 "$dir/pts.txt")
faces=$(dm2mesh -v --points -K 525,525,319.5,239.5 "$dir/pts.txt" 2>&1 >/dev/null | sed -n 's/^dm2mesh: faces=//p')
row "dm2mesh --points, 1M points: CPU, read + Delaunay + write" "$cpu" "$(awk -v f="$faces" -v t="$cpu" 'BEGIN { printf "%.1f", (t > 0 ? f / t / 1e6 : 0) }')"
row "reference: wc -l of the 1M points" "$($T "wc -l '$dir/pts.txt' >/dev/null")" ""
echo "goals: 640x480 < 0.015 s CPU, 4096x3072 < 0.5 s, 1M sparse points < 2 s (one core)"
