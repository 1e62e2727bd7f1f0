# creaseangle: usage and errors; a noiseless range mesh of mkscene's room
# shows its 90-degree creases exactly; Laplacian smoothing rounds them.
. tests/lib.sh
D=tests/data

value() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }

run_case 0 "creaseangle --help"
run_case 0 "creaseangle --version"
run_case 2 "creaseangle $D/dist_cube.ply" "" "creaseangle: two meshes needed"
run_case 2 "creaseangle -b x a.ply b.ply" "" "creaseangle: -b:"
run_case 1 "creaseangle $D/dist_cube.ply $D/dist_cube.ply" "" "creaseangle: "
run_case 1 "creaseangle $D/no_such_file.ply $D/dist_cube.ply" "" "creaseangle: $D/no_such_file.ply"

mkscene -q -o "$TMP/room"
dm2mesh -q --step 2 --camera "$TMP/room/view00.camera" --pose "$TMP/room/view00.pose" -o "$TMP/r.ply" "$TMP/room/view00.depth.pfm"
creaseangle "$TMP/r.ply" "$TMP/room/scene.ply" >"$TMP/c0"
check_num "noiseless: creases measured" "$(value count "$TMP/c0")" ">=" 2
check_num "noiseless: largest error (degrees)" "$(value max_error "$TMP/c0")" "<" 0.01
areaflow --method laplacian --iterations 5 "$TMP/r.ply" | creaseangle - "$TMP/room/scene.ply" >"$TMP/c1"
check_num "laplacian x5: creases rounded (degrees)" "$(value mean_error "$TMP/c1")" ">" 10
finish
