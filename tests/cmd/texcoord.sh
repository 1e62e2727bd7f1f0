# Texture coordinates under other programs' names (src/lib/io/texcoord.h):
# vertex texture_u texture_v (MeshLab), u v, and per-corner face lists
# texcoord (MeshLab's wedge coordinates, cyl2planar's PLY) are drawn by
# meshshot and written as vt by the OBJ writer, the same as facet's s t.
# They were carried but not used: meshshot drew them shaded, meshconv wrote
# no vt.
. tests/lib.sh
D=tests/data
cp $D/shot_atlas.png "$TMP/"

# The textured cube (tests/data/shot_gen.py) with its s t renamed, and with
# them moved into each face's corners (4 quads of 4 corners: 8 numbers).
sed 's/^property float s$/property float texture_u/; s/^property float t$/property float texture_v/' \
	$D/shot_cube.ply >"$TMP/meshlab.ply"
sed 's/^property float s$/property float u/; s/^property float t$/property float v/' \
	$D/shot_cube.ply >"$TMP/uv.ply"
awk '/^element vertex/ { nv = $3 } /^end_header/ { h = NR }
	!h { if ($0 == "property float s" || $0 == "property float t") next
		if ($0 == "property list uchar int vertex_indices") { print; print "property list uchar float texcoord"; next }
		print; next }
	NR == h { print; next }
	NR <= h + nv { s[NR - h - 1] = $4; t[NR - h - 1] = $5; print $1, $2, $3, $6; next }
	{ line = $1; for (i = 2; i <= $1 + 1; i++) line = line " " $i
	  line = line " " 2 * $1; for (i = 2; i <= $1 + 1; i++) line = line " " s[$i] " " t[$i]
	  print line, $($1 + 2) }' $D/shot_cube.ply >"$TMP/wedge.ply"
check_true "wedge fixture: texcoord lists, no vertex s" sh -c \
	"grep -q '^property list uchar float texcoord\$' $TMP/wedge.ply && ! grep -q '^property float s\$' $TMP/wedge.ply"

# meshshot draws each the same, pixel for pixel, as the s t original (and
# within 2 levels of the golden picture), in mode auto.
run_case 0 "meshshot -s 160x120 --view oblique -w -o $TMP/st.png $D/shot_cube.ply"
run_case 0 "pngsheet -d 2 $TMP/st.png $D/shot_golden_tex.png"
for f in meshlab uv wedge; do
	run_case 0 "meshshot -v -s 160x120 --view oblique -w -o $TMP/$f.png $TMP/$f.ply"
	check_true "$f: drawn textured" grep -q "meshshot: mode=texture" "$TMP/err"
	run_case 0 "pngsheet -d 0 $TMP/$f.png $TMP/st.png"
done

# meshconv writes them as vt: one per vertex (24), or one per face corner
# (24 here), every f corner naming its own vt, and the material library.
for f in meshlab uv wedge; do
	run_case 0 "meshconv -o $TMP/$f.obj $TMP/$f.ply"
	check_num "$f.obj: vt" "$(grep -c '^vt ' "$TMP/$f.obj")" == 24
	check_true "$f.obj: map_Kd" grep -q "^map_Kd shot_atlas.png\$" "$TMP/$f.mtl"
	run_case 0 "meshshot -s 160x120 --view oblique -w -o $TMP/$f.obj.png $TMP/$f.obj"
	run_case 0 "pngsheet -d 0 $TMP/$f.obj.png $TMP/st.png"
done
# Each corner's vt is its vertex's s t (the cube's vertices are one face's
# each), corners numbered in face order: the fifth quad lists its vertices
# backwards, 20/17 19/18 18/19 17/20.
run_case 0 "meshconv -o $TMP/st.obj $D/shot_cube.ply"
check_true "wedge.obj: the fifth quad's corners" grep -q "^f 20/17 19/18 18/19 17/20\$" "$TMP/wedge.obj"
check_num "wedge.obj: corners whose vt differs from their vertex's" "$(awk '
	FNR == 1 { file++ } $1 == "vt" { vt[file, ++n[file]] = $2 " " $3 }
	file == 2 && $1 == "f" { for (i = 2; i <= NF; i++) { split($i, c, "/"); bad += vt[2, c[2]] != vt[1, c[1]]; k++ } }
	END { print k == 24 ? bad : -1 }' "$TMP/st.obj" "$TMP/wedge.obj")" == 0

# cyl2planar's PLY model (per-face texcoord, texnumber over 8 views) is drawn
# textured, like its OBJ (vertices split per view, s t), and meshconv turns
# it into an OBJ with a vt per corner and a material per view.
mkscene -q --views 0 --panorama 1024x256 -o "$TMP/room"
R=$TMP/room
dm2mesh -q --step 8 --cylindrical ,,0 --pose $R/pano.pose --image $R/pano.color.png \
	-o "$TMP/dense.ply" $R/pano.depth.pfm
mkdir -p "$TMP/c"
run_case 0 "cyl2planar --mesh $TMP/dense.ply -o $TMP/c/room.ply"
run_case 0 "cyl2planar --mesh $TMP/dense.ply -o $TMP/c/room.obj"
view="-s 200x150 --eye 0,1.4,0 --target 1,1.2,1 --up 0,-1,0 --fov 80"
run_case 0 "meshshot -v $view -o $TMP/c/ply.png $TMP/c/room.ply"
check_true "cyl2planar PLY: drawn textured" grep -q "meshshot: mode=texture" "$TMP/err"
run_case 0 "meshshot $view -o $TMP/c/obj.png $TMP/c/room.obj"
run_case 0 "pngsheet -v -d 2 $TMP/c/ply.png $TMP/c/obj.png"
run_case 0 "meshconv -o $TMP/c/conv.obj $TMP/c/room.ply"
faces=$(meshinfo $TMP/c/room.ply | awk '$1 == "element:" && $2 == "face" { print $3 }')
# Each distinct value once (1748 for 23562 corners here), every corner
# naming its own: read back, the faces' texcoord lists and texnumber are
# the PLY's.
check_num "converted: no more vt than corners" "$(grep -c '^vt ' "$TMP/c/conv.obj")" "<=" $((3 * faces))
meshconv -a $TMP/c/room.ply | tail -n "$faces" >"$TMP/c/ply.faces"
meshconv -a $TMP/c/conv.obj | tail -n "$faces" >"$TMP/c/obj.faces"
check_true "converted: each corner's vt is the PLY's texcoord" cmp -s "$TMP/c/ply.faces" "$TMP/c/obj.faces"
check_num "converted: a material per view" "$(grep -c '^map_Kd ' "$TMP/c/conv.mtl")" == 8
run_case 0 "meshshot $view -o $TMP/c/conv.png $TMP/c/conv.obj"
run_case 0 "pngsheet -d 2 $TMP/c/conv.png $TMP/c/ply.png"
finish
