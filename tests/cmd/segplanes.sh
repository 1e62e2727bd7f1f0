# segplanes: a hand-made cube (six exact patches), bad input and usage, and
# mkscene rooms with exact ground truth: the automatic criterion recovers
# every true plane big enough to be seen, as one patch, its normal within a
# degree, with Kinect-class and Gaussian noise, at dm2mesh step 1 and 5;
# noiseless scenes give exact planes.
. tests/lib.sh

# report KEY FILE: a segplanes -v figure.
report() { sed -n "s/^segplanes: $1=//p" "$2"; }

# The unit cube, two triangles a face, wound outward (ascii PLY).
cat >"$TMP/cube.ply" <<'EOF'
ply
format ascii 1.0
comment a unit cube
element vertex 8
property float x
property float y
property float z
element face 12
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
1 1 0
0 0 1
1 0 1
0 1 1
1 1 1
3 0 2 3
3 0 3 1
3 4 5 7
3 4 7 6
3 0 1 5
3 0 5 4
3 2 6 7
3 2 7 3
3 0 4 6
3 0 6 2
3 1 3 7
3 1 7 5
EOF
# The patches are the six squares, numbered by their first face; the planes
# are exact: outward normals, d = 0 or -1, rms 0, four vertices each.
cat >"$TMP/cube.want" <<'EOF'
0 0 1 1 2 2 3 3 4 4 5 5
0 0 -1 0 4 0
0 0 1 -1 4 0
0 -1 0 0 4 0
0 1 0 -1 4 0
-1 0 0 0 4 0
1 0 0 -1 4 0
EOF
# body FILE: the face patch labels on one line, then the plane rows.
body() {
	awk '/^element face/ { nf = $3 } /^element vertex/ { nv = $3 } /^element plane/ { np = $3 }
		/^end_header/ { h = 1; next } !h { next }
		nv > 0 { nv--; next }
		nf > 0 { printf "%s%s", (c++ ? " " : ""), $NF; if (--nf == 0) print ""; next }
		np > 0 { print $1 + 0, $2 + 0, $3 + 0, $4 + 0, $5, $6 + 0; np-- }' "$1"
}
for opts in "" "-n 6" "--area-weighted" "--max-rms 0 -n 1" "-c 100"; do
	run_case 0 "segplanes -a $opts -o $TMP/cube.out $TMP/cube.ply"
	body "$TMP/cube.out" >"$TMP/cube.got"
	check_true "cube ($opts): six exact patches" cmp -s "$TMP/cube.got" "$TMP/cube.want"
done
# The input travels through: its comment, then the provenance; the face
# element gains patch, the plane element follows.
run_case 0 "segplanes -a -o $TMP/cube.out $TMP/cube.ply"
check_true "cube: comments kept, provenance added" \
	awk '/^comment/ { c = c $0 "|" } END { exit !(c ~ /^comment a unit cube\|comment facet segplanes -a -o /) }' "$TMP/cube.out"
check_true "cube: face patch and plane element" awk '
	/^property int patch/ { p = 1 } /^element plane 6$/ { e = 1 }
	/^property double (nx|ny|nz|d|rms)$/ { n++ } /^property int count$/ { k = 1 }
	END { exit !(p && e && n == 5 && k) }' "$TMP/cube.out"
# Binary by default, and the same from stdin; -v figures.
run_case 0 "segplanes -v <$TMP/cube.ply >$TMP/cube.bin 2>$TMP/cube.err"
run_case 0 "meshconv -a $TMP/cube.bin | sed -n '/^end_header/,\$p'" ""
sed -n '/^end_header/,$p' "$TMP/cube.out" >"$TMP/cube.body"
run_case 0 "meshconv -a $TMP/cube.bin | sed -n '/^end_header/,\$p'" "$TMP/cube.body"
check_num "cube -v patches" "$(report patches "$TMP/cube.err")" == 6
check_num "cube -v merges" "$(report merges "$TMP/cube.err")" == 6
check_num "cube -v max_rms" "$(report max_rms "$TMP/cube.err")" == 0
check_num "cube -v noise (too few vertices to tell: exact data)" "$(report noise "$TMP/cube.err")" "<" 1e-6

# Bad input: no faces (empty, or points), unreadable; bad usage.
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n' >"$TMP/empty.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 2 3\n' >"$TMP/points.ply"
run_case 1 "segplanes $TMP/empty.ply" "" "segplanes: $TMP/empty.ply: no faces to segment (an empty mesh)"
run_case 1 "segplanes <$TMP/points.ply" "" "segplanes: <stdin>: no faces to segment (a point cloud"
run_case 1 "segplanes $TMP/missing.ply" "" "segplanes: $TMP/missing.ply: "
run_case 1 "printf 'ply\\nformat ascii 1.0\\nelement vertex 3\\n' | segplanes" "" "segplanes: <stdin>"
run_case 2 "segplanes -c x $TMP/cube.ply" "" 'segplanes: -c: "x" is not a number'
run_case 2 "segplanes -n 0 $TMP/cube.ply" "" "segplanes: -n: "
run_case 2 "segplanes -n 3 -c 2 $TMP/cube.ply" "" "segplanes: -c and -n exclude each other"
run_case 2 "segplanes --max-rms -1 $TMP/cube.ply" "" "segplanes: --max-rms: "
run_case 2 "segplanes -Z $TMP/cube.ply" "" "segplanes: -Z: "
run_case 2 "segplanes $TMP/cube.ply $TMP/cube.ply" "" "segplanes: too many operands"
run_case 0 "segplanes --help | head -n 1 | grep -q '^usage: segplanes '"
run_case 0 "segplanes --version | grep -q '^segplanes (facet) '"
# A single triangle is one patch; so is a 2 x 2 grid of coplanar squares.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n2 0 0\n0 0 3\n3 0 1 2\n' >"$TMP/tri.ply"
run_case 0 "segplanes -a -o $TMP/tri.out $TMP/tri.ply"
body "$TMP/tri.out" >"$TMP/tri.got"
printf '0\n0 -1 0 0 3 0\n' >"$TMP/tri.want"
check_true "single face: one patch, n = -y" cmp -s "$TMP/tri.got" "$TMP/tri.want"

# evaluate LABELS SEG SCENE FRACTION: the true plane of each face of SEG
# (a segplanes ascii output of dm2mesh of a view) from LABELS (dm2mesh of
# the view's patch.png as a depth image: z = true patch + 1 at the same
# s t), the true normals from SCENE (scene.ply as ascii).  A plane is big
# enough to be seen when FRACTION of the faces or more are on it.  Prints
# "big B", "one N" (big planes that are the majority of exactly one patch
# of that size, and the majority of that patch), "extra E" (more such
# patches than planes), "angle A" (the largest angle between a big plane's
# normal and its patch's), "rms R" (the largest rms of those patches).
evaluate() {
	awk -v frac="$4" '
	function header() { if ($1 == "element") { el = $2; cnt[el] = $3 } }
	FNR == 1 { file++; h = 0; delete cnt; vi = 0; fi = 0; pi = 0; ti = 0 }
	!h { header(); if ($1 == "end_header") h = 1; next }
	file == 1 { if (vi++ < cnt["vertex"]) lab[$4 " " $5] = $3 - 1; next }
	file == 2 {
		if (vi < cnt["vertex"]) { k = $4 " " $5; vl[vi++] = (k in lab) ? lab[k] : -1; next }
		if (fi < cnt["face"]) {
			fi++; a = vl[$2]; t = (a >= 0 && vl[$3] == a && vl[$4] == a) ? a : -1
			p = $NF; T[t]++; P[p]++; C[t, p]++; nf++; next }
		if (pi < cnt["plane"]) { pn[pi, 0] = $1; pn[pi, 1] = $2; pn[pi, 2] = $3; prms[pi] = $6; pi++ }
		next }
	file == 3 && cnt["vertex"] > 0 { cnt["vertex"]--; next }
	file == 3 && cnt["face"] > 0 { cnt["face"]--; next }
	file == 3 && ti < cnt["plane"] { tn[ti, 0] = $1; tn[ti, 1] = $2; tn[ti, 2] = $3; ti++ }
	END {
		n = frac * nf
		for (t in T) if (t >= 0 && T[t] >= n) big++
		for (p in P) {
			if (P[p] < n) continue
			for (t in T) if (t >= 0 && T[t] >= n && 2 * C[t, p] > P[p]) {
				cover[t]++
				d = pn[p, 0] * tn[t, 0] + pn[p, 1] * tn[t, 1] + pn[p, 2] * tn[t, 2]
				d = d > 1 ? 1 : d < -1 ? -1 : d
				a = atan2(sqrt(1 - d * d), d) * 45 / atan2(1, 1)
				if (a > amax) amax = a
				if (prms[p] > rmax) rmax = prms[p]
			}
		}
		for (t in cover) { if (cover[t] == 1) one++; else extra += cover[t] - 1 }
		printf "big %d\none %d\nextra %d\nangle %.6f\nrms %.9g\n", big, one, extra, amax, rmax
	}' "$1" "$2" "$3"
}
figure() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }

# scene NAME MKSCENE-ARGS: the scene, its view's labels and true planes.
scene() {
	name=$1
	shift
	run_case 0 "mkscene $* -o $TMP/$name"
	run_case 0 "dm2mesh -a --camera $TMP/$name/view00.camera --depth-scale 1 -j 1e9 --min-faces 0 -o $TMP/$name.lab.ply $TMP/$name/view00.patch.png"
	run_case 0 "meshconv -a -o $TMP/$name.scene.ply $TMP/$name/scene.ply"
}
# view NAME STEP FRACTION TAG [SEGPLANES-ARGS]: mesh the view at STEP,
# segment, evaluate into $TMP/TAG.eval (and TAG.err: the -v figures).
view() {
	name=$1 step=$2 frac=$3 tag=$4
	shift 4
	d=$TMP/$name
	[ -f "$d-$step.ply" ] ||
		run_case 0 "dm2mesh --step $step --camera $d/view00.camera --pose $d/view00.pose --noise $d/view00.noise -o $d-$step.ply $d/view00.depth.pfm"
	run_case 0 "segplanes -a -v $* -o $TMP/$tag.seg.ply $d-$step.ply 2>$TMP/$tag.err"
	evaluate "$d.lab.ply" "$TMP/$tag.seg.ply" "$d.scene.ply" "$frac" >"$TMP/$tag.eval"
}
# recovered TAG ANGLE MIN: every big plane (at least MIN) is one patch,
# within ANGLE degrees.
recovered() {
	e=$TMP/$1.eval
	check_num "$1: big planes" "$(figure big "$e")" ">=" "$3"
	check_num "$1: each big plane one patch" "$(figure one "$e")" == "$(figure big "$e")"
	check_num "$1: no big plane split" "$(figure extra "$e")" == 0
	check_num "$1: normals within $2 degree" "$(figure angle "$e")" "<" "$2"
}

# A room (boxes, ramp, sphere, cylinder) with Kinect-class noise (sigma =
# 0.0012 z^2 along the rays: 1 mm at 1 m, 3 cm at 5 m).  Big enough to be
# seen: 0.5% of the faces at step 1, 1% at step 5 (below that a plane seen
# through this noise from 5 m has too few points for a degree: the best fit
# to the true faces of box2_+x at step 5, 178 of them, is off by 2.6).
# Patches are about 40 (the sphere and the cylinder make several), not tens
# of thousands.
scene rk --size 320x240 --fx 262.5 --noise kinect-gauss:0.0012
view rk 1 0.005 rk-1
recovered rk-1 1 9
check_num "rk-1: patches" "$(report patches "$TMP/rk-1.err")" "<" 100
check_num "rk-1: noise figure" "$(report noise "$TMP/rk-1.err")" ">" 0.0005
scene rk6 --noise kinect-gauss:0.0012
view rk6 5 0.01 rk6-5
recovered rk6-5 1 7
check_num "rk6-5: patches" "$(report patches "$TMP/rk6-5.err")" "<" 60
# Gaussian noise of 3 mm, step 1 and 5.
scene rg --size 320x240 --fx 262.5 --noise gaussian:0.003
view rg 1 0.005 rg-1
recovered rg-1 0.5 9
view rg 5 0.01 rg-5
recovered rg-5 1 5
# Area weighting on the noisy room, and the orthogonal fit of eq. 1.
view rk 1 0.005 rk-area --area-weighted
recovered rk-area 1 9
view rk 1 0.005 rk-tls --tls
recovered rk-tls 1.5 9
# Noiseless: the planes exact (rms at float rounding, normals to 0.001
# degree), at step 1 and 5.
scene r0 --size 320x240 --fx 262.5
view r0 1 0.005 r0-1
recovered r0-1 0.001 9
check_num "r0-1: rms of the planes" "$(figure rms "$TMP/r0-1.eval")" "<" 1e-6
view r0 5 0.01 r0-5
recovered r0-5 0.001 5
check_num "r0-5: rms of the planes" "$(figure rms "$TMP/r0-5.eval")" "<" 1e-6
# -n: the cube's six (above), and a fixed count on the room.
run_case 0 "segplanes -v -n 12 -o $TMP/n12.ply $TMP/rk-1.ply 2>$TMP/n12.err"
check_num "-n 12 on the room: 12 patches" "$(report patches "$TMP/n12.err")" == 12
# Deterministic: the same bytes twice (the provenance names no file here).
run_case 0 "segplanes <$TMP/rk6-5.ply >$TMP/again.ply"
run_case 0 "segplanes <$TMP/rk6-5.ply >$TMP/again2.ply"
check_true "the same bytes twice" cmp -s "$TMP/again.ply" "$TMP/again2.ply"
# The man page example.
run_case 0 "mkscene --size 160x120 --fx 131.25 --noise kinect-gauss:0.0012 -o $TMP/ex && dm2mesh --camera $TMP/ex/view00.camera --pose $TMP/ex/view00.pose $TMP/ex/view00.depth.pfm | segplanes -v -o $TMP/ex.ply 2>$TMP/ex.err"
check_num "man page example: patches" "$(report patches "$TMP/ex.err")" ">" 5
finish
