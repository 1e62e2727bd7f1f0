# segplanes: a hand-made cube (six exact patches), bad input and usage, and
# mkscene rooms with exact ground truth: the automatic criterion recovers
# every true plane big enough to be seen, as one patch, its normal within a
# degree, with Kinect-class (Gaussian and structured) and Gaussian noise, at
# dm2mesh step 1 and 5, with the noise model or sigma estimated; noiseless
# scenes give exact planes; no face of a patch farther than 3 sigma from its
# plane, on the rooms and on real frames.
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
# Free-form faces (patch -1) are no patch: a big plane left free-form is
# not one patch.
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
			if (p + 0 < 0 || P[p] < n) continue
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
# view NAME STEP FRACTION TAG [SEGPLANES-ARGS]: mesh the view at STEP
# with its noise model (STEP "est": at step 1 without it, so that segplanes
# estimates sigma from the data), segment, evaluate into $TMP/TAG.eval (and
# TAG.err: the -v figures).
view() {
	name=$1 step=$2 frac=$3 tag=$4
	shift 4
	d=$TMP/$name
	if [ ! -f "$d-$step.ply" ]; then
		case $step in
		est) run_case 0 "dm2mesh --camera $d/view00.camera --pose $d/view00.pose -o $d-$step.ply $d/view00.depth.pfm" ;;
		*) run_case 0 "dm2mesh --step $step --camera $d/view00.camera --pose $d/view00.pose --noise $d/view00.noise -o $d-$step.ply $d/view00.depth.pfm" ;;
		esac
	fi
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

# deviation SEG: how far the faces of patches in SEG (a segplanes ascii
# output with the vertex property sigma) lie from their patch's plane, in
# units of the noise as segment.h measures it: the mean over a face's
# corners of (n.p + d) / sigma, in absolute value.  Prints "faces N" (faces
# of patches), "max M" (the largest), "over K" (faces farther than 3).
# Each face keeps only its corners' sums (x/sigma ... 1/sigma), since the
# planes come after the faces.
deviation() {
	awk '/^element/ && !h { el = $2; cnt[el] = $3; np[el] = 0; next }
	/^property list/ && !h { col[el, $5] = ++np[el]; next }
	/^property/ && !h { col[el, $3] = ++np[el]; next }
	/^end_header/ && !h { h = 1; vi = fi = pi = 0; cx = col["vertex", "x"]; cy = col["vertex", "y"]
		cz = col["vertex", "z"]; cs = col["vertex", "sigma"]; next }
	!h { next }
	vi < cnt["vertex"] { w = 1 / $cs; X[vi] = $cx * w; Y[vi] = $cy * w; Z[vi] = $cz * w; W[vi++] = w; next }
	fi < cnt["face"] { fi++; k = $1; if ($(k + 2) < 0) next
		a = b = c = w = 0
		for (i = 2; i <= k + 1; i++) { v = $i; a += X[v]; b += Y[v]; c += Z[v]; w += W[v] }
		n++; FA[n] = a / k; FB[n] = b / k; FC[n] = c / k; FW[n] = w / k; FP[n] = $(k + 2); next }
	pi < cnt["plane"] { nx[pi] = $1; ny[pi] = $2; nz[pi] = $3; d[pi++] = $4 }
	END {
		for (f = 1; f <= n; f++) {
			p = FP[f]; e = nx[p] * FA[f] + ny[p] * FB[f] + nz[p] * FC[f] + d[p] * FW[f]
			e = e < 0 ? -e : e; if (e > m) m = e; o += e > 3
		}
		printf "faces %d\nmax %.6f\nover %d\n", n, m, o
	}' "$1"
}
# guarantee TAG MAX SHARE: segplanes' promise on $TMP/TAG.seg.ply: no face
# of a patch farther than --max-dev (3) sigma from its plane.  Where it is
# known not to hold (MAX given), the largest deviation stays below MAX and
# the faces beyond 3 sigma below SHARE of the patches' faces.
guarantee() {
	deviation "$TMP/$1.seg.ply" >"$TMP/$1.dev"
	check_num "$1: faces of patches" "$(figure faces "$TMP/$1.dev")" ">" 0
	if [ -z "${2:-}" ]; then
		check_num "$1: no face of a patch farther than 3 sigma from its plane" \
			"$(figure max "$TMP/$1.dev")" "<=" 3
		return
	fi
	xfail "$1: no face of a patch farther than 3 sigma from its plane (max $(figure max "$TMP/$1.dev"), $(figure over "$TMP/$1.dev") faces beyond)" \
		holds "$(figure max "$TMP/$1.dev")" "<=" 3
	check_num "$1: largest deviation of a patch face, in sigma" "$(figure max "$TMP/$1.dev")" "<" "$2"
	check_num "$1: share of patch faces beyond 3 sigma" \
		"$(awk -v o="$(figure over "$TMP/$1.dev")" -v n="$(figure faces "$TMP/$1.dev")" 'BEGIN { print o / n }')" "<" "$3"
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
# The guarantee holds here (largest 2.99 sigma at planar d60fa92).
guarantee rk-1
# Without the noise model sigma is estimated from the data, and the planes
# are found all the same (largest angle 0.36 degree).
view rk est 0.005 rk-est
recovered rk-est 1 9
check_num "rk-est: sigma estimated" "$(report noise_estimated "$TMP/rk-est.err")" == 1
# The same room with the structured noise of a Kinect as ICL-NUIM simulates
# it: the sampled pixel jittered, Gaussian noise on the disparity, and the
# disparity in 1/8-pixel steps, so that depth comes in plateaus.  The big
# planes are 0.85% of the faces or more here (8 of them; largest angle 0.42
# degree, 0.58 with sigma estimated): the next, the far side of box2 (0.8%,
# 5.5 m away), is one patch 1.3 degrees off (its true faces alone fit within
# 0.4 degree along the rays), and free-form at 640x480 or with mkscene
# --seed 2 (narrower than --min-extent).
scene rq --size 320x240 --fx 262.5 --noise kinect
view rq 1 0.0085 rq-1
recovered rq-1 1 8
check_num "rq-1: patches" "$(report patches "$TMP/rq-1.err")" "<" 60
guarantee rq-1
evaluate "$TMP/rq.lab.ply" "$TMP/rq-1.seg.ply" "$TMP/rq.scene.ply" 0.005 >"$TMP/rq-1-all.eval"
xfail "rq-1: every plane of 0.5% of the faces one patch within 1 degree (largest $(figure angle "$TMP/rq-1-all.eval"))" \
	holds "$(figure angle "$TMP/rq-1-all.eval")" "<" 1
view rq est 0.0085 rq-est
recovered rq-est 1 8
check_num "rq-est: sigma estimated" "$(report noise_estimated "$TMP/rq-est.err")" == 1
scene rk6 --noise kinect-gauss:0.0012
view rk6 5 0.01 rk6-5
recovered rk6-5 1 7
check_num "rk6-5: patches" "$(report patches "$TMP/rk6-5.err")" "<" 60
# Gaussian noise of 3 mm, step 1 and 5.
scene rg --size 320x240 --fx 262.5 --noise gaussian:0.003
view rg 1 0.005 rg-1
recovered rg-1 0.5 9
guarantee rg-1
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
# Real frames, with the Kinect noise model their camera names imply: the
# TUM desk of samples/, and 7-Scenes' first kitchen frame when the shared
# data are here; and the real 7-Scenes frame of samples/ (the guarantee once
# failed on both: at planar d60fa92, TUM 1235 of 436611 patch faces beyond
# 3 sigma, up to 5.82; 7-Scenes 217 of 485512, up to 3.57, before the
# planes were fitted a last time after the boundaries settled).
run_case 0 "dm2mesh -K tum samples/tum/TUM_depth.png | segplanes -a -o $TMP/tum.seg.ply"
guarantee tum
kitchen=
for k in ../shared/data/7scenes_redkitchen /work/shared/data/7scenes_redkitchen; do
	[ -f "$k/frames/frame-000000.depth.png" ] && kitchen=$k && break
done
if [ -n "$kitchen" ]; then
	run_case 0 "dm2mesh -K 7scenes $kitchen/frames/frame-000000.depth.png | segplanes -a -o $TMP/7s.seg.ply"
	guarantee 7s
else
	echo "segplanes.sh: no 7scenes_redkitchen in ../shared/data: its frame skipped" >&2
fi
run_case 0 "dm2mesh -K 7scenes samples/7scenes/frame-000000.depth.png | segplanes -a -o $TMP/7k.seg.ply"
guarantee 7k

# -n: the cube's six (above), and a fixed count on the room.
run_case 0 "segplanes -v -n 12 -o $TMP/n12.ply $TMP/rk-1.ply 2>$TMP/n12.err"
check_num "-n 12 on the room: 12 patches" "$(report patches "$TMP/n12.err")" == 12
# Deterministic: the same bytes twice (the provenance names no file here).
run_case 0 "segplanes <$TMP/rk6-5.ply >$TMP/again.ply"
run_case 0 "segplanes <$TMP/rk6-5.ply >$TMP/again2.ply"
check_true "the same bytes twice" cmp -s "$TMP/again.ply" "$TMP/again2.ply"
# A small room through the pipe, segplanes reading standard input (the
# man page's examples run in man_examples.sh).
run_case 0 "mkscene --size 160x120 --fx 131.25 --noise kinect-gauss:0.0012 -o $TMP/ex && dm2mesh --camera $TMP/ex/view00.camera --pose $TMP/ex/view00.pose $TMP/ex/view00.depth.pfm | segplanes -v -o $TMP/ex.ply 2>$TMP/ex.err"
check_num "pipe: patches" "$(report patches "$TMP/ex.err")" ">" 5
finish
