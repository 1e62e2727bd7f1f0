# projverts: hand-made meshes with hand-computed answers (tests/data/pv_*,
# written by pv_gen.py), bad input and usage, and mkscene's room with its
# exact planes: noisy vertices put back on the true planes, tilted planes
# snapped back to exact right angles, a known depth scale recovered.
. tests/lib.sh

D=tests/data
# report KEY FILE: a projverts -v figure.
report() { sed -n "s/^projverts: $1=//p" "$2"; }
# vertex N FILE: the N-th vertex line (from 0) of an ascii PLY.
vertex() { awk -v n="$1" 'h && i++ == n { print; exit } /^end_header/ { h = 1 }' "$2"; }
# field K LINE: the K-th number of a line.
field() { echo "$2" | awk -v k="$1" '{ print $k }'; }
absdiff() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; print d < 0 ? -d : d }'; }

# Usage: --help is the man page's SYNOPSIS.
run_case 0 "projverts --help | head -n 1 | grep -q '^usage: projverts \[-aqv\] \[-o file\]'"
help=$(projverts --help | sed -n '1,/^[^ u]/p' | sed '$d' | sed 's/^usage: projverts//' | tr -s ' \n' ' ' | sed 's/^ //; s/ $//')
syn=$(sed -n '/^\.Sh SYNOPSIS/,/^\.Sh DESCRIPTION/p' man/man1/projverts.1 | sed '1,2d;$d' |
	sed 's/^\.Op Fl \([^ ]*\) Ar \(.*\)$/[-\1 \2]/; s/^\.Op Fl \(.*\)$/[-\1]/; s/^\.Op Ar \(.*\)$/[\1]/' |
	tr '\n' ' ' | sed 's/ $//')
check_true "--help equals the SYNOPSIS ($help | $syn)" test "$help" = "$syn"
run_case 2 "projverts --orthogonal 0 $D/pv_tent.ply" "" "projverts: --orthogonal: "
run_case 2 "projverts --orthogonal 41 $D/pv_tent.ply" "" "projverts: --orthogonal: "
run_case 2 "projverts --max-move -1 $D/pv_tent.ply" "" "projverts: --max-move: "
run_case 2 "projverts --max-move 1,5 $D/pv_tent.ply" "" "projverts: --max-move: "
run_case 2 "projverts --bogus $D/pv_tent.ply" "" "projverts: "
run_case 2 "projverts $D/pv_tent.ply $D/pv_tent.ply" "" "projverts: too many operands"
run_case 0 "projverts --version | grep -q '^projverts (facet) '"

# The tent: two roof planes meeting along the ridge x = 0, z = 2.  Ridge
# vertices go onto the ridge (0, y, 2); the others onto their plane; s t of
# the ridge vertex (0, -0.5, 2), at camera-frame (0, -0.5, 3): u = 49.5,
# v = 50 * -0.5 / 3 + 39.5 = 31.1667, s = 0.5, t = 1 - 31.6667 / 80.
run_case 0 "projverts -a -v -o $TMP/tent.ply $D/pv_tent.ply 2> $TMP/tent.err"
v2=$(vertex 2 $TMP/tent.ply)
check_num "tent: ridge x" "$(absdiff "$(field 1 "$v2")" 0)" "<" 1e-15
check_num "tent: ridge y" "$(absdiff "$(field 2 "$v2")" -0.5)" "<" 1e-15
check_num "tent: ridge z" "$(absdiff "$(field 3 "$v2")" 2)" "<" 1e-15
check_num "tent: s of the ridge vertex" "$(absdiff "$(field 4 "$v2")" 0.5)" "<" 1e-7
check_num "tent: t of the ridge vertex" "$(absdiff "$(field 5 "$v2")" "$(awk 'BEGIN { printf "%.17g", 1 - (50 * -0.5 / 3 + 40) / 80 }')")" "<" 1e-7
check_num "tent: red kept" "$(field 6 "$(vertex 3 $TMP/tent.ply)")" "==" 30
# Vertex 0 (-1, -0.5, 1.52) onto the plane z = 2 + 0.5 x: r = -(n.p + d),
# foot = p + r n, n = (0.5, 0, -1) / sqrt(1.25), d = 2 / sqrt(1.25).
v0=$(vertex 0 $TMP/tent.ply)
want=$(awk 'BEGIN { s = sqrt(1.25); nx = 0.5 / s; nz = -1 / s; r = -(nx * -1 + nz * 1.52 + 2 / s)
	printf "%.17g %.17g\n", -1 + r * nx, 1.52 + r * nz }')
check_num "tent: foot x" "$(absdiff "$(field 1 "$v0")" "$(field 1 "$want")")" "<" 1e-15
check_num "tent: foot z" "$(absdiff "$(field 3 "$v0")" "$(field 2 "$want")")" "<" 1e-15
check_num "tent: vertices on one plane" "$(report vertices_k1 $TMP/tent.err)" "==" 4
check_num "tent: ridge vertices moved" "$(report moved_k2 $TMP/tent.err)" "==" 2
check_num "tent: none refused" "$(report rejected $TMP/tent.err)" "==" 0
check_num "tent: on the planes after" "$(report max_after $TMP/tent.err)" "<" 1e-15
check_num "tent: off them before" "$(report rms_before $TMP/tent.err)" ">" 0.01
check_num "tent: texture recomputed" "$(report texcoords $TMP/tent.err)" "==" 1
check_true "tent: faces keep their patch" grep -q '^3 2 4 3 1$' $TMP/tent.ply
check_true "tent: planes kept with count and rms" grep -q '^0.4472135954999579 0 -0.8944271909999159 1.7888543819998317 2 0.001$' $TMP/tent.ply
check_true "tent: TextureFile kept" grep -q '^comment TextureFile .*pv_tent.png$' $TMP/tent.ply
check_true "tent: provenance" grep -q '^comment facet projverts ' $TMP/tent.ply
# The same bytes every time, to a file or to standard output.
run_case 0 "projverts -o $TMP/tent1.ply $D/pv_tent.ply && cp $TMP/tent1.ply $TMP/tent2.ply && projverts -o $TMP/tent1.ply $D/pv_tent.ply"
run_case 0 "cmp $TMP/tent1.ply $TMP/tent2.ply"
run_case 0 "projverts < $D/pv_tent.ply > $TMP/tent3.ply && projverts < $D/pv_tent.ply | cmp - $TMP/tent3.ply"
# Run twice: the second run moves nothing further.
run_case 0 "projverts -v -o $TMP/again.ply $TMP/tent1.ply 2> $TMP/again.err"
check_num "tent: a second run moves at most rounding" "$(report max_move $TMP/again.err)" "<" 1e-15

# Without a camera: s t are left as they were, with a warning.
run_case 0 "projverts -a -o $TMP/nocam.ply $D/pv_nocam.ply" "" "projverts: warning: $D/pv_nocam.ply: no camera comment"
check_true "nocam: s t kept" test "$(field 4 "$(vertex 2 $TMP/nocam.ply)") $(field 5 "$(vertex 2 $TMP/nocam.ply)")" = "0.25 0.75"
check_num "nocam: still projected" "$(absdiff "$(field 3 "$(vertex 2 $TMP/nocam.ply)")" 2)" "<" 1e-15
run_case 0 "projverts -q -a -o $TMP/nocam.ply $D/pv_nocam.ply" "" ""
check_true "-q: no warning" test ! -s "$TMP/err"
# A camera but no s t: float s t are added.
run_case 0 "projverts -a -o $TMP/nost.ply $D/pv_nost.ply"
check_true "nost: s t added" grep -q '^property float s$' $TMP/nost.ply
check_num "nost: s of the ridge vertex" "$(absdiff "$(field 5 "$(vertex 2 $TMP/nost.ply)")" 0.5)" "<" 1e-7

# Bad input.
run_case 1 "projverts $D/pv_nopatch.ply" "" "projverts: $D/pv_nopatch.ply: no face property patch"
run_case 1 "projverts $D/pv_noplane.ply" "" "projverts: $D/pv_noplane.ply: no plane element"
: > "$TMP/nothing"
run_case 1 "projverts < $TMP/nothing" "" "projverts: <stdin>"
run_case 1 "printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n' | projverts" "" "projverts: "
run_case 0 "projverts -a -v -o $TMP/empty.ply $D/pv_empty.ply 2> $TMP/empty.err"
check_true "empty: written back empty" grep -q '^element vertex 0$' $TMP/empty.ply
check_num "empty: no vertices" "$(report vertices $TMP/empty.err)" "==" 0
# A label beyond the planes.
run_case 1 "sed 's/^3 3 4 5 1$/3 3 4 5 7/' $D/pv_tent.ply | projverts" "" "projverts: <stdin>: "

# Nearly parallel planes (5 degrees) meeting 0.229 from their shared edge:
# accepted under the default bound (the mean edge, about 1), refused under
# 0.1 (vertices kept exactly), and with --fallback moved onto their mean plane.
run_case 0 "projverts -a -v -o $TMP/par.ply $D/pv_parallel.ply 2> $TMP/par.err"
check_num "parallel: default bound accepts" "$(report moved_k2 $TMP/par.err)" "==" 2
check_num "parallel: the move is the distance to the line" "$(absdiff "$(report max_move $TMP/par.err)" "$(awk 'BEGIN { a = 5 * atan2(1, 1) / 45; x = 0.02 / sin(a); printf "%.17g", sqrt(x * x + 0.0001) }')")" "<" 1e-9
run_case 0 "projverts -a -v --max-move 0.1 -o $TMP/par.ply $D/pv_parallel.ply 2> $TMP/par.err"
check_num "parallel: refused" "$(report rejected $TMP/par.err)" "==" 2
check_true "parallel: vertex kept" test "$(vertex 2 $TMP/par.ply)" = "0 0 0.01"
run_case 0 "projverts -a -v --max-move 0.1 --fallback -o $TMP/par.ply $D/pv_parallel.ply 2> $TMP/par.err"
check_num "parallel: fallback" "$(report fallback $TMP/par.err)" "==" 2
check_num "parallel: fallback within the bound" "$(report max_move $TMP/par.err)" "<=" 0.1
# On the mean plane: the signed distances to the two planes cancel.
check_num "parallel: fallback onto the mean plane" "$(vertex 2 $TMP/par.ply | awk '{ a = 5 * atan2(1, 1) / 45
	s = $3 + sin(a) * $1 + cos(a) * $3 - 0.02; printf "%.17g", s < 0 ? -s : s }')" "<" 1e-15

# mkscene's room (scene.ply: exact planes and labels).
S=$TMP/room
run_case 0 "mkscene --size 64x48 --fx 52.5 -o $S && meshconv -a -o $S/scene_a.ply $S/scene.ply"
# Noise of up to 5 mm on every vertex of a labelled face.
awk 'BEGIN { srand(7) }
	NR == FNR { if (/^element vertex/) nv = $3; if (/^element face/) nf = $3
		if (h && ++r > nv && r <= nv + nf && $NF >= 0) for (k = 2; k <= $1 + 1; k++) on[$k] = 1
		if (/^end_header/) h = 1; next }
	g && i < nv { if (on[i]) { $1 += 0.01 * (rand() - 0.5); $2 += 0.01 * (rand() - 0.5); $3 += 0.01 * (rand() - 0.5) }
		i++; printf "%.17g %.17g %.17g\n", $1, $2, $3; next }
	{ print } /^end_header/ { g = 1 }' $S/scene_a.ply $S/scene_a.ply > $TMP/noisy.ply
run_case 0 "projverts -v --max-move 0.1 -o $TMP/back.ply $TMP/noisy.ply 2> $TMP/back.err"
check_num "room: noisy before" "$(report rms_before $TMP/back.err)" ">" 0.001
check_num "room: on the true planes after" "$(report max_after $TMP/back.err)" "<" 1e-12
check_num "room: corners of three planes" "$(report vertices_k3+ $TMP/back.err)" ">=" 20
check_num "room: none refused" "$(report rejected $TMP/back.err)" "==" 0
# The corners (k >= 3) are back exactly: distance to scene.ply at most noise
# along lines and planes, and the curved surfaces untouched.
run_case 0 "meshdist $TMP/back.ply $S/scene.ply > $TMP/back.dist && meshdist $TMP/noisy.ply $S/scene.ply > $TMP/noisy.dist"
check_num "room: closer to the true surface than the noisy input" \
	"$(awk '$1 == "mean" { print $2 }' $TMP/back.dist)" "<" "$(awk '$1 == "mean" { print $2 / 2 }' $TMP/noisy.dist)"

# --orthogonal: every plane tilted by exactly 2 degrees about its foot
# point; snapped at 5 degrees, pairs that were orthogonal or parallel are so
# again to 1e-9, and the vertices lie on the snapped planes.
awk 'BEGIN { srand(11); t = sin(2 * atan2(1, 1) / 45) / cos(2 * atan2(1, 1) / 45) }
	/^element plane/ { np = $3 } /^element/ { el = $2 }
	h && el_row() == "plane" {
		n1 = $1; n2 = $2; n3 = $3; d = $4
		r1 = rand() - 0.5; r2 = rand() - 0.5; r3 = rand() - 0.5; rn = r1 * n1 + r2 * n2 + r3 * n3
		r1 -= rn * n1; r2 -= rn * n2; r3 -= rn * n3; l = sqrt(r1 * r1 + r2 * r2 + r3 * r3)
		m1 = n1 + t * r1 / l; m2 = n2 + t * r2 / l; m3 = n3 + t * r3 / l; L = sqrt(m1 * m1 + m2 * m2 + m3 * m3)
		m1 /= L; m2 /= L; m3 /= L
		$1 = sprintf("%.17g", m1); $2 = sprintf("%.17g", m2); $3 = sprintf("%.17g", m3)
		$4 = sprintf("%.17g", d * (m1 * n1 + m2 * n2 + m3 * n3)) }
	{ print } /^end_header/ { h = 1 }
	function el_row() { return ++row > nv + nf ? "plane" : "" }
	/^element vertex/ { nv = $3 } /^element face/ { nf = $3 }' $S/scene_a.ply > $TMP/tilted.ply
run_case 0 "projverts -a -v --orthogonal 5 --max-move 1 -o $TMP/ortho.ply $TMP/tilted.ply 2> $TMP/ortho.err"
# planes FILE: the plane rows "nx ny nz" of an ascii PLY.
planes() { awk '/^element vertex/ { nv = $3 } /^element face/ { nf = $3 }
	h && ++r > nv + nf { print $1, $2, $3 } /^end_header/ { h = 1 }' "$1"; }
planes $S/scene_a.ply > $TMP/truth.n
planes $TMP/tilted.ply > $TMP/tilted.n
planes $TMP/ortho.ply > $TMP/ortho.n
# worst KIND TRUTH GOT: the worst |cos| over truly orthogonal pairs, or |sin|
# over truly parallel ones, and the number of such pairs.
worst() { awk -v kind="$1" 'NR == FNR { t[NR] = $0; n = NR; next } { g[FNR] = $0 }
	END { w = 0; c = 0
		for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) {
			split(t[i], a); split(t[j], b); split(g[i], p); split(g[j], q)
			ct = a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
			cg = p[1] * q[1] + p[2] * q[2] + p[3] * q[3]
			if (kind == "orth" && (ct < 0 ? -ct : ct) < 1e-9) { c++; v = cg < 0 ? -cg : cg; if (v > w) w = v }
			if (kind == "par" && (ct < 0 ? -ct : ct) > 1 - 1e-9) { c++
				x = p[2] * q[3] - p[3] * q[2]; y = p[3] * q[1] - p[1] * q[3]; z = p[1] * q[2] - p[2] * q[1]
				v = sqrt(x * x + y * y + z * z); if (v > w) w = v } }
		printf "%.17g %d\n", w, c }' "$2" "$3"; }
check_num "tilted: orthogonal pairs off by about 2 degrees" "$(worst orth $TMP/truth.n $TMP/tilted.n | cut -d' ' -f1)" ">" 0.03
check_num "snapped: orthogonal pairs exact" "$(worst orth $TMP/truth.n $TMP/ortho.n | cut -d' ' -f1)" "<" 1e-9
check_num "snapped: many orthogonal pairs" "$(worst orth $TMP/truth.n $TMP/ortho.n | cut -d' ' -f2)" ">" 100
check_num "snapped: parallel pairs exact" "$(worst par $TMP/truth.n $TMP/ortho.n | cut -d' ' -f1)" "<" 1e-9
check_num "snapped: vertices re-projected" "$(report max_after $TMP/ortho.err)" "<" 1e-12
check_num "snapped: two frames (the room, the turned box)" "$(report frames $TMP/ortho.err)" "==" 2
check_num "snapped: six horizontal planes" "$(report snapped_horizontal $TMP/ortho.err)" "==" 6
check_num "snapped: the ramp made square to the walls" "$(report snapped_oblique $TMP/ortho.err)" "==" 1
check_num "snapped: up is z within 2 degrees" "$(report up $TMP/ortho.err | cut -d, -f3)" ">" 0.99939

# --depth-scale-fix: the room in view 0's camera frame with depth (z)
# divided by 1.6 and the focal length with it; the fix finds 1.6 (within 1%;
# exact data gives it to 1e-9).
awk 'NR == FNR { for (k = 1; k <= NF; k++) P[FNR, k] = $k; next }
	/^element vertex/ { nv = $3 } /^element face/ { nf = $3 }
	/^comment facet/ { print "comment camera pinhole 64 48 32.8125 32.8125 31.5 23.5"; print; next }
	h { r++
		if (r <= nv) { x = $1 - P[1, 4]; y = $2 - P[2, 4]; z = $3 - P[3, 4]
			cx = P[1, 1] * x + P[2, 1] * y + P[3, 1] * z; cy = P[1, 2] * x + P[2, 2] * y + P[3, 2] * z
			cz = P[1, 3] * x + P[2, 3] * y + P[3, 3] * z
			printf "%.17g %.17g %.17g\n", cx, cy, cz / 1.6; next }
		if (r > nv + nf) { n1 = $1; n2 = $2; n3 = $3
			dc = n1 * P[1, 4] + n2 * P[2, 4] + n3 * P[3, 4] + $4
			a = P[1, 1] * n1 + P[2, 1] * n2 + P[3, 1] * n3; b = P[1, 2] * n1 + P[2, 2] * n2 + P[3, 2] * n3
			c = (P[1, 3] * n1 + P[2, 3] * n2 + P[3, 3] * n3) * 1.6; L = sqrt(a * a + b * b + c * c)
			$1 = sprintf("%.17g", a / L); $2 = sprintf("%.17g", b / L); $3 = sprintf("%.17g", c / L)
			$4 = sprintf("%.17g", dc / L) } }
	{ print } /^end_header/ { h = 1 }' $S/view00.pose $S/scene_a.ply > $TMP/flat.ply
run_case 0 "projverts -v --depth-scale-fix -a -o $TMP/fixed.ply $TMP/flat.ply 2> $TMP/fixed.err"
check_num "depth scale: 1.6 within 1%" "$(absdiff "$(report depth_scale $TMP/fixed.err)" 1.6)" "<" 0.016
check_num "depth scale: 1.6 within 1e-9 on exact data" "$(absdiff "$(report depth_scale $TMP/fixed.err)" 1.6)" "<" 1.6e-9
check_num "depth scale: the focal length scaled back" "$(absdiff "$(awk '/^comment camera/ { print $6; exit }' $TMP/fixed.ply)" 52.5)" "<" 1e-6
check_num "depth scale: vertices on the scaled planes" "$(report max_after $TMP/fixed.err)" "<" 1e-12
# Without adjacent planes that constrain it (two planes whose normals have
# no x or y in common: a_ij = 0, orthogonal at no scale), the scale stays 1
# with a warning.
run_case 0 "projverts --depth-scale-fix -o $TMP/one.ply $D/pv_parallel.ply" "" "projverts: warning: $D/pv_parallel.ply: no pair of adjacent planes constrains the depth scale"

finish
