#!/bin/sh
# meshinfo: golden outputs (compared with tolcmp; tests/cmd/expected,
# rewritten by make regold), counts and bounding box of a real scan,
# several files, stdin, errors and exit statuses.
. tests/lib.sh
D=tests/data
E=tests/cmd/expected

# golden NAME FILE: meshinfo FILE succeeds and matches expected/meshinfo_NAME.txt.
golden() {
	if meshinfo "$2" >"$TMP/$1.txt" 2>"$TMP/$1.err" && [ ! -s "$TMP/$1.err" ] &&
	   regold "$TMP/$1.txt" "$E/meshinfo_$1.txt" && tolcmp "$E/meshinfo_$1.txt" "$TMP/$1.txt"; then ok
	else not_ok "meshinfo $2 differs from $E/meshinfo_$1.txt"; fi
}

# Hand-checked: a 2x3x4 box of 12 triangles with every kind of comment; the
# same box as binary big-endian; polygons with a fan, degenerate and
# duplicate faces; vertices without faces.
golden cube $D/info_cube.ply
golden cube_be $D/info_cube_be.ply
golden mixed $D/info_mixed.ply
golden points $D/info_points.ply

# Key lines asserted exactly, so a regenerated golden cannot hide them.
line() {  # file, exact line
	if grep -qxF "$2" "$1"; then ok; else not_ok "$1: no line \"$2\""; fi
}
line "$TMP/cube.txt" "edges: 18"
line "$TMP/cube.txt" "border_edges: 0"
line "$TMP/cube.txt" "camera: pinhole width 640 height 480 fx 525 fy 525 cx 319.5 cy 239.5"
line "$TMP/cube.txt" "pose: rotation 1 0 0 0 1 0 0 0 1 translation 0.5 -0.25 2"
line "$TMP/cube.txt" "texture: tests/data/cube.png"
line "$TMP/cube.txt" "provenance: areaflow -n 3"
line "$TMP/cube_be.txt" "format: ply binary_big_endian"
line "$TMP/mixed.txt" "non_manifold_edges: 4"
line "$TMP/mixed.txt" "components: 2"
line "$TMP/mixed.txt" "degenerate_faces: 3"
line "$TMP/mixed.txt" "duplicate_faces: 1"
line "$TMP/mixed.txt" "polygons: 1"
line "$TMP/points.txt" "mean_edge_length: none"
line "$TMP/points.txt" "isolated_vertices: 3"
line "$TMP/mixed.txt" "duplicate_vertices: 0"
# A triangle soup: two triangles on the square's diagonal, each with corners
# of its own: 6 vertices at 4 positions, no edge shared.
printf 'ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 3 4 5\n' >"$TMP/soup.ply"
meshinfo "$TMP/soup.ply" >"$TMP/soup.txt"
line "$TMP/soup.txt" "duplicate_vertices: 2"
line "$TMP/soup.txt" "components: 2"
line "$TMP/soup.txt" "border_edges: 6"

# stdin, "-" and several files (one blank line between blocks).
sed 's/^file: .*/file: <stdin>/' $E/meshinfo_points.txt >"$TMP/stdin.txt"
run_case 0 "meshinfo <$D/info_points.ply" "$TMP/stdin.txt"
run_case 0 "meshinfo - <$D/info_points.ply" "$TMP/stdin.txt"
{ cat $E/meshinfo_points.txt; echo; cat $E/meshinfo_mixed.txt; } >"$TMP/two.txt"
meshinfo $D/info_points.ply $D/info_mixed.ply >"$TMP/two.out"
check_true "meshinfo with two files" tolcmp "$TMP/two.txt" "$TMP/two.out"

# Bad data: one line naming the file, exit 1; the other files are still described.
run_case 1 "meshinfo tests/bad/info_truncated.ply" "" "meshinfo: tests/bad/info_truncated.ply:30: "
run_case 1 "meshinfo $D/nonexistent.ply" "" "meshinfo: $D/nonexistent.ply: "
run_case 1 "meshinfo tests/bad/info_truncated.ply $D/info_points.ply" "" "meshinfo: tests/bad/info_truncated.ply:"
meshinfo tests/bad/info_truncated.ply $D/info_points.ply 2>/dev/null >"$TMP/after.out"
check_true "a bad file does not stop the next" cmp -s "$TMP/after.out" $E/meshinfo_points.txt
run_case 2 "meshinfo -x" "" "meshinfo: -x: unknown option"
run_case 2 "meshinfo --bogus" "" "meshinfo: --bogus: unknown option"
run_case 0 "meshinfo --help | grep -q '^usage: meshinfo \[file \.\.\.\]$'"
run_case 0 "meshinfo --version | grep -q '^meshinfo (facet) '"

# OBJ, when the reader exists: a unit square as two triangles.
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n' >"$TMP/sq.obj"
if meshconv "$TMP/sq.obj" >/dev/null 2>&1; then
	meshinfo "$TMP/sq.obj" >"$TMP/sq.txt"
	for l in "format: obj" "vertices: 4" "triangles: 2" "edges: 5" "border_edges: 4" \
	         "manifold_edges: 1" "components: 1" "bbox_size: 1 1 0"; do
		line "$TMP/sq.txt" "$l"
	done
fi

# The noise model and the vertices' sigma: min, median (the lower middle of
# four) and max; a malformed noise comment is reported, not fatal.
meshinfo $D/info_noise.ply >"$TMP/sig.txt"
for l in "noise: tof 0.001 0.002" "sigma_min: 0.100000001" "sigma_median: 0.200000003" "sigma_max: 0.400000006"; do
	line "$TMP/sig.txt" "$l"
done
sed 's/^comment noise .*/comment noise poly 1/' $D/info_noise.ply >"$TMP/badnoise.ply"
meshinfo "$TMP/badnoise.ply" >"$TMP/badnoise.txt"
line "$TMP/badnoise.txt" "noise: invalid: comment: noise: expected poly:A,B,C"
check_true "no sigma lines without the property" sh -c "! grep -q '^sigma_m' $TMP/cube.txt"

# The noise estimated from the data (noise.h), against what is known.
# Real Kinect frames meshed without a model (numeric -K: no sigma): the
# estimate is their kinect model's median sigma within 10% (all 20 frames:
# 0.92 to 1.08), growing as z^2.
S=../shared/data/7scenes_redkitchen/frames
if [ -d "$S" ]; then
	for fr in 000000 000500 000950; do
		dm2mesh -K 585,585,320,240 --pose $S/frame-$fr.pose.txt -o "$TMP/kn.ply" $S/frame-$fr.depth.png
		dm2mesh -K 7scenes --pose $S/frame-$fr.pose.txt -o "$TMP/km.ply" $S/frame-$fr.depth.png
		est=$(meshinfo "$TMP/kn.ply" | awk '$1 == "sigma_estimate:" { print $2 }')
		model=$(meshinfo "$TMP/km.ply" | awk '$1 == "sigma_median:" { print $2 }')
		check_num "7-Scenes $fr: estimate $est against the model's $model" \
			"$(awk -v a="$est" -v b="$model" 'BEGIN { d = a / b - 1; print d < 0 ? -d : d }')" "<" 0.1
		check_true "7-Scenes $fr: the estimate grows as z^2" sh -c "meshinfo $TMP/kn.ply | grep -q '^sigma_estimate_law: .* z^2 along rays\$'"
	done
fi
# A fused scan has no camera: its estimate is along the normals.  Four views
# of mkscene's room with Gaussian noise of 1 cm (and with the structured
# Kinect noise), fused at 2 cm: the fused surface's rms distance to the true
# surface (3.8 and 19.6 mm) and the estimate from the fused mesh alone
# (3.5 and 14.8) agree within 30%.
for nz in gaussian:0.01 kinect; do
	mkscene -q --views 4 --size 320x240 --fx 262.5 --noise $nz -o "$TMP/f"
	for i in 0 1 2 3; do
		dm2mesh --camera "$TMP/f/view0$i.camera" --pose "$TMP/f/view0$i.pose" -o "$TMP/f/v$i.ply" "$TMP/f/view0$i.depth.pfm"
	done
	tsdfuse --voxel 0.02 -o "$TMP/fused.ply" "$TMP"/f/v?.ply
	rms=$(meshdist "$TMP/fused.ply" "$TMP/f/scene.ply" | awk '$1 == "rms" { print $2 }')
	meshinfo "$TMP/fused.ply" >"$TMP/fused.txt"
	est=$(awk '$1 == "sigma_estimate:" { print $2 }' "$TMP/fused.txt")
	check_num "fused room ($nz): estimate $est against rms $rms" \
		"$(awk -v a="$est" -v b="$rms" 'BEGIN { d = a / b - 1; print d < 0 ? -d : d }')" "<" 0.3
	check_true "fused room: along the normals" grep -q '^sigma_estimate_law: .* z^0 along normals$' "$TMP/fused.txt"
done
line "$TMP/cube.txt" "sigma_estimate: none"

# A real scan (Open3D's colored ICP fragment, binary PLY).  Counts, bounding
# box, edges, components and degenerate faces were checked independently by
# reading the binary file with a short script.
F=/work/shared/data/open3d_coloredicp_fragment/frag_115.ply
if [ -f "$F" ]; then
	(cd "$(dirname "$F")" && meshinfo frag_115.ply) >"$TMP/frag.txt" && regold "$TMP/frag.txt" $E/meshinfo_frag115.txt
	check_true "meshinfo frag_115.ply golden" tolcmp $E/meshinfo_frag115.txt "$TMP/frag.txt"
	line "$TMP/frag.txt" "vertices: 64365"
	line "$TMP/frag.txt" "faces: 127229"
	line "$TMP/frag.txt" "triangles: 127229"
	line "$TMP/frag.txt" "edges: 191590"
	line "$TMP/frag.txt" "border_edges: 1493"
	line "$TMP/frag.txt" "non_manifold_edges: 0"
	line "$TMP/frag.txt" "components: 10"
	line "$TMP/frag.txt" "isolated_vertices: 0"
	line "$TMP/frag.txt" "degenerate_faces: 10"
	line "$TMP/frag.txt" "duplicate_faces: 0"
	line "$TMP/frag.txt" "sigma_estimate_law: 0.000430194312 z^0 along normals"
	set -- $(sed -n 's/^bbox_min: //p' "$TMP/frag.txt") $(sed -n 's/^bbox_max: //p' "$TMP/frag.txt")
	check_num "bbox min x" "$1" == 0.83984375
	check_num "bbox min y" "$2" == 0.91796875
	check_num "bbox min z" "$3" == 0.56640625
	check_num "bbox max x" "$(awk -v a="$4" 'BEGIN { print (a - 2.57239342 < 5e-9 && 2.57239342 - a < 5e-9) }')" == 1
	check_num "bbox max y" "$(awk -v a="$5" 'BEGIN { print (a - 2.81354785 < 5e-9 && 2.81354785 - a < 5e-9) }')" == 1
	check_num "bbox max z" "$(awk -v a="$6" 'BEGIN { print (a - 1.60887241 < 5e-9 && 1.60887241 - a < 5e-9) }')" == 1
fi

# The man page's examples.
run_case 0 "meshinfo $D/info_cube.ply | grep '^bbox_size:'"
run_case 0 "meshinfo $D/info_mixed.ply | sed -n 's/^border_edges: //p' | grep -qx 10"
finish
