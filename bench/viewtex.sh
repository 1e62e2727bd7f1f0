#!/bin/sh
# viewtex: the leave-views-out acceptance of issue 25 at full size, and the
# time it takes.  mkscene's room, 24 views of 640x480 with the structured
# noise and the grain albedo: 18 views fused by tsdfuse at 1 cm with vertex
# colour (the reference), and at 2 cm decimated by qemdecim to 1% of the
# reference's faces and textured by viewtex from the same 18 photos (one
# photo per face, and blended); all judged by viewjudge at the other 6.  The
# same on the shared 7-Scenes frames (15 textured, 5 judged).  Goals: PSNR
# over covered pixels at least the reference's, coverage at least 95% of
# its.  viewtex's time is the median of RUNS runs beside tsdfuse's 1 cm
# fusion of the same views in the same run.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
. bench/lib.sh
bench_dir vt

faces() { meshinfo "$1" | awk '/^faces/ { print $2 }'; }
judge() { viewjudge "$@" | awk '$1 == "all" { print $2, $3 }'; }
row() { printf '%-44s %9s %9s %9s\n' "$1" "$2" "$3" "$4"; }

# acceptance NAME TITLE K FUSE TRAIN HELD: the table of one sequence (NAME
# names its files).
acceptance() {
	name=$1 title=$2 K=$3 fuse=$4 train=$5 held=$6
	tsdfuse -K "$K" --voxel 0.01 $fuse -o "$dir/$name.f1.ply" 2>/dev/null
	tsdfuse -K "$K" --voxel 0.02 $fuse -o "$dir/$name.f2.ply" 2>/dev/null
	n1=$(faces "$dir/$name.f1.ply")
	qemdecim -q -c -n $((n1 / 100)) -o "$dir/$name.small.ply" "$dir/$name.f2.ply"
	viewtex -K "$K" -o "$dir/$name.one.obj" "$dir/$name.small.ply" $train 2>/dev/null
	viewtex --blend -K "$K" -o "$dir/$name.blend.obj" "$dir/$name.small.ply" $train 2>/dev/null
	row "$title" "faces" "covered" "PSNR dB"
	set -- $(judge -K "$K" "$dir/$name.f1.ply" $held)
	row "tsdfuse 1 cm, vertex colour (reference)" "$n1" "$1" "$2"
	set -- $(judge -K "$K" "$dir/$name.small.ply" $held)
	row "qemdecim to 1%, vertex colour" "$(faces "$dir/$name.small.ply")" "$1" "$2"
	set -- $(judge -K "$K" "$dir/$name.one.obj" $held)
	row "viewtex, one photo per face" "$(faces "$dir/$name.small.ply")" "$1" "$2"
	set -- $(judge -K "$K" "$dir/$name.blend.obj" $held)
	row "viewtex --blend" "$(faces "$dir/$name.small.ply")" "$1" "$2"
	tf=$(seconds tsdfuse -K "$K" --voxel 0.01 $fuse -o "$dir/t.ply")
	tv=$(seconds viewtex -K "$K" -o "$dir/t.obj" "$dir/$name.small.ply" $train)
	tb=$(seconds viewtex --blend -K "$K" -o "$dir/t.obj" "$dir/$name.small.ply" $train)
	printf 'seconds: tsdfuse 1 cm %.2f, viewtex %.2f (%.2fx), --blend %.2f (%.2fx)\n' "$tf" "$tv" \
		"$(awk -v a="$tv" -v b="$tf" 'BEGIN { print a / b }')" "$tb" \
		"$(awk -v a="$tb" -v b="$tf" 'BEGIN { print a / b }')"
}

mkscene -q --views 24 --noise kinect --albedo grain -o "$dir/room"
R=$dir/room
fuse="" train="" held=""
for i in $(seq 0 23); do
	n=$(printf %02d "$i")
	if [ $((i % 4)) != 3 ]; then
		fuse="$fuse --poses $R/view$n.pose --image $R/view$n.color.png $R/view$n.depth.pfm"
		train="$train --poses $R/view$n.pose $R/view$n.color.png"
	else
		held="$held --poses $R/view$n.pose $R/view$n.color.png"
	fi
done
echo "viewtex: leave views out (texture from 18, judge at 6; medians of $RUNS runs for times)"
acceptance room "mkscene room 640x480, kinect, grain" 525,525,319.5,239.5 "$fuse" "$train" "$held"

D=${FCT_DATA:-/work/shared/data}/7scenes_redkitchen/frames
if [ -d "$D" ] && imginfo "$D/frame-000000.color.jpg" >/dev/null 2>&1; then
	fuse="" train="" held="" i=0
	for f in "$D"/*.depth.png; do
		b=${f%.depth.png}
		if [ $((i % 4)) != 3 ]; then
			fuse="$fuse --poses $b.pose.txt --image $b.color.jpg $f"
			train="$train --poses $b.pose.txt $b.color.jpg"
		else
			held="$held --poses $b.pose.txt $b.color.jpg"
		fi
		i=$((i + 1))
	done
	echo
	acceptance kitchen "7-Scenes redkitchen, 20 frames" 585,585,320,240 "$fuse" "$train" "$held"
else
	echo "7-Scenes frames missing or no JPEG reader: skipped"
fi
echo "goals: PSNR at least the reference's, coverage at least 95% of its, at most 1% of its faces"
