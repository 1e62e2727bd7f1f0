# Depth images in netpbm's PGM and in datasets' own encodings (dm2mesh,
# planarize, tsdfuse --depth-code): NYU Depth v2's raw Kinect disparity
# codes written little-endian, SUN RGB-D's bit-rotated millimetres.  The
# fixtures are pieces of the real frames (tests/data/depthcode_gen.py);
# their depths are checked against a decoding of their own: od and awk for
# the PGM, the generator's PNG decoder and the rotation for the PNG.
. tests/lib.sh
N=tests/data/nyu_depth_crop.pgm
S=tests/data/sun_depth_crop.png
# The pieces' cameras: NYU's depth camera and a PrimeSense's, principal
# points moved by the pieces' corners (400, 100) and (240, 120).
KN=582.62448,582.69103,-86.95524,138.4439
KS=525,525,79.5,119.5
# zrange MESH: its smallest and largest z.
zrange() { meshinfo "$1" | awk '$1 == "bbox_min:" { lo = $4 } $1 == "bbox_max:" { hi = $4 } END { print lo, hi }'; }

# PGM: the same depths in ASCII and in binary (2000 and 2500 mm, most
# significant byte first), as a 16-bit PNG would give them.
printf 'P2\n# 3x2, millimetres\n3 2\n65535\n2000 2000 2000\n2500 2500 2500\n' >"$TMP/a.pgm"
printf 'P5 3 2 65535\n\007\320\007\320\007\320\011\304\011\304\011\304' >"$TMP/b.pgm"
run_case 0 "dm2mesh -K 3,3,1,0.5 --min-faces 1 -o $TMP/a.ply $TMP/a.pgm"
check_true "ASCII PGM: depths 2 and 2.5 m" test "$(zrange "$TMP/a.ply")" = "2 2.5"
run_case 0 "dm2mesh -K 3,3,1,0.5 --min-faces 1 -o $TMP/b.ply $TMP/b.pgm"
check_true "binary PGM: depths 2 and 2.5 m" test "$(zrange "$TMP/b.ply")" = "2 2.5"
run_case 1 "dm2mesh -K 3,3,1,0.5 $TMP/b.pgm.none" "" "dm2mesh: $TMP/b.pgm.none: No such file"
printf 'P5 3 2 65535\n\007\320' >"$TMP/c.pgm"
run_case 1 "dm2mesh -K 3,3,1,0.5 $TMP/c.pgm" "" "dm2mesh: $TMP/c.pgm: byte 13: PNM header says 3x2 with 1 channel (12 bytes) but 2 bytes follow"

# NYU: depth = 351.3 / (1092.5 - code), codes read little-endian; 19151
# pixels have data, 2.9397 to 6.6914 m.
expect=$(od -An -v -tu2 --endian=little -j 17 "$N" | awk '{ for (i = 1; i <= NF; i++) if ($i < 1092) {
	d = 351.3 / (1092.5 - $i); if (!n++ || d < lo) lo = d; if (d > hi) hi = d } } END { printf "%d %.5f %.5f", n, lo, hi }')
set -- $expect
check_num "NYU piece: pixels with data" "$1" "==" 19151
run_case 0 "dm2mesh -K $KN --depth-code nyu -o $TMP/n.ply $N"
set -- $expect $(zrange "$TMP/n.ply")
check_num "NYU piece: nearest depth, od's" "$(awk -v a="$4" -v b="$2" 'BEGIN { print (a > b ? a - b : b - a) }')" "<" 1e-5
check_num "NYU piece: farthest meshed depth within od's" "$5" "<=" "$(awk -v b="$3" 'BEGIN { print b + 1e-5 }')"
check_num "NYU piece: the far room is there" "$5" ">" 6.5
# As swap and kinect-raw given apart; read without the byte swap the codes
# are 256 times their low byte plus their high one (3 or 4): beyond 1092,
# no data, unless the low byte is below 5 (or the two bytes equal).
run_case 0 "dm2mesh -K $KN --depth-code swap,kinect-raw -o $TMP/n2.ply $N"
check_true "swap,kinect-raw is nyu" test "$(zrange "$TMP/n2.ply")" = "$(zrange "$TMP/n.ply")"
run_case 0 "dm2mesh -K $KN --depth-code kinect-raw -o $TMP/n3.ply $N"
verts() { meshinfo "$1" | awk '$1 == "element:" && $2 == "vertex" { print $3 }'; }
check_num "kinect-raw without the swap: most depths lost" \
	"$(verts "$TMP/n3.ply")" "<" "$(($(verts "$TMP/n.ply") / 4))"

# SUN: depth = (s >> 3 | s << 13) & 0xffff millimetres: 8456 pixels, 3010 to
# 9870 mm, 919 of them beyond 8192 mm where the rotation wraps.  Read as
# 1/8 mm (--depth-scale 8000), the near ones are right and the far ones not.
run_case 0 "dm2mesh -K $KS --depth-code sun -o $TMP/s.ply $S"
check_true "SUN piece: 3.01 to 9.87 m" test "$(zrange "$TMP/s.ply")" = "3.00999999 9.86999989"
run_case 0 "dm2mesh -K $KS --depth-scale 8000 -o $TMP/s8.ply $S"
set -- $(zrange "$TMP/s8.ply")
check_num "SUN piece as 1/8 mm: nothing beyond 8.192 m" "$2" "<" 8.192

# The programs that read depth images take the code too.
run_case 0 "planarize -v -K $KS --depth-code sun -o $TMP/p.ply $S"
check_num "planarize on the SUN piece: a model" "$(sed -n 's/^planarize: reduction=//p' "$TMP/err")" ">" 1
# A PPM colour frame (NYU's are) textures the model as a PNG written beside
# it, which Blender and Open3D open too: grey 128 in, grey 128 out.
{ printf 'P6\n160 120\n255\n'; head -c 57600 /dev/zero | tr '\0' '\200'; } >"$TMP/c.ppm"
run_case 0 "planarize -K $KN --depth-code nyu -o $TMP/t.obj $N $TMP/c.ppm"
check_true "PPM texture: the material names the PNG" grep -qx "map_Kd t_texture.png" "$TMP/t.mtl"
run_case 0 "imginfo $TMP/t_texture.png"
check_true "PPM texture: a PNG of its size and colour" sh -c "grep -qx 'format png' $TMP/out && grep -qx 'width 160' $TMP/out && grep -q '^channel 2 min 128 max 128 ' $TMP/out"
run_case 2 "planarize -K $KN --depth-code nyu $N $TMP/c.ppm" "" "planarize: -o model is needed: a PGM or PPM image"
printf '1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n' >"$TMP/id.pose"
run_case 0 "tsdfuse --voxel 0.05 -K $KN --depth-code nyu --poses $TMP/id.pose -o $TMP/f.ply $N"
set -- $(zrange "$TMP/f.ply")
check_num "tsdfuse on the NYU piece: near side" "$1" ">" 2.8
check_num "tsdfuse on the NYU piece: far side" "$2" "<" 6.8

# Usage and decoding errors.
run_case 2 "dm2mesh -K $KS --depth-code sunny $S" "" \
	"dm2mesh: --depth-code: \"sunny\" is not a depth code (none swap rotate kinect-raw nyu sun)"
run_case 2 "tsdfuse -K $KS --depth-code x --poses $TMP/id.pose $S" "" "tsdfuse: --depth-code: \"x\" is not a depth code"
run_case 1 "dm2mesh -K 3,3,1,0.5 --depth-code sun $TMP/a.pgm.pfm" "" "dm2mesh: $TMP/a.pgm.pfm:"
mkscene -q --size 8x6 --fx 8 -o "$TMP/m" >/dev/null
run_case 1 "dm2mesh --camera $TMP/m/view00.camera --depth-code sun $TMP/m/view00.depth.pfm" "" \
	"dm2mesh: $TMP/m/view00.depth.pfm: a depth code needs a one-channel 16-bit image, not 1 channel of f32"

# -K nyu implies the code: the whole NYU frame of the shared data, when
# present, gives the depths its README verified (1.4 to 6.7 m, median 3.3).
nyu=
for d in ../shared/data /work/shared/data; do
	[ -f "$d/rgbd_single_frames_formats/NYU_depth.pgm" ] && nyu=$d/rgbd_single_frames_formats/NYU_depth.pgm && break
done
if [ -n "$nyu" ]; then
	run_case 0 "dm2mesh -K nyu -o $TMP/nyu.ply $nyu"
	set -- $(zrange "$TMP/nyu.ply")
	check_num "NYU frame: nearest 1.39 m" "$1" ">" 1.38
	check_num "NYU frame: farthest 6.69 m" "$2" "<" 6.7
	check_num "NYU frame: farthest beyond 6.6 m" "$2" ">" 6.6
else
	echo "depthcode.sh: no rgbd_single_frames_formats in ../shared/data: the NYU frame skipped" >&2
fi
finish
