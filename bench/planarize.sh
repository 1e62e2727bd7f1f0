#!/bin/sh
# planarize (the planar model in one process) against a quadric edge-collapse
# decimation (qemdecim, Garland-Heckbert) of the same dense mesh to the same
# face count: faces, the paper's Table 1 errors (dense vertices to the model),
# on the synthetic room the distances to the TRUE surface (200k points on
# each mesh to the exact scene: mean and p95), and the CPU seconds of each
# stage (planarize -v, medians of RUNS runs) against the goal of 1.5 s for a
# 640x480 frame.  Inputs: mkscene's furnished room, 640x480, with
# structured Kinect noise and with Gaussian noise of 2 mm (each with its
# noise model), and the real TUM frame of samples/.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir plan
faces() { meshinfo "$1" | awk '$1 == "faces:" { print $2 }'; }
table1() { meshdist "$1" "$2" | awk '$1 == "mean" { m = $2 } $1 == "stdev" { s = $2 } $1 == "max" { x = $2 } END { printf "%.4f %.4f %.4f", m, s, x }'; }
truth() { meshdist -p -s 200000 "$1" "$2" | awk '$1 == "mean" { m = $2 } $1 == "p95" { p = $2 } END { printf "%.4f %.4f", m, p }'; }
# stages ARGS...: median CPU seconds of each stage and of the whole run
# over RUNS runs of planarize -v ARGS
stages() {
	i=0
	while [ $i -lt "$RUNS" ]; do
		planarize -v "$@" 2>&1 >/dev/null | awk '$4 == "vertices" { printf "%s %s\n", $2, $(NF - 1) } /^planarize: cpu_s=/ { sub(/.*=/, ""); print "all", $0 }'
		i=$((i + 1))
	done >"$dir/cpu"
	for s in dm2mesh segplanes planedecim all; do
		printf ' %s %s' "$s" "$(awk -v s=$s '$1 == s { print $2 }' "$dir/cpu" | median)"
	done
}
hdr='%-26s %7s %9s  %-22s %-16s\n'

echo "planarize against qemdecim to the same face count (Table 1: dense vertices to the model, E_avg E_std E_max;"
echo "truth: 200k points on the mesh to the exact scene, mean p95; metres); CPU seconds: medians of $RUNS runs"
echo "(all: the whole run, reading, writing and -v's Table 1 included)"
for noise in kinect gaussian:0.002; do
	R=$dir/room-${noise%%:*}
	mkscene -q --noise "$noise" -o "$R" >/dev/null
	set -- --camera "$R/view00.camera" --pose "$R/view00.pose" --noise "$R/view00.noise" \
		"$R/view00.depth.pfm" "$R/view00.color.png"
	planarize --keep "$R/st" -o "$R/model.ply" "$@"
	n=$(faces "$R/model.ply")
	qemdecim -c -n "$n" -o "$R/qem.ply" "$R/st/1-mesh.ply"
	echo
	echo "mkscene's room, 640x480, --noise $noise; the dense mesh has $(faces "$R/st/1-mesh.ply") faces," \
		"$(truth "$R/st/1-mesh.ply" "$R/scene.ply") to the truth"
	printf "$hdr" method faces reduction "Table 1" truth
	printf "$hdr" planarize "$n" "$(awk -v a="$(faces "$R/st/1-mesh.ply")" -v b="$n" 'BEGIN { printf "%.0f", a / b }')" \
		"$(table1 "$R/st/1-mesh.ply" "$R/model.ply")" "$(truth "$R/model.ply" "$R/scene.ply")"
	printf "$hdr" "qemdecim (dense given)" "$(faces "$R/qem.ply")" "" \
		"$(table1 "$R/st/1-mesh.ply" "$R/qem.ply")" "$(truth "$R/qem.ply" "$R/scene.ply")"
	echo "CPU seconds:$(stages -o "$R/m2.ply" "$@")"
done

echo
T=$dir/tum
planarize -K tum --keep "$T" -o "$dir/tum.ply" samples/tum/TUM_depth.png samples/tum/TUM_color.png
n=$(faces "$dir/tum.ply")
qemdecim -c -n "$n" -o "$dir/tumq.ply" "$T/1-mesh.ply"
echo "real TUM RGB-D frame (samples/tum), 640x480, no ground truth; the dense mesh has $(faces "$T/1-mesh.ply") faces"
printf "$hdr" method faces reduction "Table 1" ""
printf "$hdr" planarize "$n" "$(awk -v a="$(faces "$T/1-mesh.ply")" -v b="$n" 'BEGIN { printf "%.0f", a / b }')" \
	"$(table1 "$T/1-mesh.ply" "$dir/tum.ply")" ""
printf "$hdr" "qemdecim (dense given)" "$(faces "$dir/tumq.ply")" "" "$(table1 "$T/1-mesh.ply" "$dir/tumq.ply")" ""
echo "CPU seconds:$(stages -K tum -o "$dir/t2.ply" samples/tum/TUM_depth.png samples/tum/TUM_color.png) (goal: all 1.5)"
