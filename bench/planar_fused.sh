#!/bin/sh
# The planar model of a fused scan (issue 23's fused acceptance): the 20
# 7-Scenes kitchen frames of ../shared/data/7scenes_redkitchen fused by
# tsdfuse (-K 7scenes: the dataset's poses and Kinect noise model, 1 cm),
# as they come and carved (--carve: watertight), then planarize on the
# fused mesh (no camera), beside qemdecim at the same face count: of the
# fused mesh as it is, and of the fused mesh without its floating debris
# (tsdfuse --min-piece 64: the pieces planarize drops), which is what the
# model stands for.  Distances in mm by meshdist -p -H -s 200000 against the
# fused mesh: model->fused mean, p95, max and fused->model mean; meshinfo's
# non-manifold edges, degenerate and duplicate faces, border edges and
# pieces of the model.  The goals: at least 100x fewer faces than the fused
# mesh, model->fused mean no worse than qemdecim's, no non-manifold edge,
# degenerate or duplicate face.  Skipped with a message without the data.
set -eu
: "${FCT_BIN:=build/bin}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir fused

kitchen_frames
if [ -z "$kitchen" ]; then
	echo "planar_fused.sh: no 7scenes_redkitchen in ../shared/data: skipped" >&2
	exit 0
fi
views=""
for f in "$kitchen"/frame-*.depth.png; do views="$views --poses ${f%.depth.png}.pose.txt $f"; done

info() { meshinfo "$2" | awk -v k="$1:" '$1 == k { print $2 }'; }
mm() { awk -v k="$1" '$1 == k { printf "%.1f", $2 * 1000 }' "$2"; }
# dist NAME MESH FUSED: "mean p95 max ba_mean" of MESH against FUSED, in mm
dist() {
	meshdist -p -H -s 200000 "$2" "$3" >"$dir/$1.dist"
	printf '%5s %5s %6s %6s' "$(mm mean "$dir/$1.dist")" "$(mm p95 "$dir/$1.dist")" \
		"$(mm max "$dir/$1.dist")" "$(mm ba_mean "$dir/$1.dist")"
}

echo "the planar model of tsdfuse's 20 7-Scenes frames at 1 cm (planarize, defaults) beside qemdecim at the same face count"
echo "mm against the fused mesh: model->fused mean p95 max, fused->model mean; qemdecim's of the fused mesh (Q) and of it without its debris (Qd)"
printf '%-8s %8s %7s %6s | %5s %5s %6s %6s | %5s %5s %6s %6s | %5s %5s %6s %6s | %3s %3s %3s %6s %6s\n' \
	fusion fused model x mean p95 max f2m Qmean Qp95 Qmax Qf2m Qdmn Qdp95 Qdmax Qdf2m nm dg dup border pieces
for fusion in plain carve; do
	opt=""
	[ "$fusion" = carve ] && opt=--carve
	f=$dir/$fusion
	# shellcheck disable=SC2086
	tsdfuse -q $opt -K 7scenes --voxel 0.01 -o "$f.ply" $views
	planarize -v -o "$f.model.ply" "$f.ply" 2>"$f.err"
	n=$(info faces "$f.model.ply") nf=$(info faces "$f.ply")
	# The fused mesh without the pieces the model dropped (the same
	# library call, the same default).
	# shellcheck disable=SC2086
	tsdfuse -q $opt -K 7scenes --voxel 0.01 --min-piece 64 -o "$f.d.ply" $views
	qemdecim -q -n "$n" -o "$f.q.ply" "$f.ply"
	qemdecim -q -n "$n" -o "$f.qd.ply" "$f.d.ply"
	printf '%-8s %8s %7s %6.1f | %s | %s | %s | %3s %3s %3s %6s %6s\n' "$fusion" "$nf" "$n" \
		"$(awk -v a="$nf" -v b="$n" 'BEGIN { print (b > 0 ? a / b : 0) }')" \
		"$(dist "$fusion.m" "$f.model.ply" "$f.ply")" "$(dist "$fusion.q" "$f.q.ply" "$f.ply")" \
		"$(dist "$fusion.qd" "$f.qd.ply" "$f.ply")" \
		"$(info non_manifold_edges "$f.model.ply")" "$(info degenerate_faces "$f.model.ply")" \
		"$(info duplicate_faces "$f.model.ply")" "$(info border_edges "$f.model.ply")" \
		"$(info components "$f.model.ply")"
done
