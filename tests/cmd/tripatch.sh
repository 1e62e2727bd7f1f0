# tripatch: hand-made wireframes (tests/data/tri_*.ply, written by
# tri_gen.py) triangulated with known counts and areas: n + 2h - 2
# triangles per patch, areas summing to the polygon minus its holes, every
# face wound with its plane normal; the fallback from crossing s t to the
# plane; a patch touching itself; open chains; long boundaries; bad input;
# usage; the man page.  One golden file (tests/cmd/expected/tripatch_hole.ply,
# rewritten by make regold).
. tests/lib.sh
D=tests/data

# value KEY: the -v figure KEY of the last run (stderr).
value() { sed -n "s/^tripatch: $1=//p" "$TMP/err"; }

# $areas: per patch of an ascii PLY on stdin, "patch triangles area up",
# "up" when (b - a) x (c - a) . (plane normal) > 0 for all its faces (all
# wound with the normal), "DOWN" if not.  Needs the face property patch
# last and the plane element after the faces.
cat >"$TMP/areas.awk" <<'AWK'
	/^element vertex/ { nv = $3 } /^element face/ { nf = $3 } /^element plane/ { np = $3 }
	/^end_header/ { body = 1; i = 0; next }
	!body { next }
	i < nv { x[i] = $1; y[i] = $2; z[i] = $3; i++; next }
	i < nv + nf { a[i - nv] = $2; b[i - nv] = $3; c[i - nv] = $4; p[i - nv] = $5; i++; next }
	i < nv + nf + np { nx[i - nv - nf] = $1; ny[i - nv - nf] = $2; nz[i - nv - nf] = $3; i++; next }
	END {
		for (f = 0; f < nf; f++) {
			ux = x[b[f]] - x[a[f]]; uy = y[b[f]] - y[a[f]]; uz = z[b[f]] - z[a[f]]
			vx = x[c[f]] - x[a[f]]; vy = y[c[f]] - y[a[f]]; vz = z[c[f]] - z[a[f]]
			cx = uy * vz - uz * vy; cy = uz * vx - ux * vz; cz = ux * vy - uy * vx
			q = p[f]; n[q]++; area[q] += sqrt(cx * cx + cy * cy + cz * cz) / 2
			d = cx * nx[q] + cy * ny[q] + cz * nz[q]
			if (!(q in dot) || d < dot[q]) dot[q] = d
		}
		for (q = 0; q < np; q++) if (q in n) printf "%d %d %.12g %s\n", q, n[q], area[q], (dot[q] > 0 ? "up" : "DOWN")
	}
AWK
areas="awk -f $TMP/areas.awk"

# The 4 x 4 square around a 2 x 2 square (patch 1): 8 + 2 - 2 = 8 and 2
# triangles, areas 12 and 4; the greedy output is the golden file.
run_case 0 "tripatch -a $D/tri_hole.ply" tests/cmd/expected/tripatch_hole.ply
run_case 0 "tripatch -v -a $D/tri_hole.ply | $areas"
check_true "hole: areas" cmp -s "$TMP/out" - <<EOF
0 8 12 up
1 2 4 up
EOF
check_num "hole: triangles" "$(value triangles)" == 10
check_num "hole: polygons" "$(value polygons)" == 2
check_num "hole: holes" "$(value holes)" == 1
check_num "hole: plane frame" "$(value in_plane)" == 2
run_case 0 "tripatch --cdt -v -a $D/tri_hole.ply | $areas"
check_true "hole --cdt: areas" cmp -s "$TMP/out" - <<EOF
0 8 12 up
1 2 4 up
EOF
check_true "hole --cdt: method" test "$(value method)" = cdt

# Two holes, in image coordinates: 12 + 4 - 2 = 14 triangles, area
# 100 - 8; the holes' patches 2 triangles of area 4 each.
for m in "" --cdt; do
	run_case 0 "tripatch $m -v -a $D/tri_two_holes.ply | $areas"
	check_true "two holes $m: areas" cmp -s "$TMP/out" - <<EOF
0 14 92 up
1 2 4 up
2 2 4 up
EOF
	check_num "two holes $m: in s t" "$(value in_st)" == 3
	check_num "two holes $m: holes" "$(value holes)" == 2
done
run_case 0 "tripatch $D/tri_two_holes.ply | meshinfo | grep -E '^(border|non_manifold)_edges|^components|^edges'"
check_true "two holes: one disk" cmp -s "$TMP/out" - <<EOF
edges: 29
border_edges: 4
non_manifold_edges: 0
components: 1
EOF
# --plane ignores s t
run_case 0 "tripatch --plane -v $D/tri_two_holes.ply >/dev/null"
check_num "--plane" "$(value in_plane)" == 3

# The L: 4 triangles, area 3.
run_case 0 "tripatch -a $D/tri_L.ply | $areas"
check_true "L" cmp -s "$TMP/out" - <<EOF
0 4 3 up
EOF

# Crossing image coordinates: s t refused, the plane used.
run_case 0 "tripatch -v -a $D/tri_bowtie_st.ply | $areas"
check_true "bow tie: area" cmp -s "$TMP/out" - <<EOF
0 2 4 up
EOF
check_num "bow tie: fallback" "$(value fallbacks)" == 1
check_num "bow tie: not in s t" "$(value in_st)" == 0

# Patch 0 touches itself at (1,1): two loops, 2 + 2 triangles.
run_case 0 "tripatch -v -a $D/tri_touch.ply | $areas"
check_true "touch: areas" cmp -s "$TMP/out" - <<EOF
0 4 2 up
1 4 2 up
EOF
check_num "touch: polygons" "$(value polygons)" == 4
check_num "touch: repairs" "$(value repairs)" == 0

# An edge that closes nothing: reported, the square still triangulated.
run_case 0 "tripatch -a $D/tri_open.ply | $areas" "" "tripatch: warning: 1 patch edges close no loop"
check_true "open: square" cmp -s "$TMP/out" - <<EOF
0 2 1 up
EOF
run_case 0 "tripatch -q $D/tri_open.ply >/dev/null"
check_true "-q: no warning" test ! -s "$TMP/err"

# A long zig-zag strip, 20000 vertices (awk): 19998 triangles either way.
awk 'BEGIN { m = 10000; n = 2 * m
	print "ply\nformat ascii 1.0\nelement vertex " n "\nproperty float x\nproperty float y\nproperty float z"
	print "element edge " n "\nproperty int vertex1\nproperty int vertex2\nproperty int patch1\nproperty int patch2"
	print "end_header"
	for (i = 0; i < m; i++) print i, (i % 2) * 0.25, 0
	for (i = m - 1; i >= 0; i--) print i + 0.5, 2 + (i % 2) * 0.25, 0
	for (i = 0; i < n; i++) print i, (i + 1) % n, 0, -1 }' >"$TMP/long.ply"
for m in "" --cdt; do
	run_case 0 "tripatch $m -v $TMP/long.ply | meshinfo | grep -E '^(faces|border_edges|non_manifold_edges):'"
	check_true "long $m" cmp -s "$TMP/out" - <<EOF
faces: 19998
border_edges: 20000
non_manifold_edges: 0
EOF
done

# Standard input, -o, determinism.
run_case 0 "tripatch -a <$D/tri_two_holes.ply | sed '/^comment facet/d'"
cp "$TMP/out" "$TMP/stdin.ply"
run_case 0 "tripatch -a -o $TMP/o.ply $D/tri_two_holes.ply && sed '/^comment facet/d' $TMP/o.ply" "$TMP/stdin.ply"
run_case 0 "tripatch $D/tri_two_holes.ply"
cp "$TMP/out" "$TMP/one"
run_case 0 "tripatch $D/tri_two_holes.ply" "$TMP/one"

# Bad input.
run_case 1 "tripatch $D/tri_noedge.ply" "" "tripatch: $D/tri_noedge.ply: no edge element"
run_case 1 "tripatch $D/tri_badpatch.ply" "" "tripatch: $D/tri_badpatch.ply: edge 1: patch 5"
run_case 1 "tripatch </dev/null" "" "tripatch: <stdin>: "
run_case 0 "tripatch -v $D/tri_empty.ply | meshinfo | grep '^faces:'" "" "tripatch: warning: no edges"
check_true "empty: no faces" test "$(cat "$TMP/out")" = "faces: 0"
run_case 1 "tripatch $D/no_such_file.ply" "" "tripatch: $D/no_such_file.ply: "
run_case 1 "tripatch -o $TMP/no/such/dir/x.ply $D/tri_L.ply" "" "tripatch: "

# Usage.
run_case 2 "tripatch -x $D/tri_L.ply" "" "tripatch: -x: unknown option"
run_case 2 "tripatch $D/tri_L.ply $D/tri_L.ply" "" "tripatch: too many operands"
run_case 2 "tripatch -o" "" "tripatch: -o: option requires an argument"
run_case 0 "tripatch --version | grep -q '^tripatch (facet) '"

# The usage (tests/cmd/manpages.sh checks --help against the man page's
# synopsis, tests/cmd/man_examples.sh runs its examples).
run_case 0 "tripatch --help | head -n 1 | grep -q '^usage: tripatch \[-aqv\] \[-o file\] \[--cdt\] \[--plane\] \[input\]$'"

finish
