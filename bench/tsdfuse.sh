#!/bin/sh
# tsdfuse: time per 640x480 view of mkscene's room (four views) at 2 cm and
# 1 cm voxels, true distance beside the projective baseline (--projective),
# carving against fusion, marching cubes throughput, and the Stanford bunny
# (ten scans, 0.5 mm) judged with meshdist both ways; the projective rows
# again from the depth images themselves (-K, --poses).  Goals (issue 7):
# true distance under 50 ms per view at 2 cm and 150 ms at 1 cm on one core;
# carving at most twice the fusion; marching cubes above 150 M voxels/s on
# one core; bunny within 0.10 mm both ways.  Medians of RUNS runs.
set -eu
: "${FCT_BIN:=build/bin}" "${FCT_BENCH:=build/bench}" "${RUNS:=3}"
PATH=$FCT_BIN:$PATH
dir=$(mktemp -d "${TMPDIR:-/tmp}/facet-bench-tsd.XXXXXX")
trap 'rm -rf "$dir"' EXIT
. bench/lib.sh

mkscene --views 4 -o "$dir/room" 2>/dev/null
V=""
for i in 00 01 02 03; do
	dm2mesh --camera "$dir/room/view$i.camera" --pose "$dir/room/view$i.pose" \
		-o "$dir/v$i.ply" "$dir/room/view$i.depth.pfm"
	V="$V $dir/v$i.ply"
done
# The same views as depth images (mkscene's PFM, metres) with -K from the
# camera files ("camera pinhole W H fx fy cx cy") and a 4x4 pose file each.
K=$(awk '{ print $5 "," $6 "," $7 "," $8 }' "$dir/room/view00.camera")
D="-K $K"
for i in 00 01 02 03; do
	D="$D --poses $dir/room/view$i.pose"
done
for i in 00 01 02 03; do
	D="$D $dir/room/view$i.depth.pfm"
done
# figure KEY ARGS...: median over RUNS of tsdfuse -v's KEY.
figure() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		tsdfuse -v "$@" 2>&1 >/dev/null | sed -n "s/^tsdfuse: $key=//p"
		i=$((i + 1))
	done | median
}
row() { printf '%-52s %12s\n' "$1" "$2"; }
# cell KEY ARGS...: the median run's KEY and read_s, as "ms ratio": KEY in
# ms per view and its ratio to the time that run took to read a view (a
# reference measured in the same process, so that a ratio can be quoted
# on a loaded machine).
cell() {
	key=$1
	shift
	i=0
	while [ $i -lt "$RUNS" ]; do
		tsdfuse -v "$@" 2>&1 >/dev/null |
			awk -F= '/^tsdfuse: ms_per_view=/ { m = $2 } /^tsdfuse: read_s=/ { r = $2 }
			         END { printf "%.2f %.2f\n", m, m / (r * 1000 / 4) }'
		i=$((i + 1))
	done | sort -n | awk '{ v[NR] = $0 } END { print v[int((NR + 1) / 2)] }'
}
echo "tsdfuse: mkscene room, four 640x480 views (610k faces each); ms per view, and"
echo "its ratio to reading one view in the same run (median of $RUNS runs)"
printf '%-36s %16s %16s\n' "" "1 thread" "all threads"
for mode in true projective depth; do
	for vox in 0.02 0.01; do
		m="" in=$V label="$mode $vox m"
		[ $mode != true ] && m=--projective
		[ $mode = depth ] && in=$D label="projective from depth images $vox m"
		a=$(cell ms_per_view --threads 1 $m --voxel $vox $in)
		b=$(cell ms_per_view $m --voxel $vox $in)
		printf '%-36s %8s (x%5s) %8s (x%5s)\n' "$label" ${a% *} ${a#* } ${b% *} ${b#* }
	done
done
echo "projective: the goal is Open3D's VoxelBlockGrid, 14 / 33 ms per view at 0.02 / 0.01 m on"
echo "one core of this machine; it is given each depth image and preallocates its blocks.  The"
echo "mesh rows include rasterising each view's mesh into its depth image; the depth-image rows"
echo "read the image itself (like Open3D; their ratio is to reading and meshing one image), and"
echo "all rows fault in the volume's memory as it grows"
row "fusion s at 0.02 m (4 views)" "$(figure fuse_s --voxel 0.02 $V)"
row "carving s at 0.02 m (4 views)" "$(figure carve_s --carve --voxel 0.02 $V)"
# Marching cubes on the fused room at 1 cm (M voxels/s: allocated blocks *
# 512 over the time, the voxels the extraction must look at, as a dense
# volume's every voxel or Open3D's active blocks).  The goal is judged on
# one core: tsdfuse's own mcubes_s with --threads 1 (wall, everything
# fct_mcubes_stats does: output allocation, every pass, the page faults of
# the output arrays malloc does not find in memory the views freed), and
# gen_mcubes timing the extraction alone on the same volume in CPU seconds
# (steadier on a shared machine), every run into fresh memory (all of the
# output's pages faulted in: the extraction's cost in a one-shot program
# with nothing freed before it); the default thread count beside them.
mvox() { awk -v b="$1" -v s="$2" 'BEGIN { printf "%.0f", b * 512 / s / 1e6 }'; }
blocks=$(figure blocks --voxel 0.01 $V)
mc1=$(figure mcubes_s --threads 1 --voxel 0.01 $V)
mc=$(figure mcubes_s --voxel 0.01 $V)
"$FCT_BENCH/gen_mcubes" -r "$RUNS" -t 1 fused $V >"$dir/mc"
mcc=$(sed -n 's/^mcubes_s=//p' "$dir/mc")
echo "marching cubes on the room at 0.01 m: $blocks blocks, $(sed -n 's/^faces=//p' "$dir/mc") faces," \
	"$(sed -n 's/^cubes=//p' "$dir/mc") cubes ($(sed -n 's/^ambiguous=//p' "$dir/mc") ambiguous);" \
	"alone: fresh output, $(sed -n 's/^mcubes_faults=//p' "$dir/mc") page faults per extraction"
row "marching cubes s, 1 thread (wall)" "$mc1"
row "marching cubes M voxels/s, 1 thread (wall)" "$(mvox "$blocks" "$mc1")"
row "marching cubes M voxels/s, 1 thread (CPU, alone)" "$(mvox "$blocks" "$mcc")"
row "marching cubes M voxels/s, all threads (wall)" "$(mvox "$blocks" "$mc")"
echo "marching cubes alone, ms per phase (wall, median): $(sed -n 's/^phase_ms=//p' "$dir/mc" |
	awk '{ printf "pass 0 %s, pass 1 %s, pass 2 %s, allocation %s, vertices %s, triangles %s", $1, $2, $3, $4, $5, $6 }')"

# Memory: the views are read one at a time, so 72 views of the room cost
# about what 24 do (issue 25: at most 1.25 times), carving and colour on,
# depth images with their colour images, at 0.02 m; tsdfuse's own peak RSS.
mkscene -q --views 72 -o "$dir/room72" >/dev/null 2>&1
views() {
	a="-K $K" i=0
	while [ $i -lt 72 ]; do
		n=$(printf %02d $i)
		a="$a --poses $dir/room72/view$n.pose --image $dir/room72/view$n.color.png"
		i=$((i + $1))
	done
	i=0
	while [ $i -lt 72 ]; do
		a="$a $dir/room72/view$(printf %02d $i).depth.pfm"
		i=$((i + $1))
	done
	echo "$a"
}
m24=$(tsdfuse -v --carve --voxel 0.02 $(views 3) 2>&1 >/dev/null | sed -n 's/^tsdfuse: peak_rss_mb=//p')
m72=$(tsdfuse -v --carve --voxel 0.02 $(views 1) 2>&1 >/dev/null | sed -n 's/^tsdfuse: peak_rss_mb=//p')
row "peak memory MB, 24 views, --carve --color, 0.02 m" "$m24"
row "peak memory MB, 72 views, --carve --color, 0.02 m" "$m72"
row "peak memory, 72 views over 24 (goal <= 1.25)" "$(awk -v a="$m72" -v b="$m24" 'BEGIN { printf "%.3f", a / b }')"

B=/work/shared/data/stanford_bunny
if [ -r "$B/data/bun.conf" ]; then
	t=$(figure total_s --voxel 0.0005 --conf "$B/data/bun.conf")
	tsdfuse --voxel 0.0005 --conf "$B/data/bun.conf" -o "$dir/bun.ply"
	meshdist -H "$dir/bun.ply" "$B/reconstruction/bun_zipper.ply" >"$dir/d"
	row "bunny 0.5 mm: total s" "$t"
	row "bunny accuracy mm (output to bun_zipper)" "$(awk '$1 == "mean" { printf "%.4f", $2 * 1000 }' "$dir/d")"
	row "bunny completeness mm (bun_zipper to output)" "$(awk '$1 == "ba_mean" { printf "%.4f", $2 * 1000 }' "$dir/d")"
fi
