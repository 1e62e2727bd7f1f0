# meshshot and pngsheet: pictures of a textured cube compared with golden
# PNGs within a per-pixel tolerance; exact pixel counts of each face's
# texture seen head-on from six sides and from the mesh's own camera;
# determinism; the contact sheet; errors.
. tests/lib.sh
D=tests/data

# Golden pictures (rewritten by make regold; look at them before committing
# them): the cube from the fitted oblique view, textured with a wireframe,
# and coloured by the vertex property distance with its legend and a title.
run_case 0 "meshshot -s 160x120 --view oblique -w -m texture -o $TMP/tex.png $D/shot_cube.ply"
regold $TMP/tex.png $D/shot_golden_tex.png
run_case 0 "pngsheet -d 2 $TMP/tex.png $D/shot_golden_tex.png"
run_case 0 "meshshot -s 160x120 --view oblique --scalar distance --title d -o $TMP/sc.png $D/shot_cube.ply"
regold $TMP/sc.png $D/shot_golden_scalar.png
run_case 0 "pngsheet -d 2 $TMP/sc.png $D/shot_golden_scalar.png"
# The comparison does see a different picture.
run_case 1 "pngsheet -d 2 $TMP/tex.png $D/shot_golden_scalar.png" "" "pngsheet: $TMP/tex.png $D/shot_golden_scalar.png: "
# Byte-identical output for the same input, to a file or to stdout.
run_case 0 "meshshot -s 160x120 --view oblique -w -m texture $D/shot_cube.ply" "$TMP/tex.png"

# zeros FILE C: the number of zero samples in channel C.
zeros() { imginfo "$1" | awk -v c="$2" '$1 == "channel" && $2 == c { for (i = 3; i < NF; i++) if ($i == "zero") print $(i + 1) }'; }
# Seen head-on from 5 units with f = 81 px in a 101x101 picture, the face
# nearest the eye (2 units wide, 4 units away) covers the pixel centres
# within 20.25 px of the middle: 41 x 41 = 1681 pixels of its own pure
# colour on black, and no other face shows.  Faces: -z red, +z green,
# -x blue, +x yellow, -y cyan, +y magenta (tests/data/shot_gen.py).
fov=$(awk 'BEGIN { printf "%.17g", 2 * atan2(50.5, 81) * 45 / atan2(1, 1) }')
N=10201
check_face() {
	run_case 0 "meshshot --bg 0,0,0 -s 101x101 --fov $fov --eye $1 --target 0,0,0 --up $2 -o $TMP/f.png $D/shot_cube.ply"
	r=$(zeros "$TMP/f.png" 0) g=$(zeros "$TMP/f.png" 1) b=$(zeros "$TMP/f.png" 2)
	check_true "face $3: zeros $r $g $b, expected $4" test "$r $g $b" = "$4"
}
lit=$((N - 1681))
check_face 0,0,-5 0,-1,0 "-z red" "$lit $N $N"
check_face 0,0,5 0,-1,0 "+z green" "$N $lit $N"
check_face -5,0,0 0,-1,0 "-x blue" "$N $N $lit"
check_face 5,0,0 0,-1,0 "+x yellow" "$lit $lit $N"
check_face 0,-5,0 0,0,1 "-y cyan" "$N $lit $lit"
check_face 0,5,0 0,0,1 "+y magenta" "$lit $N $lit"
# Every lit sample is 255 (pure texels: the mean is 255 x 1681 / N).
run_case 0 "imginfo $TMP/f.png"
check_true "pure colours" grep -q "channel 0 min 0 max 255 mean 42.020880305852366 zero $lit" "$TMP/out"

# The same view from the mesh's own camera and pose comments.
sed -e 's/^comment TextureFile.*/comment camera pinhole 101 101 81 81 50 50\
comment pose 1 0 0 0 0 1 0 0 0 0 1 -5/' $D/shot_cube.ply >"$TMP/cam.ply"
run_case 0 "meshshot --bg 0,0,0 --texture $D/shot_atlas.png -o $TMP/c.png $TMP/cam.ply"
check_true "camera view: red face" test "$(zeros "$TMP/c.png" 0) $(zeros "$TMP/c.png" 1)" = "$lit $N"
# Without the TextureFile the default mode is shaded: grey, no pure red.
run_case 0 "meshshot -v --bg 0,0,0 -o $TMP/c.png $TMP/cam.ply"
check_true "auto mode without texture is shaded" grep -q "meshshot: mode=shaded" "$TMP/err"
check_true "1681 pixels covered" grep -q "meshshot: pixels_covered=1681" "$TMP/err"
# Patches: six different palette colours, one per face.
run_case 0 "meshshot -v -m patch --view oblique -o $TMP/p.png $D/shot_cube.ply"

# The contact sheet: two 101x101 cells, border 8, captions 11 px below.
run_case 0 "pngsheet -o $TMP/sheet.png $TMP/f.png=magenta $TMP/c.png"
run_case 0 "imginfo $TMP/sheet.png"
check_true "sheet size" grep -q "^width 226$" "$TMP/out"
check_true "sheet height" grep -q "^height 128$" "$TMP/out"

# A JPEG TextureFile (the atlas at quality 100, shot_atlas.jpg from
# tests/data/jpg_gen.py), told by its content: the oblique picture within 3
# levels of the PNG-textured golden, the head-on red face within 2 of the
# PNG-textured one; the same under a .png name.
cp $D/shot_atlas.jpg "$TMP/atlas.jpg"
cp $D/shot_atlas.jpg "$TMP/atlas_named.png"
sed 's/^comment TextureFile .*/comment TextureFile atlas.jpg/' $D/shot_cube.ply >"$TMP/jcube.ply"
run_case 0 "meshshot -s 160x120 --view oblique -w -m texture -o $TMP/jtex.png $TMP/jcube.ply"
run_case 0 "pngsheet -d 3 $TMP/jtex.png $D/shot_golden_tex.png"
run_case 0 "meshshot --bg 0,0,0 --texture $D/shot_atlas.png -o $TMP/cp.png $TMP/cam.ply"
run_case 0 "meshshot --bg 0,0,0 --texture $TMP/atlas_named.png -o $TMP/cj.png $TMP/cam.ply"
run_case 0 "pngsheet -d 2 $TMP/cj.png $TMP/cp.png"

# Pictures far larger than their files: refused from the header, before
# decoding, by the stated limits (a texture 2^26 pixels, a sheet 2^28), in
# a 512 MB address space (not under the sanitizers, whose shadow memory
# needs more): 17000x17000 in 35 KB, and 60 pictures of 4000x4000 in 2 KB
# each (2.9 GB of RGB).
lim="timeout 20"
[ -z "${FCT_SANITIZE:-}" ] && lim="ulimit -v 524288; timeout 20"
run_case 1 "$lim meshshot --texture $D/big_17000_1bit.png -m texture $D/shot_cube.ply" "" \
	"meshshot: $D/big_17000_1bit.png: byte 16: image size 17000x17000: more than the 67108864 pixels allowed here"
run_case 1 "$lim pngsheet -o $TMP/big.png $D/big_17000_1bit.png" "" \
	"pngsheet: the sheet would be 17016x17038 pixels"
run_case 1 "$lim pngsheet -d 1 $D/big_17000_1bit.png $D/big_17000_1bit.png" "" \
	"pngsheet: $D/big_17000_1bit.png: byte 16: image size 17000x17000: more than the 268435456 pixels"
set --
for i in $(seq 60); do set -- "$@" $D/big_4000_1bit.png; done
run_case 1 "$lim pngsheet -o $TMP/big.png $*" "" "pngsheet: the sheet would be 32072x32248 pixels"
check_true "no sheet written" test ! -e "$TMP/big.png"

# Errors.
run_case 2 "meshshot -s 0x10 $D/shot_cube.ply" "" "meshshot: -s: "
run_case 2 "meshshot --view back $D/shot_cube.ply" "" "meshshot: --view: "
run_case 2 "meshshot -m scalar $D/shot_cube.ply" "" "meshshot: -m scalar: "
run_case 2 "meshshot --eye 1,2 $D/shot_cube.ply" "" "meshshot: --eye: "
run_case 2 "meshshot --eye 0,0,0 --target 0,0,0 $D/shot_cube.ply" "" "meshshot: --eye: "
run_case 1 "meshshot --view camera $D/shot_cube.ply" "" "meshshot: $D/shot_cube.ply: no pinhole camera"
run_case 1 "meshshot --scalar nothing $D/shot_cube.ply" "" "meshshot: $D/shot_cube.ply: --scalar: "
run_case 1 "meshshot -e $D/shot_cube.ply" "" "meshshot: $D/shot_cube.ply: -e: "
run_case 1 "meshshot -m color $D/shot_cube.ply" "" "meshshot: $D/shot_cube.ply: -m color: "
run_case 1 "meshshot -m texture --texture $TMP/none.png $D/shot_cube.ply" "" "meshshot: "
run_case 1 "meshshot $D/dist_nan.ply" "" "meshshot: $D/dist_nan.ply:"
run_case 1 "meshshot $TMP/missing.ply" "" "meshshot: "
run_case 2 "pngsheet" "" "pngsheet: "
run_case 1 "pngsheet -d 0 $TMP/f.png $TMP/sheet.png" "" "pngsheet: "
finish
