# tsdfuse --color: a flat view of a uniform image gives exactly its colour,
# vertices no image sees get grey 128 (and are counted), depth images with
# --image colour as their meshes do, sunfuse passes --color on, bad input.
# The colour error against a scene's truth is asserted in test_viewcolor.
. tests/lib.sh

value() { awk -F= -v k="tsdfuse: $1" '$1 == k { print $2 }' "$TMP/err"; }

# A 2x2 colour PFM of (1, 0.25, 0) everywhere: 255 64 0 in 8 bits.
{
	printf 'PF\n2 2\n-1.0\n'
	for i in 1 2 3 4; do printf '\000\000\200\077\000\000\200\076\000\000\000\000'; done
} >"$TMP/orange.pfm"

# square X0 SHIFT TEXTURE: a 17x17 grid over [-0.8, 0.8]^2 at z = 2 seen
# by the 640x480 camera at (SHIFT, 0, 0), wound towards it.
square() {
	awk -v s="$1" -v tex="$2" 'BEGIN {
		n = 16
		print "ply"; print "format ascii 1.0"
		print "comment camera pinhole 640 480 525 525 319.5 239.5"
		print "comment pose 1 0 0 " s " 0 1 0 0 0 0 1 0"
		if (tex != "") print "comment TextureFile " tex
		print "element vertex " (n + 1) * (n + 1)
		print "property float x"; print "property float y"; print "property float z"
		print "element face " 2 * n * n
		print "property list uchar int vertex_indices"; print "end_header"
		for (j = 0; j <= n; j++)
			for (i = 0; i <= n; i++)
				print s - 0.8 + 1.6 * i / n, -0.8 + 1.6 * j / n, 2
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				a = j * (n + 1) + i; b = a + 1; c = a + n + 1; d = c + 1
				print 3, a, c, b; print 3, b, c, d
			}
	}'
}
square 0 orange.pfm >"$TMP/lit.ply"
square 3 "" >"$TMP/dark.ply"

# One flat view of a uniform image: every vertex exactly 255 64 0.
run_case 0 "tsdfuse -a -v --color --voxel 0.05 -o $TMP/one.ply $TMP/lit.ply"
check_num "flat: vertices" "$(value vertices)" ">" 500
check_num "flat: none uncoloured" "$(value uncolored_vertices)" == 0
check_num "flat: one view each" "$(value views_per_vertex)" == 1
awk '/^end_header/ { h = 1; next } h && NF == 9 { n++; if ($7 != 255 || $8 != 64 || $9 != 0) bad++ }
     END { print n + 0, bad + 0 }' "$TMP/one.ply" >"$TMP/c"
check_num "flat: every vertex has the image's colour" "$(awk '{ print $2 }' "$TMP/c")" == 0
check_num "flat: vertices checked" "$(awk '{ print $1 }' "$TMP/c")" ">" 500

# A second view without an image, 3 m to the right: its vertices are seen
# by no image and get grey 128; the reported count is theirs.
run_case 0 "tsdfuse -a -v --color --voxel 0.05 -o $TMP/two.ply $TMP/lit.ply $TMP/dark.ply"
awk '/^end_header/ { h = 1; next }
     h && NF == 9 { if ($1 < 1.5) { l++; if ($7 != 255 || $8 != 64 || $9 != 0) bad++ }
                    else { g++; if ($7 != 128 || $8 != 128 || $9 != 128) bad++ } }
     END { print l + 0, g + 0, bad + 0 }' "$TMP/two.ply" >"$TMP/c"
check_num "fallback: wrong colours" "$(awk '{ print $3 }' "$TMP/c")" == 0
check_num "fallback: grey vertices counted" "$(value uncolored_vertices)" == "$(awk '{ print $2 }' "$TMP/c")"
check_num "fallback: grey vertices exist" "$(awk '{ print $2 }' "$TMP/c")" ">" 500
check_num "fallback: colour views" "$(value color_views)" == 1
# Without --color nothing changes: no colour properties.
run_case 0 "tsdfuse -a --voxel 0.05 -o $TMP/plain.ply $TMP/lit.ply"
check_true "no colour without --color" sh -c "! grep -q '^property uchar red' $TMP/plain.ply"
# No view has an image: a warning, and every vertex grey.
run_case 0 "tsdfuse -a --color --voxel 0.05 -o $TMP/grey.ply $TMP/dark.ply" "" "tsdfuse: warning: --color: no view"

# mkscene's room: views as meshes with TextureFile (dm2mesh --image) and as
# depth images with -K, --poses and --image (meshed a little differently)
# give models of the same mean colour.
S=$TMP/room
mkscene --views 2 --size 160x120 --fx 131.25 -o "$S" 2>/dev/null
for i in 00 01; do
	dm2mesh --camera "$S/view$i.camera" --pose "$S/view$i.pose" --image "$S/view$i.color.png" \
		-o "$TMP/v$i.ply" "$S/view$i.depth.pfm"
done
run_case 0 "tsdfuse -v --color --voxel 0.04 -o $TMP/m.ply $TMP/v00.ply $TMP/v01.ply"
check_num "room: colour views" "$(value color_views)" == 2
check_num "room: uncoloured under 1 percent" "$(value uncolored_vertices)" "<" "$(( $(value vertices) / 100 ))"
run_case 0 "tsdfuse -v --color -K 131.25,131.25,79.5,59.5 --poses $S/view00.pose --poses $S/view01.pose \
	--image $S/view00.color.png --image $S/view01.color.png --voxel 0.04 -o $TMP/d.ply \
	$S/view00.depth.pfm $S/view01.depth.pfm"
check_num "depth images: colour views" "$(value color_views)" == 2
check_num "depth images: uncoloured under 1 percent" "$(value uncolored_vertices)" "<" "$(( $(value vertices) / 100 ))"
meshconv -a -o "$TMP/m.txt" "$TMP/m.ply"
meshconv -a -o "$TMP/d.txt" "$TMP/d.ply"
mean() { awk '/^end_header/ { h = 1; next } h && NF == 9 { n++; r += $7; g += $8; b += $9 }
              END { printf "%.2f %.2f %.2f\n", r / n, g / n, b / n }' "$1"; }
mm=$(mean "$TMP/m.txt") md=$(mean "$TMP/d.txt")
check_num "depth images = meshes: mean colour within 2 levels" \
	"$(echo "$mm $md" | awk '{ d = 0; for (k = 1; k <= 3; k++) { e = $k - $(k + 3); d = e > d ? e : -e > d ? -e : d }; print d }')" "<" 2
# The same colours for any thread count.
run_case 0 "tsdfuse --color --threads 1 --voxel 0.04 -o $TMP/t1.ply $TMP/v00.ply $TMP/v01.ply"
run_case 0 "tsdfuse --color --threads 3 --voxel 0.04 -o $TMP/t3.ply $TMP/v00.ply $TMP/v01.ply"
meshconv -a -o "$TMP/t1.txt" "$TMP/t1.ply"
meshconv -a -o "$TMP/t3.txt" "$TMP/t3.ply"
check_true "threads: the same colours" \
	sh -c "grep -v '^comment' $TMP/t1.txt >$TMP/a1 && grep -v '^comment' $TMP/t3.txt >$TMP/a3 && cmp -s $TMP/a1 $TMP/a3"

# sunfuse passes --color on (and gives dm2mesh each view's colour image).
run_case 0 "sunfuse --color --voxel 0.04 -o $TMP/sun.ply $S"
check_true "sunfuse --color: vertex colour" sh -c "meshinfo $TMP/sun.ply | grep -q 'vertex uchar red'"

# Bad input.
run_case 2 "tsdfuse --color -K 131.25,131.25,79.5,59.5 --poses $S/view00.pose --poses $S/view01.pose \
	--image $S/view00.color.png $S/view00.depth.pfm $S/view01.depth.pfm" "" "tsdfuse: 2 depth views but 1 --image"
sed 's/^comment TextureFile orange.pfm/comment TextureFile missing.png/' "$TMP/lit.ply" >"$TMP/missing.ply"
run_case 1 "tsdfuse --color -o $TMP/x.ply $TMP/missing.ply" "" "tsdfuse: $TMP/missing.png: "
finish
