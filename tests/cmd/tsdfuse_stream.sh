# tsdfuse reads its views one at a time in every mode: the peak memory of
# 72 views of a room, carving and colour on, is at most 1.25 times that of
# 24 of them (before, every view stayed in memory: 2.3x here, 2.8x at
# 640x480); both fused rooms are closed and complete.
. tests/lib.sh

value() { awk -F= -v k="tsdfuse: $1" '$1 == k { print $2 }' "$TMP/err.$2"; }

S=$TMP/room
mkscene -q --views 72 --size 160x120 --fx 131.25 -o "$S" >/dev/null 2>&1
# views STEP: -K, then the --poses, --image and depth images of every
# STEP-th view.
views() {
	a="-K $(awk '{ print $5 "," $6 "," $7 "," $8 }' "$S/view00.camera")" p="" im="" d=""
	i=0
	while [ $i -lt 72 ]; do
		n=$(printf %02d $i)
		p="$p --poses $S/view$n.pose" im="$im --image $S/view$n.color.png" d="$d $S/view$n.depth.pfm"
		i=$((i + $1))
	done
	echo "$a $p $im $d"
}
for n in 24 72; do
	run_case 0 "tsdfuse -v --carve --voxel 0.04 -o $TMP/f$n.ply $(views $((72 / n)))"
	cp "$TMP/err" "$TMP/err.$n"
	check_num "$n views: fused" "$(value views $n)" == $n
	check_num "$n views: coloured vertices" "$(value colored_vertices $n)" ">" 1000
	# Carving closes the room (its closing walls are far from the truth),
	# and the truth is within a voxel of it.
	check_num "$n views: border edges" "$(meshinfo "$TMP/f$n.ply" | awk '$1 == "border_edges:" { print $2 }')" == 0
	meshdist -H "$TMP/f$n.ply" "$S/scene.ply" >"$TMP/d"
	check_num "$n views: completeness (m)" "$(awk '$1 == "ba_mean" { print $2 }' "$TMP/d")" "<" 0.04
done
p24=$(value peak_rss_mb 24) p72=$(value peak_rss_mb 72)
check_num "peak memory of 24 views (MB)" "$p24" ">" 0
# Under AddressSanitizer freed memory waits in its quarantine instead of
# serving the next view (1.252 here): the ratio is the allocator's, not
# tsdfuse's, and is asserted in plain builds only.
if [ -z "${FCT_SANITIZE:-}" ]; then
	check_num "peak memory: 72 views over 24" "$(awk -v a="$p72" -v b="$p24" 'BEGIN { print a / b }')" "<=" 1.25
else
	echo "tsdfuse_stream.sh: sanitizer build: peak memory ratio not asserted ($p72 / $p24 MB)"
fi
finish
