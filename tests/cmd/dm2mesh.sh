# dm2mesh: depth images, disparities, cameras, poses, sparse points, checked
# against positions, counts and texture coordinates worked out by hand
# (fixtures from tests/data/dm_gen.py), then real frames.
. tests/lib.sh
D=tests/data

# The vertex lines of an ascii PLY on stdin.
verts() { awk '/^element vertex/ { n = $3 } f && n-- > 0 { print } /^end_header/ { f = 1 }'; }
# meshinfo's value for KEY of a mesh file.
info() { meshinfo "$2" | awk -v k="$1:" '$1 == k { print $2 }'; }
# Every face of an ascii PLY (x y z first) points toward the origin:
# prints the number of faces that do not.
away() {
	awk 'BEGIN { v = 0 } /^element vertex/ { nv = $3 } /^element face/ { nf = $3 }
	f && v < nv { x[v] = $1; y[v] = $2; z[v] = $3; v++; next }
	f && nf-- > 0 { a = $2; b = $3; c = $4
		ux = x[b] - x[a]; uy = y[b] - y[a]; uz = z[b] - z[a]
		wx = x[c] - x[a]; wy = y[c] - y[a]; wz = z[c] - z[a]
		nx = uy * wz - uz * wy; ny = uz * wx - ux * wz; nz = ux * wy - uy * wx
		if (nx * x[a] + ny * y[a] + nz * z[a] >= 0) bad++ }
	/^end_header/ { f = 1 } END { print bad + 0 }'
}

run_case 0 "dm2mesh --help | head -n 1 | grep -q '^usage: dm2mesh \[-aqv\] \[-o file\] \[-K fx,fy,cx,cy | name\]'"
run_case 0 "dm2mesh --version | grep -q '^dm2mesh (facet) '"

# The plane z = 2 + 0.1 x in millimetres, 8x6, holes at two corners: 35
# squares, one triangle lost at each hole's square, 46 vertices.
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 $D/dm_plane16.png > $TMP/plane.ply"
check_num "plane vertices" "$(info vertices $TMP/plane.ply)" == 46
check_num "plane faces" "$(info faces $TMP/plane.ply)" == 68
check_num "plane faces toward the camera" "$(away < $TMP/plane.ply)" == 0
check_num "plane: every vertex within 0.6 mm of z = 2 + 0.1 x" \
	"$(verts < $TMP/plane.ply | awk '{ d = $3 - 2 - 0.1 * $1; if (d < 0) d = -d; if (d > m) m = d } END { print m }')" "<" 0.0006
# The first vertex is pixel (1, 0): depth 2000 / (1 - 0.01 * -2.5) mm rounded
# to 1951 mm, s = 1.5 / 8, t = 1 - 0.5 / 6.
first=$(verts < $TMP/plane.ply | head -n 1)
check_true "first vertex of the plane: $first" test "$first" = "-0.48775 -0.48775 1.951 0.1875 0.9166667"
run_case 0 "grep -q '^comment camera pinhole 8 6 10 10 3.5 2.5\$' $TMP/plane.ply"
run_case 0 "grep -q '^comment facet dm2mesh -a -K 10,10,3.5,2.5 ' $TMP/plane.ply"

# The same camera from every kind of file gives the same mesh.
for cam in dm_cam.json dm_K.txt dm_cam.txt; do
	run_case 0 "dm2mesh -a --camera $D/$cam $D/dm_plane16.png | grep -v '^comment facet' > $TMP/cam.ply"
	run_case 0 "grep -v '^comment facet' $TMP/plane.ply | cmp -s - $TMP/cam.ply"
done
run_case 1 "dm2mesh --camera $D/dm_cam_big.txt $D/dm_plane16.png" "" \
	"dm2mesh: $D/dm_plane16.png: the camera is 640x480 but the depth image is 8x6"
run_case 1 "dm2mesh --camera $D/dm_points.txt $D/dm_plane16.png" "" "dm2mesh: $D/dm_points.txt: "
run_case 1 "dm2mesh --camera $D/nonexistent $D/dm_plane16.png" "" "dm2mesh: $D/nonexistent: "

# Subsampling: pixels 0, 2, 4, 6 of rows 0, 2, 4; (0, 0) has no data.
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --step 2 $D/dm_plane16.png > $TMP/step.ply"
check_num "step 2 vertices" "$(info vertices $TMP/step.ply)" == 11
check_num "step 2 faces" "$(info faces $TMP/step.ply)" == 11
# --range: depths beyond 2 m (columns 4-7) are no data.
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --range 0,2 $D/dm_plane16.png > $TMP/range.ply"
check_num "range faces" "$(info faces $TMP/range.ply)" == 29
# Depth scale: read as 500 units per metre, every depth doubles.
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --depth-scale 500 $D/dm_plane16.png > $TMP/scale.ply"
check_num "scale 500 doubles depth" "$(verts < $TMP/scale.ply | head -n 1 | awk '{ print $3 }')" == 3.902

# Disparity 20 px with baseline 0.1 and focal 100: depth 0.5 everywhere; a
# zero and a NaN disparity are holes (four triangles each).
run_case 0 "dm2mesh -a -K 100,100,3.5,2.5 --baseline 0.1 --focal 100 $D/dm_disp.pfm > $TMP/disp.ply"
check_num "disparity faces" "$(info faces $TMP/disp.ply)" == 62
check_num "disparity depth" "$(verts < $TMP/disp.ply | awk '$3 != 0.5 { n++ } END { print n + 0 }')" == 0
run_case 0 "dm2mesh -a -K 100,100,3.5,2.5 --baseline 0.1 $D/dm_disp.pfm | grep -v '^comment facet' > $TMP/disp2.ply"
run_case 0 "grep -v '^comment facet' $TMP/disp.ply | cmp -s - $TMP/disp2.ply"
# Middlebury: depth = b f / (d + doffs).  The same disparities with doffs 5
# are 0.1 * 100 / 25 = 0.4 m, not 0.5 m; from --doffs, or from a calib.txt
# given as --camera (baseline in millimetres, cam0's K, doffs), whose doffs
# --doffs overrides.
depths() { verts < "$1" | awk '{ if ($3 < lo || !n) lo = $3; if ($3 > hi || !n) hi = $3; n++ } END { print lo, hi }'; }
run_case 0 "dm2mesh -a -K 100,100,3.5,2.5 --baseline 0.1 --doffs 5 $D/dm_disp.pfm > $TMP/doffs.ply"
check_true "--doffs 5: every depth 0.4" test "$(depths $TMP/doffs.ply)" = "0.4 0.4"
run_case 0 "dm2mesh -a --camera $D/dm_middlebury_calib.txt $D/dm_disp.pfm > $TMP/mb.ply"
check_true "calib.txt: every depth 0.4" test "$(depths $TMP/mb.ply)" = "0.4 0.4"
check_num "calib.txt: faces" "$(info faces $TMP/mb.ply)" == 62
run_case 0 "dm2mesh -a --camera $D/dm_middlebury_calib.txt --doffs 0 $D/dm_disp.pfm > $TMP/mb0.ply"
check_true "calib.txt, --doffs 0: every depth 0.5" test "$(depths $TMP/mb0.ply)" = "0.5 0.5"
run_case 2 "dm2mesh -K 100,100,3.5,2.5 --doffs 5 $D/dm_disp.pfm" "" "dm2mesh: --doffs is for disparities and needs --baseline"

# A pose: x_world = z + 1, y_world = y + 2, z_world = -x + 3; the same from
# a 4x4 file and from a pose line.
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --pose $D/dm_pose.txt $D/dm_plane16.png > $TMP/posed.ply"
check_num "posed vertices moved" "$(verts < $TMP/plane.ply > $TMP/v0; verts < $TMP/posed.ply | paste -d' ' $TMP/v0 - |
	awk '{ d = ($6 - $3 - 1) ^ 2 + ($7 - $2 - 2) ^ 2 + ($8 + $1 - 3) ^ 2; if (d > m) m = d } END { print m }')" "<" 1e-12
run_case 0 "grep -q '^comment pose 0 0 1 1 0 1 0 2 -1 0 0 3\$' $TMP/posed.ply"
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --pose $D/dm_pose_line.txt $D/dm_plane16.png | grep -v '^comment facet' > $TMP/posed2.ply"
run_case 0 "grep -v '^comment facet' $TMP/posed.ply | cmp -s - $TMP/posed2.ply"
run_case 1 "dm2mesh -K 10,10,3.5,2.5 --pose $D/dm_badpose.txt $D/dm_plane16.png" "" \
	"dm2mesh: $D/dm_badpose.txt: pose: the 3x3 part is not a rotation"
run_case 1 "dm2mesh -K 10,10,3.5,2.5 --pose $D/dm_shortpose.txt $D/dm_plane16.png" "" \
	"dm2mesh: $D/dm_shortpose.txt: expected a 4x4 or 3x4"

# The image is recorded as given on standard output, relative to the output
# file's folder with -o.
run_case 0 "dm2mesh -K 10,10,3.5,2.5 --image $D/img_rgb8.png $D/dm_plane16.png | grep -a -q '^comment TextureFile $D/img_rgb8.png\$'"
mkdir -p "$TMP/sub"
run_case 0 "cp $D/img_rgb8.png $TMP/tex.png && cd $TMP && dm2mesh -K 10,10,3.5,2.5 --image tex.png -o sub/m.ply \"\$OLDPWD/$D/dm_plane16.png\""
run_case 0 "grep -a -q '^comment TextureFile ../tex.png\$' $TMP/sub/m.ply"

# Same input and options, same bytes; from standard input too.
run_case 0 "dm2mesh -K 10,10,3.5,2.5 $D/dm_plane16.png > $TMP/d1.ply && dm2mesh -K 10,10,3.5,2.5 $D/dm_plane16.png | cmp - $TMP/d1.ply"
run_case 0 "dm2mesh -K 10,10,3.5,2.5 - < $D/dm_plane16.png | grep -a -v '^comment facet' > $TMP/d2.ply && grep -a -v '^comment facet' $TMP/d1.ply | cmp - $TMP/d2.ply"

# Usage errors.
run_case 2 "dm2mesh $D/dm_plane16.png" "" "dm2mesh: no camera: give -K, --camera or --cylindrical"
run_case 2 "dm2mesh -K 1,2,3 $D/dm_plane16.png" "" "dm2mesh: -K: "
run_case 2 "dm2mesh -K nokinect $D/dm_plane16.png" "" "dm2mesh: -K: \"nokinect\" is neither"
run_case 2 "dm2mesh -K 10,-10,3.5,2.5 $D/dm_plane16.png" "" "dm2mesh: -K: focal lengths must be positive"
run_case 2 "dm2mesh -K tum --camera $D/dm_K.txt $D/dm_plane16.png" "" "dm2mesh: -K, --camera and --cylindrical exclude each other"
# -K with an intrinsics file says where it goes.
run_case 2 "dm2mesh -K $D/dm_K.txt $D/dm_plane16.png" "" "dm2mesh: -K: \"$D/dm_K.txt\" is a file: give an intrinsics file with --camera"
# TUM's freiburg3 K typed as numbers leaves the depth scale at 1000: the
# desk's depths come out 7-45 m (median 12.1), and dm2mesh says so.
T=samples/tum/TUM_depth.png
run_case 0 "dm2mesh -K 535.4,539.2,320.1,247.6 -o $TMP/t3.ply $T" "" "dm2mesh: warning: $T: median depth 12.1 m: implausible for an RGB-D sensor (0.3 to 8 m); the camera is tum3's, whose depth units are 5000 a metre, not 1000"
run_case 0 "dm2mesh -K 535.4,539.2,320.1,247.6 --depth-scale 5000 -o $TMP/t3.ply $T 2>&1 | wc -c | grep -qx 0"
run_case 0 "dm2mesh -K tum3 -o $TMP/t3.ply $T 2>&1 | wc -c | grep -qx 0"
run_case 2 "dm2mesh -K tum --focal 5 $D/dm_plane16.png" "" "dm2mesh: --focal is for disparities"
run_case 2 "dm2mesh -K tum --step 0 $D/dm_plane16.png" "" "dm2mesh: --step: "
run_case 2 "dm2mesh -K tum --range 3,1 $D/dm_plane16.png" "" "dm2mesh: --range: "
run_case 2 "dm2mesh -K tum --max-angle 90 $D/dm_plane16.png" "" "dm2mesh: --max-angle: "
run_case 2 "dm2mesh -K tum --max-edge 1 $D/dm_plane16.png" "" "dm2mesh: --max-edge is for --points"
run_case 2 "dm2mesh -K tum a b" "" "dm2mesh: too many operands"
run_case 2 "dm2mesh --bogus" "" "dm2mesh: --bogus: unknown option"
# Bad data.
run_case 1 "dm2mesh -K tum $D/nonexistent.png" "" "dm2mesh: $D/nonexistent.png: "
run_case 1 "dm2mesh -K 10,10,3.5,2.5 $D/img_rgb8.png" "" "dm2mesh: $D/img_rgb8.png: depth image has 3 channels"
run_case 1 "dm2mesh -K 10,10,3.5,2.5 $D/dm_points.txt" "" "dm2mesh: $D/dm_points.txt: "

# Noise models (noise.h).  Each vertex's sigma is its depth's deviation under
# the model times the length of its ray, worked out here from the vertex's
# own position: kinect F B SD STEP with unit U gives
# sqrt((z^2 SD / FB)^2 + (z^2 STEP / FB)^2 / 12 + U^2 / 12) |p| / z.
# sigma_err FB SD STEP U < ascii PLY (x y z first, sigma last): the largest
# relative error over the vertices.
sigma_err() {
	awk -v fb="$1" -v sd="$2" -v st="$3" -v u="$4" '/^element vertex/ { n = $3 }
	f && n-- > 0 { z = $3; g = z * z * sd / fb; q = z * z * st / fb
		s = sqrt(g * g + q * q / 12 + u * u / 12) * sqrt($1 * $1 + $2 * $2 + z * z) / z
		e = ($NF - s) / s; if (e < 0) e = -e; if (e > m) m = e }
	/^end_header/ { f = 1 } END { print m + 0 }'
}
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --noise kinect $D/dm_plane16.png > $TMP/nk.ply"
run_case 0 "grep -q '^comment noise kinect 585 0.075 0.051 0.125 unit 0.001\$' $TMP/nk.ply"
run_case 0 "grep -q '^property float sigma\$' $TMP/nk.ply"
check_num "kinect sigma of every vertex" "$(sigma_err 43.875 0.051 0.125 0.001 < $TMP/nk.ply)" "<" 1e-6
# Numeric intrinsics imply no model: no sigma, no comment.
check_true "no model from numeric -K" sh -c "! grep -a -q -e '^comment noise' -e sigma $TMP/plane.ply"
# A model from a file (mkscene's viewNN.noise), "comment" or not; poly with
# its own unit.
printf 'comment noise poly 0.01 0 0.001 unit 0.0005\n' > $TMP/poly.noise
run_case 0 "dm2mesh -a -K 10,10,3.5,2.5 --noise $TMP/poly.noise $D/dm_plane16.png > $TMP/np.ply"
run_case 0 "grep -q '^comment noise poly 0.01 0 0.001 unit 0.0005\$' $TMP/np.ply"
check_num "poly sigma of every vertex" "$(verts < $TMP/np.ply | awk '{ z = $3; a = 0.01 + 0.001 * z * z
	s = sqrt(a * a + 0.0005 ^ 2 / 12) * sqrt($1 * $1 + $2 * $2 + z * z) / z
	e = ($NF - s) / s; if (e < 0) e = -e; if (e > m) m = e } END { print m + 0 }')" "<" 1e-6
# PFM depth is not quantised: none has no unit, sigma = 1e-6 z |p| / z.
run_case 0 "dm2mesh -a -K 100,100,3.5,2.5 --baseline 0.1 --noise none $D/dm_disp.pfm > $TMP/nn.ply"
run_case 0 "grep -q '^comment noise none\$' $TMP/nn.ply"
check_num "none sigma" "$(verts < $TMP/nn.ply | awk '{ s = 1e-6 * sqrt($1 * $1 + $2 * $2 + $3 * $3)
	e = ($NF - s) / s; if (e < 0) e = -e; if (e > m) m = e } END { print m + 0 }')" "<" 1e-6
run_case 2 "dm2mesh -K tum --noise poly:1 $D/dm_plane16.png" "" "dm2mesh: --noise: expected poly:A,B,C"
run_case 2 "dm2mesh -K tum --noise kinect:0,1 $D/dm_plane16.png" "" "dm2mesh: --noise kinect: F and B must be positive"
run_case 2 "dm2mesh --points --noise none $D/dm_points.txt" "" "dm2mesh: --noise is for depth images"
run_case 1 "dm2mesh -K tum --noise $TMP/nonexistent $D/dm_plane16.png" "" "dm2mesh: $TMP/nonexistent: "
printf 'noise tof\nnoise none\n' > $TMP/two.noise
run_case 1 "dm2mesh -K tum --noise $TMP/two.noise $D/dm_plane16.png" "" "dm2mesh: $TMP/two.noise: expected one line"
printf 'camera pinhole 8 6 10 10 3.5 2.5\n' > $TMP/cam.noise
run_case 1 "dm2mesh -K tum --noise $TMP/cam.noise $D/dm_plane16.png" "" "dm2mesh: $TMP/cam.noise: expected \"noise MODEL ...\""
printf 'noise poly 1 2\n' > $TMP/short.noise
run_case 1 "dm2mesh -K tum --noise $TMP/short.noise $D/dm_plane16.png" "" "dm2mesh: $TMP/short.noise: noise: expected poly:A,B,C"

# Sparse points: a 5x4 lattice of 20 distinct image positions, 14 of them on
# the hull, gives 2n - 2 - h = 24 triangles; a repeated position is left
# unused; all faces toward the camera; s t from the image coordinates in an
# image of the size given by --image.
run_case 0 "dm2mesh -a -v --points -K 100,100,20,15 --image $D/img_rgb8.png $D/dm_points.txt > $TMP/pts.ply 2> $TMP/pts.err"
check_num "points faces" "$(info faces $TMP/pts.ply)" == 24
check_num "points vertices" "$(info vertices $TMP/pts.ply)" == 21
check_num "points isolated" "$(info isolated_vertices $TMP/pts.ply)" == 1
check_num "points duplicates" "$(sed -n 's/^dm2mesh: duplicates=//p' $TMP/pts.err)" == 1
check_num "points toward the camera" "$(away < $TMP/pts.ply)" == 0
run_case 0 "meshinfo $TMP/pts.ply | grep -q '^property: vertex float s\$'"
# Without a camera: the same faces, no s t.
run_case 0 "dm2mesh -a --points $D/dm_points.txt > $TMP/pts0.ply"
check_num "points without camera" "$(info faces $TMP/pts0.ply)" == 24
check_true "points without camera have no s t" sh -c "! meshinfo $TMP/pts0.ply | grep -q 'vertex float s'"
# Long-edge culling: every edge is at least 0.4 m long.
run_case 0 "dm2mesh -a --points --max-edge 0.3 $D/dm_points.txt > $TMP/pts1.ply"
check_num "max-edge culls all" "$(info faces $TMP/pts1.ply)" == 0
# PLY input; collinear points give no faces, not an error.
run_case 0 "dm2mesh -a --points $D/dm_points.ply > $TMP/ptsply.ply"
check_num "points from PLY" "$(info faces $TMP/ptsply.ply)" == 2
run_case 0 "dm2mesh -a --points $D/dm_collinear.txt > $TMP/col.ply"
check_num "collinear points" "$(info faces $TMP/col.ply)" == 0
run_case 1 "dm2mesh --points $D/dm_points_bad.txt" "" "dm2mesh: $D/dm_points_bad.txt:2: expected five numbers"
run_case 1 "dm2mesh --points $D/dm_points_nan.txt" "" "dm2mesh: $D/dm_points_nan.txt"
run_case 1 "dm2mesh --points /dev/null" "" "dm2mesh: /dev/null: no points"
run_case 2 "dm2mesh --points --step 2 $D/dm_points.txt" "" "dm2mesh: --points takes no --baseline or --step"

# A real TUM RGB-D frame (samples/tum, CC BY 4.0): the named camera sets the
# depth scale 5000; depths between 0.5 and 10 m; nearly every square of four
# valid pixels becomes two triangles (discontinuities and specks are few).
run_case 0 "dm2mesh -v -K tum -o $TMP/tum.ply samples/tum/TUM_depth.png 2> $TMP/tum.err"
check_num "tum faces" "$(info faces $TMP/tum.ply)" ">" 450000
check_num "tum near" "$(meshinfo $TMP/tum.ply | awk '$1 == "bbox_min:" { print $4 }')" ">" 0.5
check_num "tum far" "$(meshinfo $TMP/tum.ply | awk '$1 == "bbox_max:" { print $4 }')" "<" 10
check_num "tum jump faces under 3%" "$(awk -F= '/jump_faces/ { j = $2 } /^dm2mesh: faces=/ { f = $2 } END { print j / f }' $TMP/tum.err)" "<" 0.03

# Two real 7-Scenes frames 50 apart, put in the world by their poses, lie on
# each other (the data's README measured 7.6 mm median); with the inverse
# poses they would not.
S=../shared/data/7scenes_redkitchen/frames
if [ -d "$S" ]; then
	run_case 0 "dm2mesh -K 7scenes --step 2 --pose $S/frame-000000.pose.txt -o $TMP/k0.ply $S/frame-000000.depth.png"
	run_case 0 "dm2mesh -K 7scenes --step 2 --pose $S/frame-000050.pose.txt -o $TMP/k50.ply $S/frame-000050.depth.png"
	run_case 0 "meshdist $TMP/k50.ply $TMP/k0.ply > $TMP/k.out"
	check_num "7-Scenes frames agree" "$(awk '$1 == "mean" { print $2 }' $TMP/k.out)" "<" 0.05
	# The dataset's name implies its kinect model, with the PNG's millimetres.
	run_case 0 "dm2mesh -a -K 7scenes --step 4 -o $TMP/k0n.ply $S/frame-000000.depth.png"
	run_case 0 "grep -q '^comment noise kinect 585 0.0738 0.051 0.125 unit 0.001\$' $TMP/k0n.ply"
	check_num "7-Scenes sigma of every vertex" "$(sigma_err 43.173 0.051 0.125 0.001 < $TMP/k0n.ply)" "<" 1e-6
	check_num "7-Scenes median sigma (mm)" "$(meshinfo $TMP/k0n.ply | awk '$1 == "sigma_median:" { print 1000 * $2 }')" ">" 5
fi


# Every piece below --min-faces: an empty mesh, with its properties, and
# status 0 (it failed with an unset message when the properties had no
# vertices to hold).
mkscene -q --size 3x2 --fx 3 --noise kinect -o "$TMP/tiny" >/dev/null
run_case 0 "dm2mesh -v --camera $TMP/tiny/view00.camera --noise $TMP/tiny/view00.noise -o $TMP/tiny.ply $TMP/tiny/view00.depth.pfm"
check_true "a 3x2 image: its 4 faces are a speck" grep -q "^dm2mesh: speck_faces=4$" "$TMP/err"
check_true "a 3x2 image: an empty mesh with s t sigma" test "$(meshinfo "$TMP/tiny.ply" | grep -c -E '^(element: vertex 0|element: face 0|property: vertex float (s|t|sigma))$')" = 5

finish
