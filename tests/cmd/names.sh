# A file name holding a newline (or another control character) made every
# error message two lines (stage attack i): each program's messages escape
# them (\n, \t, \r, \xHH), so a message stays one line `prog: where: what`.
. tests/lib.sh

nl="$TMP/in
put.ply"
esc="$TMP/$(printf 'a\tb\033c').ply"
want_nl="$TMP/in\\nput.ply: No such file or directory"
for p in meshconv meshinfo segplanes simpchain projverts tripatch areaflow qemdecim \
	dm2mesh imginfo tsdfuse meshshot pngsheet; do
	run_case 1 "$p '$nl' >/dev/null" "" "$p: $want_nl"
done
for p in meshdist creaseangle; do
	run_case 1 "$p '$nl' '$nl' >/dev/null" "" "$p: $want_nl"
done
run_case 2 "tolcmp '$nl' '$nl'" "" "tolcmp: $want_nl"
run_case 1 "meshconv '$esc'" "" "meshconv: $TMP/a\\tb\\x1bc.ply: No such file or directory"
# An output folder that is missing, and a line of a bad file (FILE:LINE).
run_case 1 "meshconv -o '$nl/x.ply' tests/data/obj_cube.obj" "" "meshconv: $TMP/in\\nput.ply/x.ply: "
cp tests/bad/obj_nan.obj "$nl"
run_case 1 "meshconv '$nl'" "" "meshconv: $TMP/in\\nput.ply:"
# meshinfo goes on past a bad file: one line for it.
run_case 1 "meshinfo tests/data/obj_cube.obj '$TMP/no
pe.ply' >/dev/null" "" "meshinfo: $TMP/no\\npe.ply: No such file"
finish
