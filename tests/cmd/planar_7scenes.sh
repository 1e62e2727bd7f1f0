# The planar pipeline on a real Kinect frame (samples/7scenes, frame 0 of
# 7-Scenes redkitchen): the floor, the table top and the two runs of cabinet
# fronts, drawn by hand on its colour image (tests/data/7scenes_000000_
# regions.txt), each come out as one patch of segplanes (with planarize's
# --min-faces, one in 600 of the faces), 90% or more of each region's faces
# in its patch, the four patches distinct; and stay planes in planedecim's
# model, which is one manifold surface.  Quantised depth (steps of 11 mm at
# 2 m) once cut these fronts into 10 to 30 bands.
. tests/lib.sh
D=samples/7scenes
run_case 0 "dm2mesh -K 7scenes -o $TMP/d.ply $D/frame-000000.depth.png"
n=$(meshinfo "$TMP/d.ply" | awk '$1 == "faces:" { print int($2 / 600) }')
run_case 0 "segplanes -a --min-faces $n -o $TMP/s.ply $TMP/d.ply"
awk -f tests/data/regions_purity.awk tests/data/7scenes_000000_regions.txt "$TMP/s.ply" >"$TMP/purity"
for r in floor table cabinet_left cabinet_right; do
	check_num "$r: faces in the region" "$(awk -v r=$r '$1 == r { print $2 }' "$TMP/purity")" ">" 5000
	check_num "$r: one patch (share of its faces)" "$(awk -v r=$r '$1 == r { print $4 }' "$TMP/purity")" ">=" 0.9
	check_num "$r: a planar patch" "$(awk -v r=$r '$1 == r { print $3 }' "$TMP/purity")" ">=" 0
done
check_num "four distinct patches" "$(awk '{ print $3 }' "$TMP/purity" | sort -u | wc -l)" == 4
# The model keeps them as planes: faces of each of the four patches.
run_case 0 "planedecim -a -o $TMP/m.ply $TMP/s.ply"
for r in floor table cabinet_left cabinet_right; do
	p=$(awk -v r=$r '$1 == r { print $3 }' "$TMP/purity")
	check_num "$r: patch $p in the model" "$(awk -v p="$p" '/^end_header/ { h = 1; next } h && NF == 5 && $1 == 3 && $NF == p { n++ } END { print n + 0 }' "$TMP/m.ply")" ">" 0
done
meshinfo "$TMP/m.ply" >"$TMP/info"
check_num "model: no non-manifold edge" "$(awk '$1 == "non_manifold_edges:" { print $2 }' "$TMP/info")" == 0
check_num "model: no degenerate face" "$(awk '$1 == "degenerate_faces:" { print $2 }' "$TMP/info")" == 0
check_num "model: no duplicate face" "$(awk '$1 == "duplicate_faces:" { print $2 }' "$TMP/info")" == 0
check_num "model: 50x fewer faces than the dense mesh" \
	"$(awk '$1 == "faces:" { print $2 }' "$TMP/info")" "<" "$(meshinfo "$TMP/d.ply" | awk '$1 == "faces:" { print int($2 / 50) }')"

# The model does not depend on the coordinate frame the mesh is written in.
# The same frame in camera coordinates and moved rigidly (dm2mesh --pose:
# tests/data/7scenes_pose_turned.txt, made by hand: a turn of 1.6 rad about
# (1, 1, 0) and a shift of (-0.5, 3, 2) m), with the defaults: 99% of the
# faces in the same patches, the model's faces within 3%, and no patch had
# its whole outline tightened.  The patch of a cabinet front crossed its
# own outline at one spot in the turned frame and not in the camera's
# (rounding decides it); the whole outline was then kept as sampled: 5877
# faces against 4347 (+35%).  Mended where it crosses: 4236
# against 4408.  segplanes labelled 7.8% of the faces differently in the
# two frames: the quantised depth's plateaus are exactly flat in the
# camera's frame and flat to float rounding in the turned one, so their
# merges, tied at 0 in one frame, were ordered by rounding in the other.
# Residuals at rounding level now count as 0 in both: 0.11% differ, and
# the models are 4408 and 4429 faces.
for p in camera turned; do
	pose=
	[ $p = turned ] && pose="--pose tests/data/7scenes_pose_turned.txt"
	run_case 0 "dm2mesh -K 7scenes $pose -o $TMP/$p.d.ply $D/frame-000000.depth.png"
	run_case 0 "segplanes -a -o $TMP/$p.s.ply $TMP/$p.d.ply"
	run_case 0 "planedecim -v -o $TMP/$p.m.ply $TMP/$p.s.ply 2>$TMP/$p.err"
	check_num "$p frame: no whole outline tightened" "$(sed -n 's/^planedecim: tightened=//p' "$TMP/$p.err")" == 0
done
faces() { sed -n 's/^planedecim: faces=//p' "$TMP/$1.err"; }
check_num "turned frame: the camera frame's patches for 99% of the faces" \
	"$(awk -f tests/data/partition_agreement.awk "$TMP/camera.s.ply" "$TMP/turned.s.ply")" ">=" 0.99
check_num "turned frame: the camera frame's faces within 3%" \
	"$(awk -v a="$(faces turned)" -v b="$(faces camera)" 'BEGIN { d = a / b - 1; print d < 0 ? -d : d }')" "<" 0.03
finish
