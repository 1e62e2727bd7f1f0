# mkscene: the synthetic scenes against their analytic truth, read back from
# the files a user gets: depths at pixels from the PFM bytes (od) against
# ray-plane intersections computed here (awk) from scene.txt and the pose
# file, the room's panorama against the room's size, scene.ply's planes
# holding their faces, every point on the mesh (meshdist), noise and dropout
# statistics (meshdist, imginfo), determinism, usage errors, the man page.
. tests/lib.sh

# pfm_at FILE X Y: the sample at column X, row Y (row 0 at the top) of a
# grey little-endian PFM (rows are stored bottom to top).
pfm_at() {
	hdr=$(head -n 3 "$1" | wc -c)
	size=$(sed -n 2p "$1")
	w=${size% *} h=${size#* }
	od -A n -t f4 -j $((hdr + 4 * ((h - 1 - $3) * w + $2))) -N 4 "$1" | tr -d ' '
}
# near DESC VALUE WANT RELTOL: |value - want| <= reltol * |want|.
near() {
	check_num "$1 ($2 vs $3)" "$(awk -v a="$2" -v b="$3" 'BEGIN { d = a - b; if (d < 0) d = -d
		if (b < 0) b = -b; print d / (b > 0 ? b : 1) }')" "<=" "$4"
}
# img KEY FILE: a figure of channel 0 from imginfo (min max mean zero nonfinite).
img() { imginfo "$2" | awk -v k="$1" '$1 == "channel" { for (i = 3; i < NF; i += 2) if ($i == k) print $(i + 1) }'; }
# figure KEY FILE: the value of "KEY value" lines (meshdist) or "prog: KEY=value" lines (-v).
figure() { awk -v k="$1" '$1 == k { print $2 } index($0, ": " k "=") { sub(/.*=/, ""); print }' "$2"; }
# plane_t SCENE_TXT PATCH POSE CAMERA X Y: the depth of pixel (X, Y) on the
# plane PATCH: t = -(n.c + d) / (n.R ray), ray = ((x - cx)/fx, (y - cy)/fy, 1).
plane_t() {
	awk -v p="$2" -v X="$5" -v Y="$6" '
		FILENAME == ARGV[1] && $1 == "plane" && $2 == p { nx = $4; ny = $5; nz = $6; d = $7 }
		FILENAME == ARGV[2] { r++; R[r, 1] = $1; R[r, 2] = $2; R[r, 3] = $3; T[r] = $4 }
		FILENAME == ARGV[3] { fx = $5; fy = $6; cx = $7; cy = $8 }
		END {
			q1 = (X - cx) / fx; q2 = (Y - cy) / fy; q3 = 1
			for (k = 1; k <= 3; k++) D[k] = R[k, 1] * q1 + R[k, 2] * q2 + R[k, 3] * q3
			side = nx * T[1] + ny * T[2] + nz * T[3] + d
			printf "%.17g\n", -side / (nx * D[1] + ny * D[2] + nz * D[3])
		}' "$1" "$3" "$4"
}

# One tilted plane, three views of 64x48 pixels: the camera file, the
# middle view's pose exactly (looking along +x from (0, 0, 1.5)), and the
# depths at corners and inside equal to the ray-plane intersection.
P=$TMP/plane
run_case 0 "mkscene --scene plane --views 3 --size 64x48 --fx 52.5 -o $P"
for f in scene.ply scene.txt view00.depth.pfm view00.truth.pfm view00.color.png view00.patch.png \
	view00.camera view00.pose view02.pose; do
	check_true "plane: $f written" test -s "$P/$f"
done
check_true "plane: no view03" test ! -e "$P/view03.pose"
echo "camera pinhole 64 48 52.5 52.5 31.5 23.5" >"$TMP/cam"
run_case 0 "cat $P/view01.camera" "$TMP/cam"
printf '0 0 1 0\n-1 0 0 0\n0 -1 0 1.5\n0 0 0 1\n' >"$TMP/pose"
run_case 0 "cat $P/view01.pose" "$TMP/pose"
for v in 00 01 02; do
	for xy in "0 0" "63 47" "63 0" "0 47" "31 23" "10 40"; do
		set -- $xy
		near "plane view$v pixel $1,$2" "$(pfm_at $P/view$v.depth.pfm $1 $2)" \
			"$(plane_t $P/scene.txt 0 $P/view$v.pose $P/view$v.camera $1 $2)" 1e-6
	done
done
check_num "plane: one plane" "$(grep -c '^plane ' $P/scene.txt)" == 1
check_num "plane: every pixel on the plane (patch 1)" "$(img min $P/view00.patch.png)" == 1
check_num "plane: every pixel on the plane (patch 1)" "$(img max $P/view00.patch.png)" == 1

# Steps: the panel at 2.5 m left of the middle, the wall at 3.5 m right
# of it, in millimetres and TUM's fifths; the patch image labels the halves
# 2 (panel) and 1 (wall), so its mean is 1.5.
S=$TMP/steps
run_case 0 "mkscene --scene steps --depth png16 -o $S"
check_num "steps png16 min" "$(img min $S/view00.depth.png)" == 2500
check_num "steps png16 max" "$(img max $S/view00.depth.png)" == 3500
check_num "steps png16 mean" "$(img mean $S/view00.depth.png)" == 3000
check_num "steps patch mean" "$(img mean $S/view00.patch.png)" == 1.5
check_num "steps truth left" "$(pfm_at $S/view00.truth.pfm 319 100)" == 2.5
check_num "steps truth right" "$(pfm_at $S/view00.truth.pfm 320 100)" == 3.5
run_case 0 "mkscene --scene steps --depth png16 --depth-scale 5000 -o $S"
check_num "steps png16 5000 min" "$(img min $S/view00.depth.png)" == 12500
check_num "steps png16 5000 max" "$(img max $S/view00.depth.png)" == 17500
# Beyond 65535 units a 16-bit depth becomes 0: at 20000 units per metre the
# wall (70000) but not the panel (50000).
run_case 0 "mkscene --scene steps --depth png16 --depth-scale 20000 -v -o $S 2>$TMP/v"
check_num "steps png16 overflow" "$(figure png16_overflow $TMP/v)" == 153600
check_num "steps png16 overflow zeros" "$(img zero $S/view00.depth.png)" == 153600
check_num "steps png16 panel" "$(img max $S/view00.depth.png)" == 50000
# A working range of [0.5, 3] m drops the wall: half the pixels.
run_case 0 "mkscene --scene steps --range 0.5,3 -o $S"
check_num "steps range zeros" "$(img zero $S/view00.depth.pfm)" == 153600
check_num "steps range truth kept" "$(img zero $S/view00.truth.pfm)" == 0

# The room's panorama from (0, 0, 1.4): on the equator rows the walls, at
# rho = min(3 / |cos theta|, 2 / |sin theta|) with theta = 2 pi u / 2048;
# the top row meets the ceiling 1.4 m up at rho = 1.4 f / 255.5.
R=$TMP/room
run_case 0 "mkscene --views 2 --panorama 2048x512 --points -o $R"
echo "camera cylindrical 2048 512 325.94932345220167 255.5 0" >"$TMP/cam"
run_case 0 "cat $R/pano.camera" "$TMP/cam"
printf '0 0 1 0\n-1 0 0 0\n0 -1 0 1.3999999999999999\n0 0 0 1\n' >"$TMP/pose"
run_case 0 "cat $R/pano.pose" "$TMP/pose"
for u in 0 100 256 512 700 1024 1300 1536 2000; do
	for v in 255 256 200; do
		want=$(awk -v u=$u 'BEGIN { t = 2 * atan2(0, -1) * u / 2048; c = cos(t); s = sin(t)
			if (c < 0) c = -c; if (s < 0) s = -s
			r = c > 0 ? 3 / c : 1e30; if (s > 0 && 2 / s < r) r = 2 / s; printf "%.17g\n", r }')
		near "pano column $u row $v" "$(pfm_at $R/pano.depth.pfm $u $v)" "$want" 1e-6
	done
done
near "pano ceiling" "$(pfm_at $R/pano.depth.pfm 0 0)" 1.7860236634474474 1e-6
near "pano floor" "$(pfm_at $R/pano.depth.pfm 2000 511)" 1.7860236634474474 1e-6

# scene.ply: 25 planes; every vertex of a face with patch p on plane p to
# 1e-9; unit normals; each count is the number of faces with that patch.
meshconv -a "$R/scene.ply" >"$TMP/scene.txt"
awk '
	/^element vertex/ { nv = $3 } /^element face/ { nf = $3 } /^element plane/ { np = $3 }
	/^end_header/ { body = 1; next }
	!body { next }
	++row <= nv { x[row - 1] = $1; y[row - 1] = $2; z[row - 1] = $3; next }
	row <= nv + nf { face[row - nv - 1] = $0; next }
	{ p = row - nv - nf - 1; nx[p] = $1; ny[p] = $2; nz[p] = $3; d[p] = $4; cnt[p] = $5; rms[p] = $6 }
	END {
		bad = 0; worst = 0
		for (f = 0; f < nf; f++) {
			split(face[f], a, " "); k = a[1]; p = a[k + 2]
			if (p < 0) continue
			have[p]++
			for (i = 2; i <= k + 1; i++) {
				v = a[i]; e = nx[p] * x[v] + ny[p] * y[v] + nz[p] * z[v] + d[p]
				if (e < 0) e = -e; if (e > worst) worst = e
			}
		}
		for (p = 0; p < np; p++) {
			u = nx[p] * nx[p] + ny[p] * ny[p] + nz[p] * nz[p] - 1
			if (u > 1e-15 || u < -1e-15 || have[p] != cnt[p] || rms[p] != 0) bad++
		}
		print np, bad, worst
	}' "$TMP/scene.txt" >"$TMP/planes"
read -r np bad worst <"$TMP/planes"
check_num "room planes" "$np" == 25
check_num "room planes with a wrong normal, count or rms" "$bad" == 0
check_num "room: vertices off their planes by" "$worst" "<=" 1e-9
check_true "room: double coordinates" grep -q '^property double x$' "$TMP/scene.txt"
check_true "room: patch property" grep -q '^property int patch$' "$TMP/scene.txt"

# Every pixel's point lies on the mesh: float depths in the PFM, float
# coordinates in the point cloud, so within a few 1e-7 of depths below 8 m.
for base in view00 view01 pano; do
	run_case 0 "meshdist $R/$base.points.ply $R/scene.ply >$TMP/d"
	check_num "room $base points off the mesh" "$(figure max $TMP/d)" "<=" 2e-6
	check_num "room $base points" "$(figure count $TMP/d)" == \
		"$(awk '/^element vertex/ { print $3 }' $R/$base.points.ply)"
done
check_true "room points carry the camera" grep -q -a '^comment camera pinhole 640 480 525 525 319.5 239.5' $R/view00.points.ply
check_true "room points carry the pose" grep -q -a '^comment pose ' $R/view00.points.ply
# In millimetres, half a millimetre of rounding along the ray.
run_case 0 "mkscene --depth png16 --points -o $TMP/room16"
run_case 0 "meshdist $TMP/room16/view00.points.ply $TMP/room16/scene.ply >$TMP/d"
check_num "room png16 points off the mesh" "$(figure max $TMP/d)" "<=" 0.0008
check_num "room png16 points off the mesh" "$(figure max $TMP/d)" ">=" 0.0001

# Noise on the steps, whose planes face the camera: a point moved by e along
# its ray lies |e| from its plane, so meshdist measures the noise itself.
# Gaussian 0.01: rms 0.01 and mean 0.01 sqrt(2 / pi) within 2 percent (the
# estimates' own spread is 0.13 percent).
run_case 0 "mkscene --scene steps --noise gaussian:0.01 --points -v -o $S 2>$TMP/v"
near "gaussian -v stdev" "$(figure noise_stdev $TMP/v)" 0.01 0.02
check_num "gaussian -v noisy pixels" "$(figure noisy $TMP/v)" == 307200
run_case 0 "meshdist $S/view00.points.ply $S/scene.ply >$TMP/d"
near "gaussian rms distance" "$(figure rms $TMP/d)" 0.01 0.02
near "gaussian mean distance" "$(figure mean $TMP/d)" 0.0079788456080286535 0.02
near "gaussian mean depth" "$(img mean $S/view00.depth.pfm)" 3 0.0001
check_num "gaussian truth" "$(img mean $S/view00.truth.pfm)" == 3
cp "$S/view00.depth.pfm" "$TMP/g1.pfm"
# Kinect 0.002: sigma = 0.002 z^2, half the pixels at 2.5 m, half at 3.5 m:
# rms = 0.002 sqrt((2.5^4 + 3.5^4) / 2).
run_case 0 "mkscene --scene steps --noise kinect-gauss:0.002 --points -o $S"
run_case 0 "meshdist $S/view00.points.ply $S/scene.ply >$TMP/d"
near "kinect rms distance" "$(figure rms $TMP/d)" 0.019448650338776981 0.02
# The same seed gives the same bytes; another seed other noise on the same truth.
run_case 0 "mkscene --scene steps --noise gaussian:0.01 --points -o $S"
check_true "same seed, same depth" cmp -s "$S/view00.depth.pfm" "$TMP/g1.pfm"
run_case 0 "mkscene --scene steps --noise gaussian:0.01 --seed 2 -o $S"
check_true "another seed, other depths" sh -c "! cmp -s $S/view00.depth.pfm $TMP/g1.pfm"
# Structured light (kinect: ICL-NUIM's simulation, jitter of half a pixel) on
# the plane, 2.5 m ahead and turned 35 degrees: every depth as written is a
# disparity level 43.875 / (k / 8) (the PFM's floats read back with od), the
# levels about 2.5 m are 2.5^2 / 351 m apart, the rms against the truth is
# the model's (the rms of fct_noise_sigma over the same pixels) within 15%,
# and viewNN.noise says the model for dm2mesh.
run_case 0 "mkscene --scene plane --size 320x240 --fx 262.5 --noise kinect -v -o $TMP/sk 2>$TMP/v"
near "kinect: rms against the truth is the model's" "$(figure noise_stdev $TMP/v)" "$(figure noise_model_rms $TMP/v)" 0.15
check_num "kinect: every pixel measured" "$(figure noisy $TMP/v)" == 76800
pfm_values() { od -A n -v -t f4 -j "$(head -n 3 "$1" | wc -c)" "$1" | tr -s ' ' '\n' | awk 'NF'; }
check_num "kinect: depths off the disparity levels" "$(pfm_values $TMP/sk/view00.depth.pfm |
	awk '$1 > 0 { k = 351 / $1; e = k - int(k + 0.5); if (e < 0) e = -e; if (e > m) m = e } END { print m + 0 }')" "<" 0.001
# Neighbouring levels z1 < z2 are z1 z2 / 351 apart (1 / z1 - 1 / z2 = 1 / 351):
# the median ratio of the gaps to that, between 2 and 3 m.
near "kinect: levels z^2 / 351 apart" "$(pfm_values $TMP/sk/view00.depth.pfm | sort -g -u |
	awk '$1 > 2 && $1 < 3 { if (p) print ($1 - p) / (p * $1 / 351); p = $1 }' | sort -g |
	awk '{ r[NR] = $1 } END { print r[int((NR + 1) / 2)] }')" 1 0.01
check_true "kinect: view00.noise" test "$(cat $TMP/sk/view00.noise)" = "noise kinect 585 0.075 0.051 0.125"
run_case 0 "dm2mesh --camera $TMP/sk/view00.camera --noise $TMP/sk/view00.noise $TMP/sk/view00.depth.pfm | meshinfo - | grep -qx 'noise: kinect 585 0.075 0.051 0.125'"
cp "$TMP/sk/view00.depth.pfm" "$TMP/k1.pfm"
run_case 0 "mkscene --scene plane --size 320x240 --fx 262.5 --noise kinect -o $TMP/sk"
check_true "kinect: same seed, same depth" cmp -s "$TMP/sk/view00.depth.pfm" "$TMP/k1.pfm"
run_case 0 "mkscene --scene plane --size 320x240 --fx 262.5 --noise kinect --jitter 0 -v -o $TMP/sk 2>$TMP/v0"
check_num "kinect: jitter adds to the error on the slant" "$(figure noise_stdev $TMP/v0)" "<" "$(figure noise_stdev $TMP/v)"
check_true "kinect: jitter moves the depths" sh -c "! cmp -s $TMP/sk/view00.depth.pfm $TMP/k1.pfm"
# The other models' files: Gaussian as poly, png16's millimetres as unit;
# none by default; both Gaussian kinds together: no file.
run_case 0 "mkscene --scene cube --size 64x48 --noise gaussian:0.01 -o $TMP/g && cat $TMP/g/view00.noise" ""
check_true "gaussian: view00.noise" test "$(cat $TMP/out)" = "noise poly 0.01 0 0"
run_case 0 "mkscene --scene cube --size 64x48 --noise kinect-gauss:0.0015 --depth png16 -o $TMP/g && cat $TMP/g/view00.noise" ""
check_true "kinect-gauss: view00.noise" test "$(cat $TMP/out)" = "noise poly 0 0 0.0015 unit 0.001"
run_case 0 "mkscene --scene cube --size 64x48 -o $TMP/g0 && cat $TMP/g0/view00.noise" ""
check_true "no noise: view00.noise" test "$(cat $TMP/out)" = "noise none"
run_case 0 "mkscene --scene cube --size 64x48 --noise gaussian:0.01 --noise kinect-gauss:0.001 -o $TMP/g2"
check_true "both Gaussian kinds: no view00.noise" test ! -e "$TMP/g2/view00.noise"
run_case 0 "mkscene --scene cube --size 64x48 --noise stereo:40,0.1 -v -o $TMP/g3 2>$TMP/v3"
near "stereo: rms against the truth is the model's" "$(figure noise_stdev $TMP/v3)" "$(figure noise_model_rms $TMP/v3)" 0.1

# Missing 10 percent: zeros within a percent of 30720.  Outliers 5 percent:
# depths up to 1.5 times the truth.
run_case 0 "mkscene --scene steps --missing 0.1 --outliers 0.05 -v -o $S 2>$TMP/v"
zeros=$(img zero $S/view00.depth.pfm)
near "missing fraction" "$(awk -v z=$zeros 'BEGIN { print z / 307200 }')" 0.1 0.1
check_num "missing -v" "$(figure missing $TMP/v)" == "$zeros"
near "outliers fraction" "$(awk -v o=$(figure outliers $TMP/v) -v z=$zeros 'BEGIN { print o / (307200 - z) }')" 0.05 0.2
check_num "outliers reach beyond the wall" "$(img max $S/view00.depth.pfm)" ">" 3.6
check_num "outliers stay below 1.5 times the wall" "$(img max $S/view00.depth.pfm)" "<" 5.25
# Grazing 30 degrees on the fronto-parallel steps keeps the pixels within
# 30 degrees of the optical axis: x^2 + y^2 < tan^2(30) 525^2 (within a few
# pixels: those on the circle are decided by rounding).
run_case 0 "mkscene --scene steps --grazing 30 -o $S"
kept=$(awk 'BEGIN { t = 525 * 525 / 3; n = 0
	for (y = 0; y < 480; y++) for (x = 0; x < 640; x++) { a = x - 319.5; b = y - 239.5; n += a * a + b * b < t }
	print n }')
near "grazing kept" "$((307200 - $(img zero $S/view00.depth.pfm)))" "$kept" 0.001

# The whole output is deterministic: a second run into the same folder
# writes the same bytes.
run_case 0 "mkscene --views 2 --panorama 256x64 --noise kinect-gauss:0.0015 --missing 0.05 --points -o $TMP/det1"
mkdir "$TMP/det2"
cp "$TMP"/det1/* "$TMP/det2/"
run_case 0 "mkscene --views 2 --panorama 256x64 --noise kinect-gauss:0.0015 --missing 0.05 --points -o $TMP/det1"
check_true "same options, same bytes" sh -c "for f in $TMP/det1/*; do cmp -s \$f $TMP/det2/\${f##*/} || exit 1; done"
check_num "files of a run" "$(ls $TMP/det1 | wc -l)" == 26
run_case 0 "mkscene --views 2 --panorama 256x64 --noise kinect --missing 0.05 --points -o $TMP/det3"
mkdir "$TMP/det4"
cp "$TMP"/det3/* "$TMP/det4/"
run_case 0 "mkscene --views 2 --panorama 256x64 --noise kinect --missing 0.05 --points -o $TMP/det3"
check_true "same options, same bytes (kinect)" sh -c "for f in $TMP/det3/*; do cmp -s \$f $TMP/det4/\${f##*/} || exit 1; done"
check_num "files of a kinect run" "$(ls $TMP/det3 | wc -l)" == 26

# -K sets the intrinsics; the camera file says so.
run_case 0 "mkscene --scene cube --size 100x80 -K 90,95,49,41.5 -o $TMP/k"
echo "camera pinhole 100 80 90 95 49 41.5" >"$TMP/cam"
run_case 0 "cat $TMP/k/view00.camera" "$TMP/cam"
run_case 0 "mkscene --scene cube --views 0 -o $TMP/none && ls $TMP/none | tr '\n' ' '"
check_true "views 0: only the scene" test "$(cat "$TMP/out")" = "scene.ply scene.txt "

# Usage and errors: one line each.
run_case 2 "mkscene" "" "mkscene: -o dir is needed"
run_case 2 "mkscene -o $TMP/x extra" "" "mkscene: extra: unexpected operand"
run_case 2 "mkscene --scene attic -o $TMP/x" "" "mkscene: --scene: \"attic\" is not one of room plane steps cube sphere"
run_case 2 "mkscene --size 0x5 -o $TMP/x" "" "mkscene: --size: \"0x5\" is not WxH"
run_case 2 "mkscene --size 640 -o $TMP/x" "" "mkscene: --size: \"640\" is not WxH"
run_case 2 "mkscene --size 640x480x3 -o $TMP/x" "" "mkscene: --size: "
run_case 2 "mkscene --size 100000x100000 -o $TMP/x" "" "mkscene: --size: "
run_case 2 "mkscene --panorama -5x5 -o $TMP/x" "" "mkscene: --panorama: "
run_case 2 "mkscene --views -1 -o $TMP/x" "" "mkscene: --views: -1 must be in [0, 1000]"
run_case 2 "mkscene --views many -o $TMP/x" "" "mkscene: --views: \"many\" is not an integer"
run_case 2 "mkscene --noise perlin:1 -o $TMP/x" "" "mkscene: --noise: \"perlin:1\" is not gaussian:sigma, kinect-gauss:a or a sensor model (none kinect tof poly stereo)"
run_case 2 "mkscene --noise kinect:0.0012 -o $TMP/x" "" "mkscene: --noise: kinect:0.0012: sigma = a z^2 is kinect-gauss:a; kinect takes F,B[,SD[,STEP]]"
run_case 2 "mkscene --noise kinect:0,1 -o $TMP/x" "" "mkscene: --noise kinect: F and B must be positive"
run_case 2 "mkscene --noise kinect --noise gaussian:0.01 -o $TMP/x" "" "mkscene: --noise: gaussian:0.01 and a sensor model exclude each other"
run_case 2 "mkscene --noise gaussian:0.01 --noise tof -o $TMP/x" "" "mkscene: --noise: tof: one sensor model, without gaussian: or kinect-gauss:"
run_case 2 "mkscene --jitter -1 -o $TMP/x" "" "mkscene: --jitter: -1 must be in [0, 10]"
run_case 2 "mkscene --noise gaussian:x -o $TMP/x" "" "mkscene: --noise gaussian: \"x\" is not a number"
run_case 2 "mkscene --noise gaussian:-1 -o $TMP/x" "" "mkscene: --noise gaussian: -1 must be in"
run_case 2 "mkscene --missing 2 -o $TMP/x" "" "mkscene: --missing: 2 must be in [0, 1]"
run_case 2 "mkscene --outliers nan -o $TMP/x" "" "mkscene: --outliers: \"nan\" is not a number"
run_case 2 "mkscene --depth jpg -o $TMP/x" "" "mkscene: --depth: \"jpg\" is not png16 or pfm"
run_case 2 "mkscene --depth-scale 0 -o $TMP/x" "" "mkscene: --depth-scale: 0 must be in"
run_case 2 "mkscene -K 1,2,3 -o $TMP/x" "" "mkscene: -K: \"1,2,3\" is not 4 comma-separated numbers"
run_case 2 "mkscene -K 0,1,2,3 -o $TMP/x" "" "mkscene: -K: the focal lengths must be positive"
run_case 2 "mkscene -K 1,1,2,3 --fx 5 -o $TMP/x" "" "mkscene: -K and --fx exclude each other"
run_case 2 "mkscene --range 3,1 -o $TMP/x" "" "mkscene: --range: \"3,1\" is not near,far"
run_case 2 "mkscene --grazing 91 -o $TMP/x" "" "mkscene: --grazing: 91 must be in [0, 90]"
run_case 2 "mkscene --seed -3 -o $TMP/x" "" "mkscene: --seed: -3 must be in"
run_case 2 "mkscene -x -o $TMP/x" "" "mkscene: -x: unknown option"
run_case 2 "mkscene --bogus -o $TMP/x" "" "mkscene: --bogus: unknown option"
run_case 2 "mkscene --views" "" "mkscene: --views: unknown option, or it needs an argument"
check_true "no folder made by a usage error" test ! -e "$TMP/x"
: >"$TMP/file"
run_case 1 "mkscene -o $TMP/file" "" "mkscene: $TMP/file: exists and is not a folder"
run_case 1 "mkscene -o $TMP/no/such/dir" "" "mkscene: $TMP/no/such/dir: No such file or directory"

# The usage (tests/cmd/manpages.sh checks --help against the man page's
# synopsis, tests/cmd/man_examples.sh runs its examples).
run_case 0 "mkscene --help | head -n 1 | grep -q '^usage: mkscene \[-qv\] \[-K fx,fy,cx,cy\] '"
run_case 0 "mkscene --version | grep -q '^mkscene (facet) '"

finish
