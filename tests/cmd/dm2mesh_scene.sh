# dm2mesh on synthetic scenes with exact ground truth (mkscene): the mesh of
# a noiseless depth map lies on the true surface, pinhole and cylindrical; no
# face spans a depth discontinuity; subsampling and holes; Kinect-class noise
# is not mistaken for discontinuities.
. tests/lib.sh

# figure KEY FILE: the "key value" line of a meshdist output.
figure() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }
# report KEY FILE: a dm2mesh -v figure.
report() { sed -n "s/^dm2mesh: $1=//p" "$2"; }

# A room with boxes, a sphere and a cylinder, one pinhole view, exact float
# depth: every vertex on scene.ply to float precision (the issue's bound is
# 1e-4 of the depth; depths here are 0.5 to 7 m, so 1e-5 m is stricter).
S=$TMP/room
run_case 0 "mkscene --panorama 720x180 -o $S"
run_case 0 "dm2mesh -v --camera $S/view00.camera --pose $S/view00.pose -o $TMP/room.ply $S/view00.depth.pfm 2> $TMP/room.err"
run_case 0 "meshdist $TMP/room.ply $S/scene.ply > $TMP/room.dist"
check_num "room: vertices on the true surface" "$(figure max $TMP/room.dist)" "<" 1e-5
check_num "room: nearly all pixels meshed" "$(figure count $TMP/room.dist)" ">" 300000
check_num "room: few faces cut as jumps" "$(report jump_faces $TMP/room.err)" "<" 10000

# The cylindrical panorama of the same room, from its centre: on the true
# surface, and the seam closed (faces join the last column to the first,
# whose texture coordinates s are about 1 and 0).
run_case 0 "dm2mesh -a --camera $S/pano.camera --pose $S/pano.pose -o $TMP/pano.ply $S/pano.depth.pfm"
run_case 0 "meshdist $TMP/pano.ply $S/scene.ply > $TMP/pano.dist"
check_num "panorama: vertices on the true surface" "$(figure max $TMP/pano.dist)" "<" 1e-5
check_num "panorama: faces across the seam" "$(awk '/^element vertex/ { nv = $3 } /^element face/ { nf = $3 }
	f && v < nv { s[v++] = $4; next } f && nf-- > 0 { lo = hi = 0
		for (k = 2; k <= 4; k++) { if (s[$k] < 0.01) lo = 1; if (s[$k] > 0.99) hi = 1 }
		n += lo && hi } /^end_header/ { f = 1; v = 0 } END { print n + 0 }' $TMP/pano.ply)" ">" 300
check_num "panorama: all of the circle" "$(meshinfo $TMP/pano.ply | awk '$1 == "bbox_size:" { print $2 }')" "==" 6

# Two parallel walls 1 m apart: points sampled on the faces lie on the true
# surface, so no face spans the jump; with the jump test off, faces bridge
# it and lie up to 0.5 m off.
P=$TMP/steps
run_case 0 "mkscene --scene steps --size 320x240 --fx 262.5 -o $P"
run_case 0 "dm2mesh --camera $P/view00.camera --pose $P/view00.pose -o $TMP/steps.ply $P/view00.depth.pfm"
run_case 0 "meshdist -s 100000 $TMP/steps.ply $P/scene.ply > $TMP/steps.dist"
check_num "steps: faces on the surfaces" "$(figure max $TMP/steps.dist)" "<" 1e-6
run_case 0 "dm2mesh -j 1e9 --camera $P/view00.camera --pose $P/view00.pose -o $TMP/bridge.ply $P/view00.depth.pfm"
run_case 0 "meshdist -s 100000 $TMP/bridge.ply $P/scene.ply > $TMP/bridge.dist"
check_num "steps without the jump test bridge the gap" "$(figure max $TMP/bridge.dist)" ">" 0.4
# Kinect-class noise (sigma = 0.0012 z^2): the jump is still cut (sampled
# points within noise of the surface, far from 0.5 m) and noise cuts few faces.
run_case 0 "mkscene --scene steps --size 320x240 --fx 262.5 --noise kinect-gauss:0.0012 -o $P/n"
run_case 0 "dm2mesh -v --camera $P/n/view00.camera --pose $P/n/view00.pose -o $TMP/noisy.ply $P/n/view00.depth.pfm 2> $TMP/noisy.err"
run_case 0 "meshdist -s 100000 $TMP/noisy.ply $P/scene.ply > $TMP/noisy.dist"
check_num "noisy steps: no face across the jump" "$(figure max $TMP/noisy.dist)" "<" 0.1
check_num "noisy steps: under 2% of faces cut" "$(awk -F= '/jump_faces/ { j = $2 } /^dm2mesh: faces=/ { f = $2 } END { print j / (f + j) }' $TMP/noisy.err)" "<" 0.02

# Subsampling one in five: 64 x 48 samples of a view that sees the room
# everywhere, all on the true surface.
run_case 0 "mkscene --size 320x240 --fx 262.5 -o $TMP/small"
run_case 0 "dm2mesh --step 5 --camera $TMP/small/view00.camera --pose $TMP/small/view00.pose -o $TMP/step5.ply $TMP/small/view00.depth.pfm"
run_case 0 "meshdist $TMP/step5.ply $TMP/small/scene.ply > $TMP/step5.dist"
check_num "step 5: vertices on the surface" "$(figure max $TMP/step5.dist)" "<" 1e-5
check_num "step 5: at most 64 x 48 vertices" "$(figure count $TMP/step5.dist)" "<=" 3072
check_num "step 5: nearly all of them" "$(figure count $TMP/step5.dist)" ">" 2900

# Holes: 20% of the pixels without data; every vertex is a pixel with data,
# and nearly every such pixel is a vertex.
run_case 0 "mkscene --size 320x240 --fx 262.5 --missing 0.2 -o $TMP/holes"
run_case 0 "dm2mesh --min-faces 0 --camera $TMP/holes/view00.camera --pose $TMP/holes/view00.pose -o $TMP/holes.ply $TMP/holes/view00.depth.pfm"
valid=$(imginfo $TMP/holes/view00.depth.pfm | awk '$1 == "channel" { print 320 * 240 - $10 }')
verts=$(meshinfo $TMP/holes.ply | awk '$1 == "vertices:" { print $2 }')
check_num "holes: vertices only at pixels with data" "$verts" "<=" "$valid"
check_num "holes: most pixels with data are vertices" "$verts" ">" "$(awk -v v="$valid" 'BEGIN { print 0.97 * v }')"
run_case 0 "meshdist $TMP/holes.ply $TMP/holes/scene.ply > $TMP/holes.dist"
check_num "holes: on the surface" "$(figure max $TMP/holes.dist)" "<" 1e-5

# 16-bit PNG depth in millimetres: z within half a millimetre of the truth,
# so the vertex within 0.5 mm times the longest ray (1.25 at this image's
# corners, z = 1) of the surface.
run_case 0 "mkscene --size 320x240 --fx 262.5 --depth png16 -o $TMP/png"
run_case 0 "dm2mesh --camera $TMP/png/view00.camera --pose $TMP/png/view00.pose -o $TMP/png.ply $TMP/png/view00.depth.png"
run_case 0 "meshdist $TMP/png.ply $TMP/png/scene.ply > $TMP/png.dist"
check_num "png16: within 0.5 mm along z" "$(figure max $TMP/png.dist)" "<" 0.000626

# A georeferenced pose (the room moved 500 km east, 4000 km north): float
# rounded the world coordinates to 0.25 m and segplanes found 87 patches
# and no noise where the room at home has 28; written as double, the
# planes are the same.
G=$TMP/geo
mkscene -q --views 1 --size 160x120 --fx 131.25 --noise kinect-gauss:0.0015 -o "$G"
awk 'NR == 1 { $4 += 500000 } NR == 2 { $4 += 4000000 } { print }' "$G/view00.pose" >"$G/far.pose"
run_case 0 "dm2mesh -v --camera $G/view00.camera --pose $G/far.pose -o $G/far.ply $G/view00.depth.pfm 2>$G/far.err"
check_num "georeferenced: double positions reported" "$(report double_xyz "$G/far.err")" == 1
check_true "georeferenced: x is double on disk" sh -c "meshinfo $G/far.ply | grep -q '^property: vertex double x'"
run_case 0 "dm2mesh --camera $G/view00.camera --pose $G/view00.pose -o $G/near.ply $G/view00.depth.pfm"
check_true "at home: x stays float" sh -c "meshinfo $G/near.ply | grep -q '^property: vertex float x'"
segfig() { segplanes -v -o /dev/null "$1" 2>&1 | sed -n "s/^segplanes: $2=//p"; }
check_num "georeferenced: segplanes' patches as at home" "$(segfig "$G/far.ply" patches)" == "$(segfig "$G/near.ply" patches)"
check_num "georeferenced: segplanes' noise as at home" "$(segfig "$G/far.ply" noise)" == "$(segfig "$G/near.ply" noise)"
finish
