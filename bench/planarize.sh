#!/bin/sh
# The planar pipeline (planarize) against a quadric edge-collapse decimation
# (qemdecim, Garland-Heckbert) of the same dense mesh to the same face count:
# faces, seconds, the paper's Table 1 errors (dense vertices to the model) and,
# on the synthetic room, the errors against the TRUE surface (accuracy:
# points sampled on the model to the exact scene; completeness: the true
# visible surface to the model).  Inputs: mkscene's furnished room, 640x480,
# Kinect-like noise (sigma = 0.0012 z^2), and the real TUM frame of samples/.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
dir=$(mktemp -d "${TMPDIR:-/tmp}/facet-bench-plan.XXXXXX")
trap 'rm -rf "$dir"' EXIT
T="$FCT_BENCH/timeit $RUNS"
mean() { meshdist "$@" | awk '$1 == "mean" { printf "%.5f", $2 }'; }
table1() { meshdist "$1" "$2" | awk '$1 == "mean" { m = $2 } $1 == "stdev" { s = $2 } $1 == "max" { x = $2 } END { printf "%.5f %.5f %.5f", m, s, x }'; }
faces() { meshinfo "$1" | awk '$1 == "faces:" { print $2 }'; }

mkscene --noise kinect-gauss:0.0012 -o "$dir/room" >/dev/null
R=$dir/room
planarize --camera "$R/view00.camera" --pose "$R/view00.pose" --keep "$dir/st" -o "$dir/model.ply" \
	"$R/view00.depth.pfm" "$R/view00.color.png"
dense=$dir/st/1-mesh.ply
n=$(faces "$dir/model.ply")
qemdecim -c -n "$n" -o "$dir/qem.ply" "$dense"
dm2mesh --camera "$R/view00.camera" --pose "$R/view00.pose" -o "$dir/truth.ply" "$R/view00.truth.pfm"
tp=$($T "planarize --camera '$R/view00.camera' --pose '$R/view00.pose' -o '$dir/m2.ply' '$R/view00.depth.pfm' '$R/view00.color.png'")
tq=$($T "qemdecim -c -n $n -o '$dir/q2.ply' '$dense'")
td=$($T "dm2mesh --camera '$R/view00.camera' --pose '$R/view00.pose' -o '$dir/d2.ply' '$R/view00.depth.pfm'")

echo "planar pipeline vs quadric decimation to the same face count; seconds are medians of $RUNS runs"
echo "synthetic furnished room (mkscene), 640x480, Kinect-like noise; the dense mesh has $(faces "$dense") faces"
echo "  dense mesh to the true surface (sampled): $(mean -s 200000 "$dense" "$R/scene.ply") m mean"
printf '%-28s %7s %8s  %-26s %12s %12s\n' "method" "faces" "seconds" "Table 1: E_avg E_std E_max" "to truth" "completeness"
printf '%-28s %7s %8s  %-26s %12s %12s\n' "planarize (all stages)" "$n" "$tp" "$(table1 "$dense" "$dir/model.ply")" \
	"$(mean -s 200000 "$dir/model.ply" "$R/scene.ply")" "$(mean "$dir/truth.ply" "$dir/model.ply")"
printf '%-28s %7s %8s  %-26s %12s %12s\n' "qemdecim (dense mesh given)" "$(faces "$dir/qem.ply")" "$tq" "$(table1 "$dense" "$dir/qem.ply")" \
	"$(mean -s 200000 "$dir/qem.ply" "$R/scene.ply")" "$(mean "$dir/truth.ply" "$dir/qem.ply")"
printf '%-28s %7s %8s\n' "reference: dm2mesh alone" "" "$td"

echo "real TUM RGB-D frame (samples/tum), no ground truth: Table 1 errors only"
planarize -K tum --keep "$dir/tum" -o "$dir/tum.ply" samples/tum/TUM_depth.png samples/tum/TUM_color.png
n=$(faces "$dir/tum.ply")
qemdecim -c -n "$n" -o "$dir/tumq.ply" "$dir/tum/1-mesh.ply"
printf '%-28s %7s  %-26s\n' "method" "faces" "Table 1: E_avg E_std E_max"
printf '%-28s %7s  %-26s\n' "planarize" "$n" "$(table1 "$dir/tum/1-mesh.ply" "$dir/tum.ply")"
printf '%-28s %7s  %-26s\n' "qemdecim" "$(faces "$dir/tumq.ply")" "$(table1 "$dir/tum/1-mesh.ply" "$dir/tumq.ply")"
echo "(the dense TUM mesh has $(faces "$dir/tum/1-mesh.ply") faces)"
