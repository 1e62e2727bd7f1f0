# Blender (bpy from PyPI) reads facet's OBJ and writes it back with its
# default export (normals on: a vn per corner, UVs deduplicated): the
# result read by facet must be the same connected mesh (issue 24: 1156
# vertices in 213 pieces for 699 vertices in 34 before).  Skipped with a
# message when the bpy module is absent (pip install bpy).
. tests/lib.sh

if ! python3 -c 'import bpy' >/dev/null 2>&1; then
	echo "obj_blender.sh: python3 module bpy missing (pip install bpy), skipped" >&2
	finish
	exit
fi
S=samples/tum
cat >"$TMP/rt.py" <<'PY'
import sys, bpy
src, dst = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=src)
bpy.ops.wm.obj_export(filepath=dst)
PY
# A planar model of the TUM desk, textured (vertex s t and a material).
run_case 0 "dm2mesh -K tum --step 4 --image $S/TUM_color.png $S/TUM_depth.png | segplanes | simpchain | projverts | tripatch -o $TMP/model.obj"
run_case 0 "python3 $TMP/rt.py -- $TMP/model.obj $TMP/back.obj >/dev/null 2>&1"
check_true "Blender wrote a normal per corner" grep -q '^f [0-9]*/[0-9]*/[0-9]' "$TMP/back.obj"
info() { meshinfo "$1" | awk -v k="$2:" '$1 == k { print $2 }'; }
check_num "as many vertices back" "$(info "$TMP/back.obj" vertices)" == "$(info "$TMP/model.obj" vertices)"
check_num "as many pieces back" "$(info "$TMP/back.obj" components)" == "$(info "$TMP/model.obj" components)"
# The same positions and texture coordinates, vertex by vertex (Blender
# prints 6 decimals, after its axis conversion there and back).
verts() { meshconv -a "$1" | awk 'h && n-- > 0 { print $1, $2, $3, $4, $5 } /^element vertex/ { n = $3 } /^end_header/ { h = 1 }'; }
verts "$TMP/model.obj" >"$TMP/a.txt"
verts "$TMP/back.obj" >"$TMP/b.txt"
check_true "positions and s t within 2e-6 of facet's" tolcmp -s -a 2e-6 -r 0 "$TMP/a.txt" "$TMP/b.txt"
check_num "the vertex lines compared" "$(wc -l <"$TMP/a.txt")" == "$(info "$TMP/model.obj" vertices)"

# Per-corner data facet writes (vt / vn indices per corner, from a PLY's
# texcoord and corner_normal lists) opens in Blender as one mesh of 8
# vertices whose 24 corners have the cube's UVs.
cat >"$TMP/count.py" <<'PY'
import sys, bpy
src = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=src)
me = bpy.data.objects[0].data
uv = me.uv_layers.active.data
print(len(me.vertices), len(me.polygons), len(me.loops),
      len({(round(u.uv[0], 4), round(u.uv[1], 4)) for u in uv}))
PY
run_case 0 "meshconv -o $TMP/cube.ply tests/data/obj_blender_cube.obj && meshconv -o $TMP/cube.obj $TMP/cube.ply"
check_true "Blender reads facet's per-corner OBJ: 8 vertices, 6 faces, 24 corners, 14 UVs" \
	sh -c "python3 $TMP/count.py -- $TMP/cube.obj 2>/dev/null | grep -qx '8 6 24 14'"
finish
