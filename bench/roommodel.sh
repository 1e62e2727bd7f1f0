#!/bin/sh
# roommodel: the shared 7-Scenes frames (20 of redkitchen) to a textured
# model, end to end, beside tsdfuse's fusion of the same frames at the same
# voxel (2 cm) in the same run; medians of RUNS runs.  Issue 25's goal: the
# whole pipeline under 60 s on the project's machine.  Also mkscene's room,
# 24 views of 640x480 with the structured noise.
set -eu
: "${FCT_BIN:=build/bin}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir rm

faces() { meshinfo "$1" | awk '/^faces/ { print $2 }'; }
row() { printf '%-40s %9s %9s %9s %9s\n' "$1" "$2" "$3" "$4" "$5"; }

echo "roommodel: a sequence to a textured model (wall s, medians of $RUNS runs)"
row "input" "tsdfuse_s" "room_s" "fused" "model"

D=${FCT_DATA:-/work/shared/data}/7scenes_redkitchen/frames
if [ -d "$D" ]; then
	fuse=""
	for f in "$D"/*.depth.png; do fuse="$fuse --poses ${f%.depth.png}.pose.txt $f"; done
	ft=$(seconds tsdfuse -K 7scenes --voxel 0.02 $fuse -o "$dir/k.ply")
	rt=$(seconds roommodel --keep "$dir/k" -o "$dir/kitchen.obj" "$D")
	row "7-Scenes redkitchen, 20 frames" "$ft" "$rt" "$(faces "$dir/k/1-fused.ply")" "$(faces "$dir/kitchen.obj")"
else
	echo "roommodel.sh: $D missing: the 7-Scenes row skipped" >&2
fi

mkscene -q --views 24 --size 640x480 --noise kinect --albedo grain -o "$dir/seq"
fuse="" views=""
for i in $(seq 0 23); do
	n=$(printf %02d "$i")
	fuse="$fuse --poses $dir/seq/view$n.pose $dir/seq/view$n.depth.pfm"
	views="$views --poses $dir/seq/view$n.pose --image $dir/seq/view$n.color.png $dir/seq/view$n.depth.pfm"
done
K=525,525,319.5,239.5
ft=$(seconds tsdfuse -K $K --noise kinect --voxel 0.02 $fuse -o "$dir/s.ply")
rt=$(seconds roommodel -K $K --noise kinect --keep "$dir/s" -o "$dir/room.obj" $views)
row "mkscene room, 24 views 640x480, kinect" "$ft" "$rt" "$(faces "$dir/s/1-fused.ply")" "$(faces "$dir/room.obj")"
