# qemdecim: quadric edge-collapse decimation of mkscene views against their
# exact ground truth (meshdist to scene.ply and to the noise-free view),
# exact face counts, validity (meshinfo), properties and comments carried,
# determinism, polygons, bad input and usage.
. tests/lib.sh
D=tests/data

# figure KEY FILE: the value of "KEY value" lines (meshdist), "KEY: value"
# lines (meshinfo) or "prog: KEY=value" lines (-v).
figure() {
	awk -v k="$1" '$1 == k || $1 == k ":" { print $2; exit }
		index($0, ": " k "=") { sub(/.*=/, ""); print; exit }' "$2"
}

# A plane filling the view: 37842 triangles to 2, on the plane (float
# coordinates: within 1e-6) and covering the same rectangle (Hausdorff
# distance both ways 1e-6).
mkscene --scene plane --size 160x120 -o "$TMP/p" >/dev/null
dm2mesh --camera "$TMP/p/view00.camera" --pose "$TMP/p/view00.pose" -o "$TMP/p.ply" "$TMP/p/view00.depth.pfm"
run_case 0 "qemdecim -v -n 2 -o $TMP/p2.ply $TMP/p.ply"
cp "$TMP/err" "$TMP/p2.v"
check_num "plane: faces_in" "$(figure faces_in "$TMP/p2.v")" == 37842
check_num "plane: faces_out" "$(figure faces_out "$TMP/p2.v")" == 2
check_num "plane: vertices_out" "$(figure vertices_out "$TMP/p2.v")" == 4
check_num "plane: max_error" "$(figure max_error "$TMP/p2.v")" "<" 1e-5
run_case 0 "meshdist -H -s 20000 $TMP/p2.ply $TMP/p/scene.ply"
check_num "plane: on the true plane" "$(figure max "$TMP/out")" "<" 1e-6
run_case 0 "meshdist -H -s 20000 $TMP/p2.ply $TMP/p.ply"
check_num "plane: the same rectangle" "$(figure hausdorff "$TMP/out")" "<" 1e-6
# An error bound alone goes as far: the same two triangles.
run_case 0 "qemdecim -e 1e-5 $TMP/p.ply | meshinfo -"
check_num "plane -e: faces" "$(figure faces "$TMP/out")" == 2

# Steps: two components of planes at right angles; at a 10 micrometre
# bound the flat treads and risers go to a few triangles, every point still
# on the true surface.
mkscene --scene steps --size 160x120 -o "$TMP/s" >/dev/null
dm2mesh --camera "$TMP/s/view00.camera" --pose "$TMP/s/view00.pose" -o "$TMP/s.ply" "$TMP/s/view00.depth.pfm"
run_case 0 "qemdecim -e 1e-5 -o $TMP/s2.ply $TMP/s.ply"
run_case 0 "meshinfo $TMP/s2.ply"
check_num "steps: faces" "$(figure faces "$TMP/out")" "<=" 8
check_num "steps: components" "$(figure components "$TMP/out")" == 2
run_case 0 "meshdist -s 20000 $TMP/s2.ply $TMP/s/scene.ply"
check_num "steps: on the true surface" "$(figure max "$TMP/out")" "<" 1e-5

# The furnished room, two views at 320x240, decimated 100 times.  Without
# noise the model stays within 0.2 mm of the true surface on average (the
# input: 0.06 mm, its triangles cutting the sphere and cylinder), and the
# view's mesh within 0.2 mm of the model.  With Kinect-like noise the model
# is closer to the truth than the noisy input was (6 mm against 16 mm for
# view 0: the quadrics average the noise out), and the truth within 15 mm
# of it.  Every output is manifold where the input was, with the same
# components, and has exactly 1% of the faces.
mkscene --size 320x240 --fx 262.5 --views 2 -o "$TMP/r" >/dev/null
mkscene --size 320x240 --fx 262.5 --views 2 --noise kinect-gauss:0.0015 -o "$TMP/n" >/dev/null
for v in 00 01; do
	for s in r n; do
		dm2mesh --camera "$TMP/$s/view$v.camera" --pose "$TMP/$s/view$v.pose" -o "$TMP/$s$v.ply" "$TMP/$s/view$v.depth.pfm"
	done
	dm2mesh --camera "$TMP/n/view$v.camera" --pose "$TMP/n/view$v.pose" -o "$TMP/t$v.ply" "$TMP/n/view$v.truth.pfm"
	faces=$(meshinfo "$TMP/r$v.ply" | sed -n 's/^faces: //p')
	run_case 0 "qemdecim -v -r 0.01 -o $TMP/r$v.d.ply $TMP/r$v.ply"
	check_num "room $v: 1% of $faces faces" "$(figure faces_out "$TMP/err")" == "$(awk -v f="$faces" 'BEGIN { printf "%d", f / 100 + 0.5 }')"
	run_case 0 "meshdist -s 100000 $TMP/r$v.d.ply $TMP/r/scene.ply"
	check_num "room $v: mean distance to the truth" "$(figure mean "$TMP/out")" "<" 2e-4
	run_case 0 "meshdist -s 100000 $TMP/r$v.ply $TMP/r$v.d.ply"
	check_num "room $v: mean distance of the view to the model" "$(figure mean "$TMP/out")" "<" 2e-4
	meshinfo "$TMP/r$v.ply" >"$TMP/i0"
	run_case 0 "meshinfo $TMP/r$v.d.ply"
	check_num "room $v: non-manifold edges" "$(figure non_manifold_edges "$TMP/out")" == 0
	check_num "room $v: components" "$(figure components "$TMP/out")" == "$(figure components "$TMP/i0")"
	check_num "room $v: degenerate faces" "$(figure degenerate_faces "$TMP/out")" == 0

	faces=$(meshinfo "$TMP/n$v.ply" | sed -n 's/^faces: //p')
	run_case 0 "qemdecim -v -c -r 0.01 -o $TMP/n$v.d.ply $TMP/n$v.ply"
	check_num "noisy room $v: 1% of $faces faces" "$(figure faces_out "$TMP/err")" == "$(awk -v f="$faces" 'BEGIN { printf "%d", f / 100 + 0.5 }')"
	run_case 0 "meshdist -s 100000 $TMP/n$v.ply $TMP/n/scene.ply"
	in=$(figure mean "$TMP/out")
	run_case 0 "meshdist -s 100000 $TMP/n$v.d.ply $TMP/n/scene.ply"
	out=$(figure mean "$TMP/out")
	check_num "noisy room $v: model nearer the truth than the input ($out < $in)" "$out" "<" "$in"
	check_num "noisy room $v: mean distance to the truth" "$out" "<" 0.01
	run_case 0 "meshdist -s 100000 $TMP/t$v.ply $TMP/n$v.d.ply"
	check_num "noisy room $v: mean distance of the true view to the model" "$(figure mean "$TMP/out")" "<" 0.015
	run_case 0 "meshinfo $TMP/n$v.d.ply"
	check_num "noisy room $v: non-manifold edges" "$(figure non_manifold_edges "$TMP/out")" == 0
done

# Texture coordinates, camera, pose and texture comments come through, with
# the provenance line; s t stay in [0, 1].
dm2mesh --camera "$TMP/r/view00.camera" --image "$TMP/r/view00.color.png" -o "$TMP/tex.ply" "$TMP/r/view00.depth.pfm"
run_case 0 "qemdecim -a -r 0.05 $TMP/tex.ply"
check_true "s t kept" grep -q "^property float s$" "$TMP/out"
check_true "camera kept" grep -q "^comment camera pinhole 320 240" "$TMP/out"
check_true "texture kept" grep -q "^comment TextureFile " "$TMP/out"
check_true "provenance" grep -q "^comment facet qemdecim -a -r 0.05 " "$TMP/out"
check_num "s t in [0, 1]" "$(awk '/^end_header/ { b = 1; next } b && NF == 5 { if ($4 < 0 || $4 > 1 || $5 < 0 || $5 > 1) n++ } END { print n + 0 }' "$TMP/out")" == 0

# The same input and options give the same bytes.
run_case 0 "qemdecim -r 0.02 $TMP/n00.ply >$TMP/a.ply && qemdecim -r 0.02 $TMP/n00.ply >$TMP/b.ply && cmp $TMP/a.ply $TMP/b.ply"

# Quads from OBJ are fanned: a 3 x 3 grid of unit squares to 2 triangles.
{
	for y in 0 1 2 3; do for x in 0 1 2 3; do echo "v $x $y 0"; done; done
	for y in 0 1 2; do for x in 0 1 2; do
		a=$((y * 4 + x + 1))
		echo "f $a $((a + 1)) $((a + 5)) $((a + 4))"
	done; done
} >"$TMP/q.obj"
run_case 0 "qemdecim -v -n 2 -o $TMP/q.ply $TMP/q.obj"
check_num "quads: faces_in" "$(figure faces_in "$TMP/err")" == 18
check_num "quads: faces_out" "$(figure faces_out "$TMP/err")" == 2
run_case 0 "meshdist -H $TMP/q.ply $TMP/q.obj"
check_num "quads: the same square" "$(figure hausdorff "$TMP/out")" == 0

# Closed: a unit cube of 12 triangles.  No collapse is free, so an error
# bound keeps it whole; a target of 4 makes it a tetrahedron, still closed,
# and no target goes below that.
run_case 0 "qemdecim -e 1e-9 $D/dist_cube.ply | meshinfo -"
check_num "cube -e: 12 faces" "$(figure faces "$TMP/out")" == 12
run_case 0 "qemdecim -n 0 $D/dist_cube.ply | meshinfo -"
check_num "cube -n 0: a tetrahedron" "$(figure faces "$TMP/out")" == 4
check_num "cube -n 0: closed" "$(figure border_edges "$TMP/out")" == 0
check_num "cube -n 0: manifold" "$(figure non_manifold_edges "$TMP/out")" == 0

# Bad and odd input.
run_case 0 "qemdecim $D/dist_empty.ply | meshinfo -"
check_num "empty: faces" "$(figure faces "$TMP/out")" == 0
run_case 0 "qemdecim $D/dist_nofaces.ply | meshinfo -"
check_num "points only: kept" "$(figure vertices "$TMP/out")" == 2
# A million points and no face: nothing to collapse, so no quadrics and
# lists per vertex (peak 202 MB before, 27 MB now): in a 120 MB address
# space (not under the sanitizers, whose shadow memory needs more).
awk 'BEGIN { n = 1000000; printf "ply\nformat ascii 1.0\nelement vertex %d\n", n
	print "property float x\nproperty float y\nproperty float z\nend_header"
	for (i = 0; i < n; i++) print i % 1000, int(i / 1000), (i * 7) % 13 }' >"$TMP/cloud.ply"
limit=
[ -z "${FCT_SANITIZE:-}" ] && limit="ulimit -v 120000;"
run_case 0 "$limit qemdecim -o $TMP/cloud_out.ply $TMP/cloud.ply"
run_case 0 "meshinfo $TMP/cloud_out.ply"
check_num "point cloud: every point kept" "$(figure vertices "$TMP/out")" == 1000000
run_case 1 "qemdecim $D/dist_nan.ply" "" "qemdecim: $D/dist_nan.ply:"
run_case 1 "qemdecim $D/no_such_file.ply" "" "qemdecim: $D/no_such_file.ply"
run_case 1 "printf 'garbage\n' | qemdecim" "" "qemdecim: <stdin>"

# Usage.
run_case 0 "qemdecim --help"
check_true "--help starts with the usage" grep -q "^usage: qemdecim " "$TMP/out"
run_case 2 "qemdecim -n 5 -r 0.5 $D/dist_cube.ply" "" "qemdecim: -n and -r"
run_case 2 "qemdecim -r 2 $D/dist_cube.ply" "" "qemdecim: -r: "
run_case 2 "qemdecim -n x $D/dist_cube.ply" "" "qemdecim: -n: "
run_case 2 "qemdecim -e -1 $D/dist_cube.ply" "" "qemdecim: -e: "
run_case 2 "qemdecim -z $D/dist_cube.ply" "" "qemdecim: -z"
run_case 2 "qemdecim $D/dist_cube.ply $D/dist_cube.ply" "" "qemdecim: too many operands"
finish
