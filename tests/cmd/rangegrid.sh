# meshconv --grid and --conf: a hand-made 4x4 range grid meshed into 18
# triangles, placed in the world by a .conf pose to hand-computed
# coordinates; registering before or after meshing agree; errors.
. tests/lib.sh

# 4x4 cells 1 mm apart on the plane z = -0.5 (cell (i, j) at x = i mm,
# y = -j mm), listed in the vertex element in cell order.
cp tests/data/rangegrid_4x4.ply "$TMP/scan.ply"
# 90 degrees about z, applied conjugated (x -> -y), then t = (1, 2, 3).
echo "bmesh scan.ply 1 2 3 0 0 0.70710678118654752 0.70710678118654752" >"$TMP/scan.conf"

# line N of the body of PLY file F (ascii).
body() { awk -v n="$1" 'p && ++k == n { print; exit } /^end_header/ { p = 1 }' "$2"; }
# near "desc" "x y z" "X Y Z": each coordinate within 1e-6.
near() {
	check_true "$1: $2 vs $3" awk -v a="$2" -v b="$3" 'BEGIN { split(a, p); split(b, q)
		for (k = 1; k <= 3; k++) if ((p[k] - q[k]) ^ 2 > 1e-12) exit 1 }'
}

run_case 0 "meshconv -a --grid -o $TMP/grid.ply $TMP/scan.ply"
check_true "grid: 16 vertices" grep -q '^element vertex 16$' "$TMP/grid.ply"
check_true "grid: 18 triangles" grep -q '^element face 18$' "$TMP/grid.ply"
check_true "grid: range_grid dropped" sh -c "! grep -q range_grid $TMP/grid.ply"
check_true "grid: obj_info kept" grep -q '^obj_info num_cols 4$' "$TMP/grid.ply"
check_num "grid: every face a triangle" "$(awk 'p && NF == 4 && $1 == 3 { n++ } /^end_header/ { p = 1 } END { print n }' "$TMP/grid.ply")" == 18
near "grid: vertex 6 stays" "$(body 6 "$TMP/grid.ply")" "0.001 -0.001 -0.5"

run_case 0 "meshconv -a --conf $TMP/scan.conf -o $TMP/reg.ply $TMP/scan.ply"
check_true "conf: meshed" grep -q '^element face 18$' "$TMP/reg.ply"
check_true "conf: pose comment [0 1 0 | 1; -1 0 0 | 2; 0 0 1 | 3]" awk '$1 == "comment" && $2 == "pose" {
	split("0 1 0 1 -1 0 0 2 0 0 1 3", w); for (k = 1; k <= 12; k++) if (($(k + 2) - w[k]) ^ 2 > 1e-24) exit 1
	found = 1 } END { exit !found }' "$TMP/reg.ply"
near "conf: cell (0, 0) at t" "$(body 1 "$TMP/reg.ply")" "1 2 2.5"
near "conf: cell (1, 0): x -> -y" "$(body 2 "$TMP/reg.ply")" "1 1.999 2.5"
near "conf: cell (2, 3)" "$(body 15 "$TMP/reg.ply")" "0.997 1.998 2.5"
# Meshed first, registered after: the same file.
mkdir "$TMP/g2"
cp "$TMP/grid.ply" "$TMP/g2/scan.ply"
run_case 0 "meshconv -a --conf $TMP/scan.conf $TMP/g2/scan.ply" "$TMP/reg.ply"

# Errors.
run_case 2 "meshconv --conf $TMP/scan.conf <$TMP/scan.ply" "" "meshconv: --conf: "
run_case 1 "meshconv --conf $TMP/scan.conf $TMP/grid.ply" "" "meshconv: $TMP/scan.conf: no bmesh line names grid.ply"
run_case 1 "meshconv --conf $TMP/scan.conf $TMP/reg.ply" "" "meshconv: $TMP/scan.conf: no bmesh line names reg.ply"
cp "$TMP/reg.ply" "$TMP/g2/scan.ply"
run_case 1 "meshconv --conf $TMP/scan.conf $TMP/g2/scan.ply" "" "meshconv: $TMP/g2/scan.ply: already has a pose comment"
run_case 1 "meshconv --grid $TMP/grid.ply" "" "meshconv: $TMP/grid.ply: no range_grid element"
sed 's/^1 15$/1 16/' "$TMP/scan.ply" >"$TMP/bad.ply"
run_case 1 "meshconv --grid $TMP/bad.ply" "" "meshconv: $TMP/bad.ply: range_grid cell 15: vertex index out of range"
echo "bmesh scan.ply 0 0 0 0 0 0 2" >"$TMP/bad.conf"
run_case 1 "meshconv --conf $TMP/bad.conf $TMP/scan.ply" "" "meshconv: $TMP/bad.conf:1: "
finish
