# OBJ: hand-written fixtures against hand-checked PLY goldens (vertex
# splitting, negative indices, materials), exact round trips PLY -> OBJ ->
# PLY (fixtures and a real scan), texture paths and material libraries, and
# the messages of bad OBJ files.
. tests/lib.sh
D=tests/data
top=$(pwd)

# Fixtures: the counts are worked out in each file's comments.
for n in obj_cube obj_split obj_negative; do
	run_case 0 "meshconv -a $D/$n.obj" "$D/$n.ply"
done
# A vertex is its v line: normals and texture coordinates that differ round
# a position go per corner, and the mesh stays connected (it was split into
# 24 vertices, 6 pieces, before).
info() { meshinfo "$1" | awk -v k="$2:" '$1 == k { print $2 }'; }
check_num "cube: 8 positions are 8 vertices" "$(info $D/obj_cube.obj vertices)" == 8
check_num "cube: one closed surface" "$(info $D/obj_cube.obj components)$(info $D/obj_cube.obj border_edges)" == 10
check_true "cube: texture from the mtl, relative to the current folder" \
	grep -q "^comment TextureFile tests/data/obj_wood.png$" $D/obj_cube.ply

# Issue 24's reproduction: one normal value under two indices made 6
# vertices in 2 pieces.
check_num "issue 24: 4 vertices" "$(info $D/obj_shared_edge.obj vertices)" == 4
check_num "issue 24: 1 component" "$(info $D/obj_shared_edge.obj components)" == 1

# Blender's default cube as its OBJ exporter writes it (normals on, UVs,
# flat shading: every corner its own vt / vn pair) is one closed surface of
# 8 vertices, and OBJ -> PLY -> OBJ gives back the same OBJ, vt and vn
# indices per corner (the 14 vt and 6 vn of the file, in its order).
B=$D/obj_blender_cube.obj
check_num "blender cube: 8 vertices" "$(info $B vertices)" == 8
check_num "blender cube: one closed surface" "$(info $B components)$(info $B border_edges)" == 10
run_case 0 "meshconv -o $TMP/bc.obj $B && meshconv -o $TMP/bc.ply $B && meshconv -o $TMP/bc2.obj $TMP/bc.ply && cmp $TMP/bc.obj $TMP/bc2.obj"
check_num "blender cube: 14 vt back" "$(grep -c '^vt ' $TMP/bc2.obj)" == 14
check_num "blender cube: 6 vn back" "$(grep -c '^vn ' $TMP/bc2.obj)" == 6
grep '^f ' $B >"$TMP/f.want"
check_true "blender cube: the faces' indices as Blender wrote them" sh -c "grep '^f ' $TMP/bc2.obj | cmp -s - $TMP/f.want"

# Per-corner texture coordinates from a PLY (cyl2planar's texcoord lists,
# one texture per face by texnumber) become vt per corner and a material
# per texture (meshconv wrote no vt for them before), and read back the same.
cp $D/obj_corner_tex.ply "$TMP/"
run_case 0 "cd $TMP && meshconv -o ct.obj obj_corner_tex.ply && meshconv -a ct.obj > ct.back.ply"
check_true "texcoord lists: vt per corner, distinct values once" sh -c "grep '^vt\|^f\|^usemtl' $TMP/ct.obj | tr '\n' ';' | grep -qx 'vt 0 0;vt 1 0;vt 0 1;vt 0 0.5;vt 1 0.5;usemtl material_0;f 1/1 2/2 3/3;usemtl material_1;f 2/4 4/5 3/3;'"
check_true "texcoord lists: OBJ -> PLY gives them back" sh -c "grep -v '^comment facet' $TMP/ct.back.ply | cmp -s - $D/obj_corner_tex.ply"

# PLY -> OBJ -> PLY keeps vertex count, polygons, every property value bit
# for bit, and the comments (camera, pose, TextureFile, provenance, obj_info).
# Run in one folder so that TextureFile paths stay as written.
for n in obj_rt obj_rt_tex2; do
	cp $D/$n.ply "$TMP/"
	run_case 0 "cd $TMP && meshconv -o $n.obj $n.ply && meshconv -a $n.obj > $n.back.ply && meshconv -a $n.ply > $n.orig.ply"
	check_true "$n: PLY -> OBJ -> PLY is identical" cmp -s "$TMP/$n.orig.ply" "$TMP/$n.back.ply"
done
check_true "obj_rt: mtllib names the library beside it" grep -q "^mtllib obj_rt.mtl$" "$TMP/obj_rt.obj"
check_true "obj_rt: one material with the texture" grep -q "^map_Kd tex.png$" "$TMP/obj_rt.mtl"
check_true "obj_rt: faces use matching indices" grep -q "^f 1/1/1 2/2/2 3/3/3 4/4/4$" "$TMP/obj_rt.obj"
check_true "obj_rt: colours as float/255" grep -q "^v 0.1 0.2 0.3 1 0 0$" "$TMP/obj_rt.obj"
check_true "obj_rt: provenance as a comment" grep -q "^# comment facet dm2mesh -s 2 depth.png$" "$TMP/obj_rt.obj"
check_num "obj_rt_tex2: three materials (two textures, untextured)" "$(grep -c '^newmtl' "$TMP/obj_rt_tex2.mtl")" == 3
check_true "obj_rt_tex2: texnumber read back" grep -q "^property int texnumber$" "$TMP/obj_rt_tex2.back.ply"

# On the pipes (no material library) the comments still carry everything.
run_case 0 "cd $TMP && meshconv -f obj obj_rt.ply | meshconv -a | cmp - obj_rt.orig.ply"

# OBJ -> PLY -> OBJ: what facet writes, it reads back the same.
run_case 0 "cd $TMP && meshconv -o a.obj obj_rt.back.ply && meshconv a.obj > a.ply && meshconv -o a2.obj a.ply && sed s/a2.mtl/a.mtl/ a2.obj | cmp - a.obj && cmp a.mtl a2.mtl"

# A real scan with normals and colours: binary PLY -> OBJ -> binary PLY, same bytes.
f=../shared/data/open3d_coloredicp_fragment/frag_115.ply
if [ -f "$f" ]; then
	run_case 0 "meshconv -o $TMP/frag.obj $f && meshconv $TMP/frag.obj | cmp - $f"
fi
# Properties OBJ cannot hold (confidence, intensity) are dropped; the rest stays.
f=samples/bunny/bun_zipper_res2.ply
if [ -f "$f" ]; then
	meshconv -o "$TMP/bun.obj" "$f" && meshconv -a "$TMP/bun.obj" >"$TMP/bun.ply"
	awk 'h && NF == 5 { print $1, $2, $3; next } h { $1 = $1; print; next } /^end_header/ { h = 1 }' "$f" >"$TMP/bun.want"
	sed '1,/^end_header/d' "$TMP/bun.ply" >"$TMP/bun.got"
	check_true "bunny: positions and faces survive OBJ" cmp -s "$TMP/bun.want" "$TMP/bun.got"
	check_true "bunny: confidence is gone" sh -c "! grep -q confidence $TMP/bun.ply"
fi

# Texture paths: relative to the current folder on the pipes, to the file's
# folder in the .mtl, through a model moved to another folder.
mkdir -p "$TMP/in" "$TMP/models"
cp $D/obj_cube.obj $D/obj_cube.mtl "$TMP/in/"
run_case 0 "cd $TMP && meshconv -o models/c.obj in/obj_cube.obj"
check_true "map_Kd relative to the model's folder" grep -q "^map_Kd ../in/obj_wood.png$" "$TMP/models/c.mtl"
run_case 0 "cd $TMP && meshconv -a models/c.obj | grep -q '^comment TextureFile in/obj_wood.png$'"
# A missing material library is no error: the mesh comes without texture.
run_case 0 "cd $TMP/in && rm obj_cube.mtl && meshconv -a obj_cube.obj | grep -c TextureFile | grep -q '^0$'"

# Bad files: one line naming the file and line.
run_case 1 "meshconv tests/bad/obj_missing_vertex.obj" "" \
	"meshconv: tests/bad/obj_missing_vertex.obj:5: face: vertex index 4 out of range (3 vertices)"
run_case 1 "meshconv tests/bad/obj_huge_index.obj" "" \
	"meshconv: tests/bad/obj_huge_index.obj:4: face: vertex index 99999999999 out of range (3 vertices)"
run_case 1 "meshconv tests/bad/obj_junk_ref.obj" "" \
	"meshconv: tests/bad/obj_junk_ref.obj:5: face: \"1/x/2\" is not a vertex reference"
run_case 1 "meshconv tests/bad/obj_binary.obj" "" \
	"meshconv: tests/bad/obj_binary.obj: not a PLY or OBJ file (no vertex)"
run_case 1 "meshconv < tests/bad/obj_empty.obj" "" "meshconv: <stdin>: not a PLY or OBJ file (no vertex)"
for f in tests/bad/obj_*.obj; do
	run_case 1 "meshconv $f >/dev/null" "" "meshconv: $f:"
done
finish
