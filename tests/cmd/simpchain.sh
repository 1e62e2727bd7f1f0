# simpchain: patch boundaries cut into chains and simplified, on hand-made
# fixtures, on mkscene's exact scene meshes (whose true corners are known)
# and on a noiseless dm2mesh view labelled with the true planes
# (tests/data/chain_label.awk); every wireframe is checked independently by
# tests/data/chain_check.awk: labels valid, each vertex pair once, every
# patch's edges closed (in- and out-degree equal), and every original
# boundary vertex within the tolerance of the simplified boundary.  One
# golden file (tests/cmd/expected/simpchain_tri.ply, rewritten by make
# regold).
. tests/lib.sh

# report KEY FILE: a simpchain -v figure.
report() { sed -n "s/^simpchain: $1=//p" "$2"; }
# figure KEY FILE: a chain_check.awk figure.
figure() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }
# check_wire NAME INPUT WIREFRAME ERR: the invariants, and the distance bound.
check_wire() {
	awk -f tests/data/chain_check.awk "$2" "$3" >"$TMP/check"
	for k in bad_labels bad_index dup_pairs unbalanced; do
		check_num "$1: $k" "$(figure $k "$TMP/check")" "==" 0
	done
	check_num "$1: boundary vertices as simpchain counts them" "$(figure boundary "$TMP/check")" "==" "$(report boundary_vertices "$4")"
	check_num "$1: every boundary point within the tolerance" "$(figure max_dist "$TMP/check")" "<=" "$(report tolerance "$4")"
	check_num "$1: largest deviation within the tolerance" "$(report max_dev "$4")" "<=" "$(report tolerance "$4")"
	check_num "$1: edges as reported" "$(figure edges "$TMP/check")" "==" "$(report edges "$4")"
}

# Usage.
run_case 0 "simpchain --help | head -n 1 | grep -q '^usage: simpchain \[-aqv\] \[-o file\] \[-t threshold\] \[--keep-small-loops\] \[input\]$'"
run_case 0 "simpchain --version | grep -q '^simpchain (facet) '"
run_case 2 "simpchain -t 0,5 tests/data/chain_tri.ply" "" 'simpchain: -t: "0,5" is not a number'
run_case 2 "simpchain -t -1 tests/data/chain_tri.ply" "" "simpchain: -t: "
run_case 2 "simpchain -x tests/data/chain_tri.ply" "" "simpchain: -x: "
run_case 2 "simpchain a.ply b.ply" "" "simpchain: too many operands"
run_case 2 "simpchain -o $TMP/w.obj tests/data/chain_tri.ply" "" "simpchain: -o $TMP/w.obj: OBJ cannot hold the edge element"

# Bad and small input.  Faces without labels, and points without faces, are
# refused; labels past the planes too.
run_case 1 "simpchain tests/data/chain_nopatch.ply" "" "simpchain: tests/data/chain_nopatch.ply: faces have no patch property (label them with segplanes)"
run_case 1 "simpchain samples/bunny/bun_zipper_res3.ply" "" "simpchain: samples/bunny/bun_zipper_res3.ply: faces have no patch property"
run_case 1 "simpchain tests/data/chain_points.ply" "" "simpchain: tests/data/chain_points.ply: no faces with a patch property"
run_case 1 "simpchain < tests/data/chain_badlabel.ply" "" "simpchain: <stdin>: face 1: patch 5 is not -1 or a plane (1 planes)"
run_case 1 "printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n' | simpchain" "" "simpchain: <stdin>"
# An empty labelled mesh gives an empty wireframe.
run_case 0 "simpchain -a tests/data/chain_empty.ply > $TMP/empty.ply"
check_true "empty: no vertices, no edges" grep -q '^element edge 0$' "$TMP/empty.ply"
check_true "empty: no face element" sh -c "! grep -q '^element face' $TMP/empty.ply"
# One triangle: its three corners and its three edges, in its winding, the
# outside on the right; s t and the plane carried through.
run_case 0 "simpchain -a tests/data/chain_tri.ply" tests/cmd/expected/simpchain_tri.ply
# A wireframe is no input for another round: it has no faces.
run_case 1 "simpchain < tests/data/chain_tri.ply | simpchain -a" "" "simpchain: <stdin>: no faces with a patch property"

# mkscene's exact room: 42 kept vertices, its true corners: 8 of the room,
# 8 of each of the 3 boxes (their bottoms are the border of their own
# component), 6 of the ramp and 4 for the cylinder's cap, a loop of 24
# points against the curved side; 36 junctions.  Every crease is straight,
# so only the cap deviates.
S=$TMP/room
run_case 0 "mkscene --views 0 -o $S"
run_case 0 "simpchain -v -a -o $TMP/room.ply $S/scene.ply 2> $TMP/room.err"
run_case 0 "meshconv -a $S/scene.ply > $TMP/scene.ply"
check_wire room "$TMP/scene.ply" "$TMP/room.ply" "$TMP/room.err"
check_num "room: kept vertices" "$(report vertices_kept $TMP/room.err)" "==" 42
check_num "room: edges" "$(report edges $TMP/room.err)" "==" 60
check_num "room: junctions" "$(report junctions $TMP/room.err)" "==" 36
check_num "room: loops" "$(report loops $TMP/room.err)" "==" 1
check_num "room: boundary vertices" "$(report boundary_vertices $TMP/room.err)" "==" 134
check_true "room: planes and comments carried" grep -q '^element plane 25$' "$TMP/room.ply"
check_true "room: provenance of both stages" sh -c "grep -q '^comment facet mkscene' $TMP/room.ply && grep -q '^comment facet simpchain -v -a' $TMP/room.ply"
check_true "room: no faces" sh -c "! grep -q '^element face' $TMP/room.ply"
# Threshold 0 keeps every point not exactly on its segment: rounding puts
# all of them off, so all 134 stay.
run_case 0 "simpchain -v -t 0 $S/scene.ply 2> $TMP/room0.err > /dev/null"
check_num "room -t 0: kept vertices" "$(report vertices_kept $TMP/room0.err)" "==" 134
check_num "room -t 0: no deviation" "$(report max_dev $TMP/room0.err)" "==" 0
# The same bytes from the same input, from a file or a pipe (but for the
# provenance line, which names the file).
run_case 0 "simpchain -a $S/scene.ply | grep -v '^comment facet simpchain' > $TMP/r1.ply && cat $S/scene.ply | simpchain -a | grep -v '^comment facet simpchain' > $TMP/r2.ply && cmp -s $TMP/r1.ply $TMP/r2.ply"

# All faces one patch (mkscene's plane: one square face): the boundary is
# the border.  The default threshold (3 edges, here 3 times the side) leaves
# the loop its three points; below half the diagonal over the side (0.707)
# all four corners stay.
run_case 0 "mkscene --scene plane --views 0 -o $TMP/plane"
run_case 0 "simpchain -v -a $TMP/plane/scene.ply > $TMP/plane.ply 2> $TMP/plane.err"
check_num "plane: a loop keeps three points" "$(report vertices_kept $TMP/plane.err)" "==" 3
run_case 0 "simpchain -v -a -t 0.7 $TMP/plane/scene.ply > $TMP/plane.ply 2> $TMP/plane.err"
check_num "plane -t 0.7: its four corners" "$(report vertices_kept $TMP/plane.err)" "==" 4
check_num "plane: all edges against the outside" "$(awk '/^end_header/ { b = 1; next } b && NF == 4 && $4 == -1' $TMP/plane.ply | wc -l)" "==" 4

# A noiseless 320x240 view of the room through dm2mesh, each face labelled
# with the true plane holding its corners: boundaries that are pixel
# staircases in 3-D.
V=$TMP/view
run_case 0 "mkscene --size 320x240 --fx 262.5 -o $V"
run_case 0 "dm2mesh -a --camera $V/view00.camera --pose $V/view00.pose -o $V/mesh.ply $V/view00.depth.pfm"
meshconv -a "$V/scene.ply" | awk '/^element/ { name[ne] = $2; cnt[ne++] = $3 }
	/^end_header/ { b = 1; e = 0; r = 0; next }
	b { while (r >= cnt[e]) { e++; r = 0 } r++; if (name[e] == "plane") print $1, $2, $3, $4 }' >"$V/planes.txt"
run_case 0 "awk -f tests/data/chain_label.awk $V/planes.txt $V/mesh.ply > $V/labelled.ply"
run_case 0 "simpchain -v -a -o $V/wire.ply $V/labelled.ply 2> $V/err"
check_wire view "$V/labelled.ply" "$V/wire.ply" "$V/err"
# Measured: 3561 boundary vertices, 41 junctions, 110 kept at t = 3 (about
# 300 at t = 1), largest deviation 2.95 mean edges.
check_num "view: boundary vertices" "$(report boundary_vertices $V/err)" ">" 3000
check_num "view: 25 times fewer vertices kept" "$(awk -v k="$(report vertices_kept $V/err)" -v b="$(report boundary_vertices $V/err)" 'BEGIN { print k * 25 }')" "<" "$(report boundary_vertices $V/err)"
check_num "view: at least the visible corners" "$(report vertices_kept $V/err)" ">=" 40
check_num "view: deviation used" "$(report max_dev_edges $V/err)" ">" 2.5
check_num "view: no crossing left in the image" "$(report crossings_left_image $V/err)" "==" 0
check_true "view: camera and pose carried" sh -c "grep -q '^comment camera pinhole 320 240' $V/wire.ply && grep -q '^comment pose ' $V/wire.ply"
check_true "view: s t carried" grep -q '^property float s$' "$V/wire.ply"
run_case 0 "simpchain -v -t 1 -o $V/wire1.ply $V/labelled.ply 2> $V/err1"
check_num "view -t 1: more vertices than -t 3" "$(report vertices_kept $V/err1)" ">" "$(awk -v k="$(report vertices_kept $V/err)" 'BEGIN { print 2 * k }')"
check_num "view -t 1: deviation within one edge" "$(report max_dev_edges $V/err1)" "<=" 1
# The same view with every face in one patch: the border only, all of its
# edges against the outside.
awk '/^end_header/ { b = 1 } b && NF == 5 && $1 == 3 && $2 ~ /^[0-9]+$/ && $5 ~ /^-?[0-9]+$/ { $5 = 0 } { print }' "$V/labelled.ply" >"$V/one.ply"
run_case 0 "simpchain -v -a -o $V/onew.ply $V/one.ply 2> $V/one.err"
check_wire "one patch" "$V/one.ply" "$V/onew.ply" "$V/one.err"
check_num "one patch: only border edges" "$(awk '/^end_header/ { b = 1; next } b && NF == 4 && $4 != -1' $V/onew.ply | wc -l)" "==" 0
# Small loops: a noisy view at step 1 has holes where the depth-jump test cut
# faces; loops within the tolerance are dropped (holes filled), and no edge
# is left bounding them, unless --keep-small-loops.
L=$TMP/loops
run_case 0 "mkscene --size 320x240 --fx 262.5 --noise kinect-gauss:0.0029 -o $L"
run_case 0 "dm2mesh --camera $L/view00.camera $L/view00.depth.pfm | segplanes -o $L/seg.ply"
run_case 0 "simpchain -v -o $L/drop.ply $L/seg.ply 2> $L/drop.err"
run_case 0 "simpchain -v --keep-small-loops -o $L/keep.ply $L/seg.ply 2> $L/keep.err"
dropped=$(sed -n 's/^simpchain: loops_dropped=//p' $L/drop.err)
check_num "small loops dropped" "$dropped" ">" 10
check_num "none with --keep-small-loops" "$(sed -n 's/^simpchain: loops_dropped=//p' $L/keep.err)" == 0
edges() { meshinfo "$1" | awk '$1 == "element:" && $2 == "edge" { print $3 }'; }
check_num "at least three edges fewer per dropped loop" "$(($(edges $L/keep.ply) - $(edges $L/drop.ply)))" ">=" "$((3 * dropped))"

# A plane count of NaN or 1e300 was cast to long unchecked (undefined, caught
# by -fsanitize=float-cast-overflow): one line naming the plane and the value.
run_case 1 "simpchain tests/bad/planes_count_nan.ply" "" \
	"simpchain: tests/bad/planes_count_nan.ply: element plane 0: count nan is not a count of points"
run_case 1 "projverts tests/bad/planes_count_1e300.ply" "" \
	"projverts: tests/bad/planes_count_1e300.ply: element plane 0: count 1e+300 is not a count of points"

finish
