# meshconv: exact round trips between encodings on real scans, atomic -o,
# TextureFile paths, quiet end on a closed pipe, usage errors, and the man
# page's examples.
. tests/lib.sh
D=../shared/data
bunny=samples/bunny/bun_zipper_res2.ply

# Round trips: ascii -> LE -> BE -> ascii must give the same ascii bytes, and
# LE -> BE -> LE the same binary bytes.
for f in "$bunny" "$D/stanford_bunny/data/bun000.ply" "$D/open3d_coloredicp_fragment/frag_115.ply"; do
	[ -f "$f" ] || continue
	n=$(basename "$f" .ply)
	meshconv -a "$f" >"$TMP/$n.a.ply"
	meshconv "$TMP/$n.a.ply" >"$TMP/$n.le.ply"
	meshconv -f binary_big_endian "$TMP/$n.le.ply" >"$TMP/$n.be.ply"
	meshconv -a "$TMP/$n.be.ply" >"$TMP/$n.a2.ply"
	meshconv "$TMP/$n.be.ply" >"$TMP/$n.le2.ply"
	check_true "$n: ascii round trip" cmp -s "$TMP/$n.a.ply" "$TMP/$n.a2.ply"
	check_true "$n: binary round trip" cmp -s "$TMP/$n.le.ply" "$TMP/$n.le2.ply"
	check_true "$n: big-endian header" grep -q "^format binary_big_endian 1.0" "$TMP/$n.be.ply"
done
# A binary little-endian file written by another program comes back identical.
f=$D/open3d_coloredicp_fragment/frag_115.ply
[ -f "$f" ] && run_case 0 "meshconv $f" "$f"
# The ascii scan keeps its obj_info lines and its range_grid element of lists.
f=$D/stanford_bunny/data/bun000.ply
if [ -f "$f" ]; then
	meshconv -a "$f" >"$TMP/b.ply"
	check_true "bun000: obj_info kept" grep -q "^obj_info num_cols 512" "$TMP/b.ply"
	check_true "bun000: range_grid kept" grep -q "^element range_grid 204800" "$TMP/b.ply"
	check_num "bun000: same line count as the original" "$(wc -l <"$TMP/b.ply")" == "$(wc -l <"$f")"
fi

# Atomic output: a failed run leaves an existing file untouched and no
# temporary file behind.
echo keep >"$TMP/out.ply"
run_case 1 "meshconv -o $TMP/out.ply tests/bad/ply_nan.ply" "" "meshconv: tests/bad/ply_nan.ply:9: "
check_true "failed run left the old file" grep -q keep "$TMP/out.ply"
check_num "no temporary files left" "$(ls -a "$TMP" | grep -c '^\.out')" == 0
run_case 0 "meshconv -o $TMP/out.ply $bunny"
check_true "successful run replaced the file" cmp -s "$TMP/out.ply" "$TMP/bun_zipper_res2.le.ply"
run_case 1 "meshconv -o /nonexistent/dir/x.ply $bunny" "" "meshconv: /nonexistent/dir/x.ply: "

# TextureFile paths are relative to the current folder on the pipes and to
# the output's folder in a file.
mkdir -p "$TMP/img" "$TMP/models"
printf 'ply\nformat ascii 1.0\ncomment TextureFile img/tex.png\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n' >"$TMP/tex.ply"
(cd "$TMP" && meshconv -a -o models/m.ply tex.ply)
check_true "TextureFile rewritten for the output folder" grep -q "^comment TextureFile ../img/tex.png" "$TMP/models/m.ply"
(cd "$TMP" && meshconv -f binary_big_endian -o models/m2.ply tex.ply)
check_true "TextureFile rewritten for any output format" grep -aq "^comment TextureFile ../img/tex.png" "$TMP/models/m2.ply"
(cd "$TMP" && meshconv -a models/m.ply >back.ply)
check_true "TextureFile read from a file is relative to the current folder again" \
	grep -q "^comment TextureFile img/tex.png$" "$TMP/back.ply"
(cd "$TMP" && meshconv -a <tex.ply >pipe.ply)
check_true "TextureFile untouched on the pipes" grep -q "^comment TextureFile img/tex.png" "$TMP/pipe.ply"

# A closed pipe ends the program quietly.
sh -c "meshconv -a $bunny 2>$TMP/pipe_err | head -c 10 >/dev/null"
check_num "no message on a closed pipe" "$(wc -c <"$TMP/pipe_err")" == 0

# Usage errors: exit 2.
run_case 2 "meshconv -f banana $bunny" "" "meshconv: -f: unknown format"
run_case 2 "meshconv -Z" "" ""
run_case 2 "meshconv - - <$bunny" "" "meshconv: standard input given 2 times"
run_case 1 "meshconv /nonexistent.ply" "" "meshconv: /nonexistent.ply: No such file"
run_case 0 "meshconv --version" "" ""
run_case 0 "meshconv -h" "" ""

# Fuzz finds kept as regressions (run under ASan by make sanitize): an OBJ
# whose vertex columns were added while a pointer to an earlier one was held.
run_case 0 "meshconv tests/data/obj_fuzz_uaf.obj >/dev/null"

# The man page's examples.
cp "$TMP/bun_zipper_res2.le.ply" "$TMP/in.ply"
cp "$TMP/bun_zipper_res2.le.ply" "$TMP/scan.ply"
run_case 0 "cd $TMP && meshconv -a scan.ply > scan_ascii.ply && meshconv -f binary_big_endian in.ply | meshconv | cmp - in.ply"
# -o to something that is not a regular file (a FIFO here; /dev/null in
# real use) writes into it and leaves it what it was, not a renamed file.
mkfifo "$TMP/fifo"
wc -c <"$TMP/fifo" >"$TMP/fifo.count" &
run_case 0 "meshconv -o $TMP/fifo $bunny"
wait
check_true "-o FIFO stays a FIFO" test -p "$TMP/fifo"
check_num "-o FIFO carried the mesh" "$(cat "$TMP/fifo.count")" ">" 1000

# Several inputs joined, --weld: two triangles sharing an edge, given as two
# files, become 4 vertices (the second file's copies of the shared corners
# merged) and 2 faces; a third file whose only face collapses onto a point
# when welded loses it; a fourth with other vertex properties is refused.
tri() { printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n%s\n%s\n%s\n3 0 1 2\n' "$@"; }
tri "0 0 0" "1 0 0" "0 1 0" >"$TMP/j1.ply"
tri "1 0 0" "1 1 0" "0 1 0" >"$TMP/j2.ply"
tri "1 1 0" "1 1 0" "0 0 0" >"$TMP/j3.ply"
run_case 0 "meshconv -v -a --weld -o $TMP/j.ply $TMP/j1.ply $TMP/j2.ply"
check_num "joined: vertices" "$(awk '$1 == "element" && $2 == "vertex" { print $3 }' "$TMP/j.ply")" == 4
check_num "joined: faces" "$(awk '$1 == "element" && $2 == "face" { print $3 }' "$TMP/j.ply")" == 2
check_num "joined: vertices merged" "$(awk -F= '$1 == "meshconv: welded_vertices" { print $2 }' "$TMP/err")" == 2
check_true "joined: second face renumbered" grep -qx "3 1 3 2" "$TMP/j.ply"
run_case 0 "meshconv -v -a --weld -o $TMP/j.ply $TMP/j1.ply $TMP/j2.ply $TMP/j3.ply"
check_num "welded: degenerate face dropped" "$(awk -F= '$1 == "meshconv: degenerate_faces" { print $2 }' "$TMP/err")" == 1
check_num "welded: faces" "$(awk '$1 == "element" && $2 == "face" { print $3 }' "$TMP/j.ply")" == 2
run_case 0 "meshconv -a $TMP/j1.ply $TMP/j2.ply >$TMP/j12.ply"
check_num "joined without --weld: 6 vertices" "$(awk '$1 == "element" && $2 == "vertex" { print $3 }' "$TMP/j12.ply")" == 6
run_case 1 "meshconv $TMP/j1.ply $bunny" "" "meshconv: $bunny: vertex property "

# A texture path padded to a 261-byte header line (found by fuzz_ply): read
# as it is, written as OBJ, refused as PLY in one line before a byte is
# written, since MeshLab and Open3D read at most 255.
long=tests/data/texture_path_261.ply
run_case 0 "meshconv -o $TMP/long.obj $long"
run_case 1 "meshconv -o $TMP/long.ply $long" "" "meshconv: $TMP/long.ply: header line \"comment TextureFile"
check_true "long header line: no PLY written" test ! -s "$TMP/long.ply"

finish
