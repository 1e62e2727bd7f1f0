#!/bin/sh
# segplanes: planar segmentation of a million faces (dm2mesh of a 1024x512
# view of the mkscene room with Kinect noise), and of a 640x480 view at
# step 1 and 5.  Seconds are medians of segplanes -v segment_s (the library
# call: adjacency, both phases, planes; reading and writing excluded) and
# cpu_s (the whole run); peak memory is /usr/bin/time's maximum resident set,
# per face, beside the same figure for meshconv reading and writing the same
# file (the mesh alone) measured in the same run.  Goals: 1M faces under
# 1 s on one core, under 250 bytes per face.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=5}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir seg

# figure KEY FILE: median over RUNS of segplanes -v's KEY on FILE.
figure() {
	i=0
	while [ $i -lt "$RUNS" ]; do
		segplanes -v -o /dev/null "$2" 2>&1 | sed -n "s/^segplanes: $1=//p"
		i=$((i + 1))
	done | median
}
# peak KB of a command (GNU time's %M), or "-" without /usr/bin/time.
peak() {
	if [ -x /usr/bin/time ]; then
		/usr/bin/time -f %M sh -c "$1" 2>&1 >/dev/null | tail -n 1
	else
		echo -
	fi
}
row() { printf '%-44s %9s %9s %10s %10s\n' "$1" "$2" "$3" "$4" "$5"; }

mkscene --size 1024x512 --fx 615 --noise kinect-gauss:0.0012 -o "$dir/big" >/dev/null
dm2mesh --camera "$dir/big/view00.camera" --pose "$dir/big/view00.pose" -o "$dir/big.ply" "$dir/big/view00.depth.pfm"
mkscene --noise kinect-gauss:0.0012 -o "$dir/room" >/dev/null
dm2mesh --camera "$dir/room/view00.camera" --pose "$dir/room/view00.pose" -o "$dir/room1.ply" "$dir/room/view00.depth.pfm"
dm2mesh --step 5 --camera "$dir/room/view00.camera" --pose "$dir/room/view00.pose" -o "$dir/room5.ply" "$dir/room/view00.depth.pfm"

echo "segplanes on $(uname -m), $(nproc) cores: mkscene room, Kinect noise 0.0012 z^2, dm2mesh; medians of $RUNS runs"
row "what" "faces" "segment s" "M faces/s" "cpu s"
for case in "1024x512 step 1:big" "640x480 step 1:room1" "640x480 step 5:room5"; do
	name=${case%%:*} file=$dir/${case#*:}.ply
	faces=$(segplanes -v -o /dev/null "$file" 2>&1 | sed -n 's/^segplanes: faces=//p')
	seg=$(figure segment_s "$file")
	cpu=$(figure cpu_s "$file")
	row "segplanes, $name" "$faces" "$seg" "$(awk -v f="$faces" -v t="$seg" 'BEGIN { printf "%.2f", (t > 0 ? f / t / 1e6 : 0) }')" "$cpu"
done
faces=$(segplanes -v -o /dev/null "$dir/big.ply" 2>&1 | sed -n 's/^segplanes: faces=//p')
row "reference: meshconv read+write, 1024x512" "$faces" "" "" "$("$FCT_BENCH/timeit" "$RUNS" "meshconv '$dir/big.ply' >/dev/null")"
seg_kb=$(peak "segplanes '$dir/big.ply' >/dev/null")
conv_kb=$(peak "meshconv '$dir/big.ply' >/dev/null")
if [ "$seg_kb" != - ]; then
	echo
	printf 'peak memory, %s faces: segplanes %s KB (%s bytes/face), meshconv %s KB (%s bytes/face)\n' "$faces" \
		"$seg_kb" "$(awk -v k="$seg_kb" -v f="$faces" 'BEGIN { printf "%.0f", k * 1024 / f }')" \
		"$conv_kb" "$(awk -v k="$conv_kb" -v f="$faces" 'BEGIN { printf "%.0f", k * 1024 / f }')"
fi
echo "goals: 1M faces segmented under 1 s on one core, under 250 bytes of memory per face"
