#!/bin/sh
# The planar model on real depth frames (issue 23's table): dm2mesh |
# segplanes | planedecim with their defaults, beside a quadric edge-collapse
# decimation (qemdecim) of the same dense mesh to the same face count.
# Frames: the 20 7-Scenes kitchen frames of ../shared/data/7scenes_redkitchen
# (dm2mesh -K 7scenes; skipped with a message when absent), the TUM frame
# of samples/tum (-K tum), and the NYU Depth v2 and SUN RGB-D frames of
# ../shared/data/rgbd_single_frames_formats when there (-K nyu, and -K
# primesense --depth-code sun: SUN's camera is not recorded with it).  Distances in mm by meshdist -p -H -s
# 200000 (200000 points spread by area on each surface, seed 1) against the
# frame's own dense mesh (raw): model->raw mean, p95 and max, raw->model
# mean; the same for qemdecim.  CPU seconds: each stage's -v cpu_s, one run
# a frame (their medians over the frames at the end), and qemdecim's on the
# same dense mesh in the same sitting, the reference that holds on a
# machine faster or slower than the day's: the pipeline's time over it.
# The goals are
# issue 23's: model->raw and raw->model means no worse than qemdecim's,
# model->raw max under 100 mm, at least 50x fewer faces than the dense mesh.
set -eu
: "${FCT_BIN:=build/bin}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir real

kitchen_frames
# The frames, as "name camera depth-image [dm2mesh options]" lines.
{
	if [ -n "$kitchen" ]; then
		for f in "$kitchen"/frame-*.depth.png; do
			n=${f##*/frame-}
			echo "${n%.depth.png} 7scenes $f"
		done
	fi
	echo "tum tum samples/tum/TUM_depth.png"
	for o in ../shared/data/rgbd_single_frames_formats /work/shared/data/rgbd_single_frames_formats; do
		[ -f "$o/NYU_depth.pgm" ] || continue
		echo "nyu nyu $o/NYU_depth.pgm"
		echo "sun primesense $o/SUN_depth.png --depth-code sun"
		break
	done
} >"$dir/frames"
# cpu STAGE FILE: the cpu_s figure of a stage's -v output.
cpu() { sed -n "s/^$1: cpu_s=//p" "$2"; }
# dist A B: model->raw mean p95 max and raw->model mean, in mm.
dist() {
	meshdist -p -H -s 200000 "$1" "$2" |
		awk '{ v[$1] = $2 * 1000 } END { printf "%6.1f %5.1f %5.0f %6.1f", v["mean"], v["p95"], v["max"], v["ba_mean"] }'
}

echo "the planar model on real frames (dm2mesh | segplanes | planedecim, defaults) against qemdecim at the same face count"
[ -n "$kitchen" ] || echo "(no 7scenes_redkitchen in ../shared/data: the 7-Scenes frames skipped)"
echo "distances in mm to the frame's dense mesh (meshdist -p -H -s 200000); CPU seconds of one run per stage"
printf '%-7s %6s %5s | %6s %5s %5s %6s | %6s %5s %6s | %6s %6s %6s | %6s %5s\n' frame faces red \
	m2r p95 max r2m Qm2r Qp95 Qr2m dm2mesh seg plane qemdec /Q
while read -r name cam depth extra; do
	d=$dir/$name
	# shellcheck disable=SC2086
	dm2mesh -v -K "$cam" $extra -o "$d.raw.ply" "$depth" 2>"$d.dm.err"
	if ! segplanes -v -o "$d.seg.ply" "$d.raw.ply" 2>"$d.seg.err" ||
	   ! planedecim -v -o "$d.model.ply" "$d.seg.ply" 2>"$d.pd.err"; then
		echo "$name: FAILED: $(tail -n 1 "$d.seg.err") $(tail -n 1 "$d.pd.err" 2>/dev/null)"
		continue
	fi
	n=$(sed -n 's/^planedecim: faces=//p' "$d.pd.err")
	red=$(sed -n 's/^planedecim: reduction=//p' "$d.pd.err")
	qemdecim -v -n "$n" -o "$d.qem.ply" "$d.raw.ply" 2>"$d.qem.err"
	m=$(dist "$d.model.ply" "$d.raw.ply")
	q=$(dist "$d.qem.ply" "$d.raw.ply")
	t="$(cpu dm2mesh "$d.dm.err") $(cpu segplanes "$d.seg.err") $(cpu planedecim "$d.pd.err") $(cpu qemdecim "$d.qem.err")"
	printf '%-7s %6s %5.0f | %s | %s | %s\n' "$name" "$n" "$red" "$m" \
		"$(echo "$q" | awk '{ printf "%6.1f %5.1f %6.1f", $1, $2, $4 }')" \
		"$(echo "$t" | awk '{ printf "%6s %6s %6s | %6s %5.2f", $1, $2, $3, $4, ($1 + $2 + $3) / $4 }')"
	echo "$name $n $red $m $q $t" >>"$dir/rows"
	rm -f "$d".*.ply
done <"$dir/frames"

[ -s "$dir/rows" ] || exit 0
# Fields of rows: 1 name, 2 faces, 3 reduction, 4-7 model m2r mean p95 max
# r2m, 8-11 qemdecim's, 12-14 CPU seconds of the stages, 15 qemdecim's.
col() { awk -v c="$1" '{ print $c }' "$dir/rows" | median; }
ratio=$(awk '{ print ($12 + $13 + $14) / $15 }' "$dir/rows" | median)
printf '%-7s %6s %5.0f | %6.1f %5.1f %5.0f %6.1f | %6.1f %5.1f %6.1f | %6s %6s %6s | %6s %5.2f\n' median \
	"$(col 2)" "$(col 3)" "$(col 4)" "$(col 5)" "$(col 6)" "$(col 7)" "$(col 8)" "$(col 9)" "$(col 11)" \
	"$(col 12)" "$(col 13)" "$(col 14)" "$(col 15)" "$ratio"
# The goals count issue 23's frames (the kitchen's and TUM's), not the
# NYU and SUN frames beside them.
awk '$1 != "nyu" && $1 != "sun" { n++; m += $4 <= $8; r += $7 <= $11; x += $6 < 100; f += $3 >= 50
	cpu = $12 + $13 + $14; if (cpu > worst) { worst = cpu; wq = $15 } }
	END { printf "goals met, of the issue'"'"'s %d frames: model->raw mean <= qemdecim %d, raw->model mean <= qemdecim %d, max < 100 mm %d, >= 50x fewer faces %d; slowest frame %.2f s CPU (goal 1.5; qemdecim %.2f s on it)\n", n, m, r, x, f, worst, wq }' "$dir/rows"

# What the distance to the raw mesh rewards.  On noisy depth a decimation
# spends its faces following the noise: on 7-Scenes frame 000500's far wall
# (2.6 m, 10 mm of noise) qemdecim at the model's count puts 1375 faces
# where the model has 91, and tilts 63% of their area 20 degrees or more
# off the wall, which lies within 4 mm of the raw points that the wall's
# plane misses by 8.  mkscene's room under the same Kinect model has
# the truth: qemdecim at 1 to 30 times the model's face count, each to the
# true surface and to the raw mesh (mean, mm; 200000 points).  Its distance
# to the raw mesh falls as it follows the noise while its distance to the
# truth rises; the model is closer to the truth than any of them.
R=$dir/room
mkscene -q --noise kinect -o "$R" >/dev/null
planarize --camera "$R/view00.camera" --pose "$R/view00.pose" --noise "$R/view00.noise" \
	--keep "$R/st" -o "$R/model.ply" "$R/view00.depth.pfm"
n=$(awk '$1 == "element" && $2 == "face" { print $3; exit }' "$R/model.ply")
# mean_mm A B: the mean distance from A to B, in mm.
mean_mm() { meshdist -s 200000 "$1" "$2" | awk '$1 == "mean" { printf "%6.2f", $2 * 1000 }'; }
echo
echo "the raw-distance yardstick on mkscene's room with Kinect noise (truth known): mean distances in mm"
printf '%-22s %6s | %6s %6s %6s\n' mesh faces truth m2r r2m
printf '%-22s %6s | %6s %6s %6s\n' "planar model" "$n" "$(mean_mm "$R/model.ply" "$R/scene.ply")" \
	"$(mean_mm "$R/model.ply" "$R/st/1-mesh.ply")" "$(mean_mm "$R/st/1-mesh.ply" "$R/model.ply")"
for k in 1 2 5 10 30; do
	qemdecim -c -n $((k * n)) -o "$R/qem.ply" "$R/st/1-mesh.ply"
	printf '%-22s %6s | %6s %6s %6s\n' "qemdecim, ${k}x the count" $((k * n)) "$(mean_mm "$R/qem.ply" "$R/scene.ply")" \
		"$(mean_mm "$R/qem.ply" "$R/st/1-mesh.ply")" "$(mean_mm "$R/st/1-mesh.ply" "$R/qem.ply")"
done
printf '%-22s %6s | %6s\n' "dense mesh" "$(awk '$1 == "element" && $2 == "face" { print $3; exit }' "$R/st/1-mesh.ply")" \
	"$(mean_mm "$R/st/1-mesh.ply" "$R/scene.ply")"

# Closer to the truth?  A real frame has no ground truth, and its own dense
# mesh carries the sensor's disparity steps and warp, which qemdecim follows
# and planes average out.  The 20 kitchen frames fused at 1 cm (tsdfuse -K
# 7scenes with their poses) average each frame's steps over other viewpoints
# and stand in for the truth.  Each frame again in the world frame
# (dm2mesh --pose), its model and qemdecim at the same face count, and its
# dense mesh, measured to the fused mesh from their side only (the fusion
# covers more than one frame sees): mean and median in mm.  The frame is one
# of the 20 fused, which favours its dense mesh and qemdecim, not the model.
[ -n "$kitchen" ] || exit 0
set --
for d in "$kitchen"/frame-*.depth.png; do
	set -- "$@" --poses "${d%.depth.png}.pose.txt" "$d"
done
tsdfuse -K 7scenes --voxel 0.01 -o "$dir/fused.ply" "$@"
# tofused A: A->fused mean and median, in mm.
tofused() {
	meshdist -p -s 200000 "$1" "$dir/fused.ply" |
		awk '{ v[$1] = $2 * 1000 } END { printf "%6.2f %6.2f", v["mean"], v["p50"] }'
}
echo
echo "closer to the truth: the 20 kitchen frames fused (tsdfuse -K 7scenes, 1 cm, $(awk '$1 == "element" && $2 == "face" { print $3 }' "$dir/fused.ply" | head -n 1) faces) as a stand-in;"
echo "each frame in the world frame, model / qemdecim at the same count / dense mesh -> fused, mean and median in mm"
printf '%-7s %6s | %6s %6s | %6s %6s | %6s %6s\n' frame faces model p50 qem p50 dense p50
: >"$dir/truth"
while read -r name cam depth extra; do
	[ "$cam" = 7scenes ] || continue
	d=$dir/w$name
	dm2mesh -K 7scenes --pose "${depth%.depth.png}.pose.txt" -o "$d.raw.ply" "$depth"
	segplanes -o "$d.seg.ply" "$d.raw.ply" && planedecim -o "$d.model.ply" "$d.seg.ply" || continue
	n=$(awk '$1 == "element" && $2 == "face" { print $3; exit }' "$d.model.ply")
	qemdecim -n "$n" -o "$d.qem.ply" "$d.raw.ply"
	row="$(tofused "$d.model.ply") $(tofused "$d.qem.ply") $(tofused "$d.raw.ply")"
	# shellcheck disable=SC2086
	printf '%-7s %6s | %6s %6s | %6s %6s | %6s %6s\n' "$name" "$n" $row
	echo "$name $n $row" >>"$dir/truth"
	rm -f "$d".*.ply
done <"$dir/frames"
[ -s "$dir/truth" ] || exit 0
tcol() { awk -v c="$1" '{ print $c }' "$dir/truth" | median; }
printf '%-7s %6s | %6.2f %6.2f | %6.2f %6.2f | %6.2f %6.2f\n' median "$(tcol 2)" "$(tcol 3)" "$(tcol 4)" \
	"$(tcol 5)" "$(tcol 6)" "$(tcol 7)" "$(tcol 8)"
awk '{ n++; q += $3 < $5; r += $3 < $7 }
	END { printf "model closer to the fused kitchen than qemdecim on %d of %d frames, than the dense mesh on %d\n", q, n, r }' "$dir/truth"
