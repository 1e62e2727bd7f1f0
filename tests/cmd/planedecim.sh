# planedecim: the planar model of mkscene's rooms (320x240, step 1) with
# Gaussian, structured Kinect and Gaussian Kinect-class noise, against the
# exact scene: far fewer faces, closer to the true surface than the dense
# mesh and than qemdecim at the same face count (accuracy: points on the
# model to the scene; completeness: the true visible surface to the model),
# manifold, every vertex of a patch face on its plane within its
# uncertainty, the same bytes twice; a mesh without camera or sigma; bad
# input and usage.  The figures asserted were measured at planar d60fa92
# (in the comments) and are asserted with a margin.
. tests/lib.sh

# report KEY FILE: a planedecim -v figure; info KEY MESH: a meshinfo line;
# figure KEY FILE: a meshdist line, in mm.
report() { sed -n "s/^planedecim: $1=//p" "$2"; }
info() { meshinfo "$2" | sed -n "s/^$1: //p"; }
figure() { awk -v k="$1" '$1 == k { printf "%.6f", $2 * 1000 }' "$2"; }

# room TAG MKSCENE-ARGS: in $TMP/TAG.*: the scene, its dense mesh with its
# noise model, segmented (seg.ply), modelled (model.ply, -v figures in
# model.err), qemdecim of the dense mesh to the model's face count
# (qem.ply), the true visible surface (truth.ply: dm2mesh of the noiseless
# depth); for each of dense, model and qem, .acc (meshdist -p from 200000
# points on it to the scene) and .compl (from the truth's vertices to it).
room() {
	t=$TMP/$1
	shift
	run_case 0 "mkscene --size 320x240 --fx 262.5 $* -o $t"
	cam="--camera $t/view00.camera --pose $t/view00.pose"
	run_case 0 "dm2mesh $cam --noise $t/view00.noise -o $t.dense.ply $t/view00.depth.pfm"
	run_case 0 "segplanes -o $t.seg.ply $t.dense.ply"
	run_case 0 "planedecim -v -o $t.model.ply $t.seg.ply 2>$t.model.err"
	run_case 0 "qemdecim -n $(report faces "$t.model.err") -o $t.qem.ply $t.dense.ply"
	run_case 0 "dm2mesh $cam -o $t.truth.ply $t/view00.truth.pfm"
	for m in dense model qem; do
		meshdist -p -s 200000 "$t.$m.ply" "$t/scene.ply" >"$t.$m.acc"
		meshdist -p "$t.truth.ply" "$t.$m.ply" >"$t.$m.compl"
	done
}

# off_plane MODEL: the largest distance of a vertex of a patch face from
# that patch's plane, over the vertex's uncertainty sqrt(sigma^2 +
# spacing^2), its spacing the span of one pixel at its distance from the
# camera (MODEL an ascii planedecim output with camera, pose and sigma).
# planedecim tears a vertex still farther than that (planemodel.h).
off_plane() {
	awk '/^comment camera pinhole/ && !h { fx = $6; fy = $7 }
	/^comment pose/ && !h { ox = $6; oy = $10; oz = $14 }
	/^element/ && !h { el = $2; cnt[el] = $3; np[el] = 0; next }
	/^property list/ && !h { col[el, $5] = ++np[el]; next }
	/^property/ && !h { col[el, $3] = ++np[el]; next }
	/^end_header/ && !h { h = 1; vi = fi = pi = nf = 0; cs = col["vertex", "sigma"]; next }
	!h { next }
	vi < cnt["vertex"] { x[vi] = $1; y[vi] = $2; z[vi] = $3; s[vi++] = $cs; next }
	fi < cnt["face"] { fi++; k = $1; if ($(k + 2) < 0) next
		for (i = 2; i <= k + 1; i++) { fv[nf] = $i; fp[nf++] = $(k + 2) }; next }
	pi < cnt["plane"] { nx[pi] = $1; ny[pi] = $2; nz[pi] = $3; d[pi++] = $4 }
	END {
		for (i = 0; i < nf; i++) {
			v = fv[i]; p = fp[i]
			r = nx[p] * x[v] + ny[p] * y[v] + nz[p] * z[v] + d[p]
			sp = sqrt((x[v] - ox) ^ 2 + (y[v] - oy) ^ 2 + (z[v] - oz) ^ 2) / sqrt(fx * fy)
			q = (r < 0 ? -r : r) / sqrt(s[v] ^ 2 + sp ^ 2)
			if (q > m) m = q
		}
		printf "%.6f\n", m
	}' "$1"
}

# border_length MESH: the total length of MESH's border edges (edges of one
# face), in mm (MESH ascii).
border_length() {
	awk 'NR == 1, /^end_header/ {
		if ($1 == "element" && $2 == "vertex") nv = $3
		if ($1 == "element" && $2 == "face") nf = $3
		next
	}
	++i <= nv { x[i - 1] = $1; y[i - 1] = $2; z[i - 1] = $3; next }
	i <= nv + nf {
		for (k = 2; k <= $1 + 1; k++) {
			a = $k; b = (k == $1 + 1) ? $2 : $(k + 1)
			e = a < b ? a " " b : b " " a
			n[e]++
		}
	}
	END {
		for (e in n) if (n[e] == 1) {
			split(e, v, " ")
			s += sqrt((x[v[1]] - x[v[2]]) ^ 2 + (y[v[1]] - y[v[2]]) ^ 2 + (z[v[1]] - z[v[2]]) ^ 2)
		}
		printf "%.1f\n", s * 1000
	}' "$1"
}

# model TAG REDUCTION ACC: the checks of a room's model: at least
# REDUCTION times fewer faces than the dense mesh; mean distance to the
# true surface below ACC mm, and below the dense mesh's and qemdecim's,
# p95 too; the true surface closer to it than to the dense mesh and to
# qemdecim's (mean), and than to the dense mesh (p95); manifold, no
# degenerate or duplicate face; every vertex of a patch face within its
# max_move (4) uncertainties of its plane: on it, or at its sample where
# the move along its ray onto the plane was beyond that bound (measured
# 1.6, 3.7 and 3.0 uncertainties on rg, rq and rk; on the plane within 1
# before moves were bounded).
model() {
	t=$TMP/$1
	check_num "$1: reduction" "$(report reduction "$t.model.err")" ">=" "$2"
	check_num "$1: model's faces = qemdecim's" "$(info faces "$t.qem.ply")" == "$(report faces "$t.model.err")"
	check_num "$1: model to the truth, mean (mm)" "$(figure mean "$t.model.acc")" "<" "$3"
	for ref in dense qem; do
		check_num "$1: model to the truth, mean, below $ref's" \
			"$(figure mean "$t.model.acc")" "<" "$(figure mean "$t.$ref.acc")"
		check_num "$1: model to the truth, p95, below $ref's" \
			"$(figure p95 "$t.model.acc")" "<" "$(figure p95 "$t.$ref.acc")"
		check_num "$1: truth to the model, mean, below $ref's" \
			"$(figure mean "$t.model.compl")" "<" "$(figure mean "$t.$ref.compl")"
	done
	check_num "$1: truth to the model, p95, below the dense mesh's" \
		"$(figure p95 "$t.model.compl")" "<" "$(figure p95 "$t.dense.compl")"
	meshinfo "$t.model.ply" >"$t.info"
	for k in non_manifold_edges degenerate_faces duplicate_faces; do
		check_num "$1: $k" "$(sed -n "s/^$k: //p" "$t.info")" == 0
	done
	meshconv -a -o "$t.model.a.ply" "$t.model.ply"
	check_num "$1: patch vertices off their plane, in uncertainties" "$(off_plane "$t.model.a.ply")" "<=" 4.001
}

# Gaussian noise of 3 mm.  Measured: 416 faces (363x); to the truth mean /
# p95 0.25 / 1.06 mm, dense 1.14 / 3.20, qemdecim 1.15 / 5.23; truth to it
# 0.42 / 2.02, dense 1.43 / 3.64, qemdecim 6.29 / 43.0; 0.83 uncertainty.
room rg --noise gaussian:0.003
model rg 250 0.35
# Structured Kinect noise (jitter, disparity noise, 1/8-pixel steps).
# Measured: 746 faces (202x); 2.36 / 10.2 mm, dense 15.8 / 49.9, qemdecim
# 8.86 / 29.9; truth to it 1.64 / 8.60, dense 4.50 / 11.7, qemdecim 17.8 /
# 81.1; 0.99 uncertainty; 120 vertices torn.
room rq --noise kinect
model rq 150 3.3
# The outline of a plane seen obliquely follows its pixels' uncertainty
# stretched over the plane, not the noise: the far edges of the boxes'
# tops had teeth of 0.1-0.2 m (the border 1.49 times as long as the true
# visible surface's, whose pixel steps make it longer than the scene's own;
# 1.38 since the border chains' tolerance grows with the obliquity).
meshconv -a -o "$TMP/rq.truth.a.ply" "$TMP/rq.truth.ply"
check_num "rq: border length over the truth's" \
	"$(awk -v a="$(border_length "$TMP/rq.model.a.ply")" -v b="$(border_length "$TMP/rq.truth.a.ply")" 'BEGIN { print a / b }')" "<" 1.45
# The side of a box seen edge-on, 0.4 m before the wall: its plane met the
# wall's on a crease line across the gap between them (0.199 m from the
# true surface; 0.131 m since a crease must not hide a vertex's sample and
# such a vertex is split, an occlusion border for each patch).
check_num "rq: model to the truth, max (sampled), mm" "$(figure max "$TMP/rq.model.acc")" "<" 160
check_num "-v split: vertices at the boxes' occlusions" "$(report split "$TMP/rq.model.err")" ">" 0
# Gaussian Kinect-class noise, sigma = 0.0012 z^2.  Measured: 473 faces
# (319x); 2.37 / 10.7 mm, dense 12.7 / 40.8, qemdecim 8.57 / 28.9; truth to
# it 1.41 / 7.90, dense 3.92 / 10.6, qemdecim 26.3 / 126; 0.985.
room rk --noise kinect-gauss:0.0012
model rk 250 3.3

# -v: every figure the man page lists, and the counts consistent.
for k in vertices_in faces_in vertices faces reduction planes sigma_estimated facets \
	small_faces speck_faces off_plane_faces holes_filled projected creased split uncreased collapses corners refused_topology \
	refused_flip refused_error max_error free_faces_in free_faces border_free_faces outline_vertices \
	outline_tolerance planar_triangles rounds dense_patches pinned mended tightened \
	unclean_patches reprojected moved_line moved_corner \
	stayed moves_undone torn no_pixel read_s model_s total_s cpu_s; do
	check_true "-v $k" grep -q "^planedecim: $k=[0-9]" "$TMP/rq.model.err"
done
check_num "-v faces = planar + free-form" "$(report faces "$TMP/rq.model.err")" == \
	"$(($(report planar_triangles "$TMP/rq.model.err") + $(report free_faces "$TMP/rq.model.err")))"
# border_free_faces: the model's free-form faces (patch -1, its last face
# property) with a corner on an edge of one face, counted here from the
# model itself.
check_num "-v border_free_faces: counted from the model" "$(report border_free_faces "$TMP/rq.model.err")" == \
	"$(awk 'NR == 1, /^end_header/ {
		if ($1 == "element" && $2 == "vertex") nv = $3
		if ($1 == "element" && $2 == "face") nf = $3
		next
	}
	++i <= nv { next }
	i <= nv + nf {
		f = i - nv - 1; c[f] = $1; p[f] = $NF
		for (k = 2; k <= $1 + 1; k++) {
			v[f, k] = $k; a = $k; b = (k == $1 + 1) ? $2 : $(k + 1)
			n[a < b ? a " " b : b " " a]++
		}
	}
	END {
		for (e in n) if (n[e] == 1) { split(e, ab, " "); on[ab[1]] = on[ab[2]] = 1 }
		for (f = 0; f < nf; f++) {
			if (p[f] >= 0) continue
			hit = 0
			for (k = 2; k <= c[f] + 1; k++) hit = hit || (v[f, k] in on)
			m += hit
		}
		print m + 0
	}' "$TMP/rq.model.a.ply")"
check_num "-v border_free_faces: some (the view's borders)" "$(report border_free_faces "$TMP/rq.model.err")" ">" 0
check_num "-v faces_in = the dense mesh's" "$(report faces_in "$TMP/rq.model.err")" == "$(info faces "$TMP/rq.dense.ply")"
check_num "-v sigma from the mesh" "$(report sigma_estimated "$TMP/rq.model.err")" == 0
check_num "-v free-form decimation within -e (1.5 sigma, the default)" "$(report max_error "$TMP/rq.model.err")" "<=" 1.5
check_num "-v torn (the occlusions of the boxes)" "$(report torn "$TMP/rq.model.err")" ">" 0
check_num "-v creased: vertices put on crease lines (the Kinect room's floor and walls)" "$(report creased "$TMP/rq.model.err")" ">" 0
check_num "-v uncreased <= creased" "$(report uncreased "$TMP/rq.model.err")" "<=" "$(report creased "$TMP/rq.model.err")"
check_num "-v projected >= creased" "$(report projected "$TMP/rq.model.err")" ">=" "$(report creased "$TMP/rq.model.err")"
# The output: patch labels and the planes as they came, the provenance.
check_true "model keeps the plane element" sh -c "meshinfo $TMP/rq.model.ply | grep -q '^element: plane $(report planes "$TMP/rq.model.err")\$'"
check_true "model's faces carry patch" sh -c "meshinfo $TMP/rq.model.ply | grep -q '^property: face int patch\$'"
check_true "provenance" sh -c "meshinfo $TMP/rq.model.ply | grep -q '^provenance: planedecim -v -o '"

# Deterministic: the same bytes twice.
run_case 0 "planedecim <$TMP/rq.seg.ply >$TMP/again1.ply"
run_case 0 "planedecim <$TMP/rq.seg.ply >$TMP/again2.ply"
check_true "the same bytes twice" cmp -s "$TMP/again1.ply" "$TMP/again2.ply"

# A mesh without camera, pose, noise comment or sigma (a fused scan,
# another tool's mesh): the structured-noise room's dense mesh stripped of
# them, through segplanes and planedecim.  Measured: 4598 faces, sigma
# estimated, manifold, 11.3 mm from the truth (dense 15.8).
meshconv -a "$TMP/rq.dense.ply" | awk '
	/^comment/ && !h { next }
	/^element/ && !h { el = $2; n = 0; if (el == "vertex") nv = $3 }
	/^property/ && !h { n++; if (el == "vertex" && $NF == "sigma") { drop = n; next } }
	/^end_header/ && !h { h = 1; print; next }
	!h || !drop || nv-- <= 0 { print; next }
	{ $drop = ""; $0 = $0; $1 = $1; print }' >"$TMP/bare.ply"
check_true "bare mesh: no comment, no sigma" sh -c "! grep -qE '^comment|sigma' $TMP/bare.ply"
run_case 0 "segplanes $TMP/bare.ply | planedecim -v -o $TMP/bare.model.ply 2>$TMP/bare.err"
check_num "bare: sigma estimated" "$(report sigma_estimated "$TMP/bare.err")" == 1
check_num "bare: reduction" "$(report reduction "$TMP/bare.err")" ">=" 20
meshinfo "$TMP/bare.model.ply" >"$TMP/bare.info"
for k in non_manifold_edges degenerate_faces duplicate_faces; do
	check_num "bare: $k" "$(sed -n "s/^$k: //p" "$TMP/bare.info")" == 0
done
meshdist -s 200000 "$TMP/bare.model.ply" "$TMP/rq/scene.ply" >"$TMP/bare.acc"
check_num "bare: model to the truth, mean, below the dense mesh's" \
	"$(figure mean "$TMP/bare.acc")" "<" "$(figure mean "$TMP/rq.dense.acc")"

# Bad input: no patch (the dense mesh), a patch that is no plane, a plane
# that is no plane; unreadable; bad usage.
run_case 1 "planedecim $TMP/rq.dense.ply" "" "planedecim: $TMP/rq.dense.ply: no face property patch: segment it first (segplanes)"
run_case 1 "planedecim <$TMP/rq.dense.ply" "" "planedecim: <stdin>: no face property patch"
head='ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nproperty int patch\nelement plane 1\nproperty double nx\nproperty double ny\nproperty double nz\nproperty double d\nend_header\n0 0 0\n1 0 0\n0 1 0\n'
printf "${head}3 0 1 2 5\n0 0 1 0\n" >"$TMP/badpatch.ply"
printf "${head}3 0 1 2 0\n0 0 2 0\n" >"$TMP/badplane.ply"
printf "${head}3 0 1 2 0\n0 0 1 0\n" >"$TMP/one.ply"
run_case 1 "planedecim $TMP/badpatch.ply" "" "planedecim: $TMP/badpatch.ply: face 0: patch 5 is not -1 or a plane (1 planes)"
run_case 1 "planedecim $TMP/badplane.ply" "" "planedecim: $TMP/badplane.ply: element plane 0: "
run_case 1 "planedecim $TMP/missing.ply" "" "planedecim: $TMP/missing.ply: "
run_case 0 "planedecim -a $TMP/one.ply | grep -q '^element face 1\$'"
run_case 2 "planedecim -e x $TMP/one.ply" "" 'planedecim: -e: "x" is not a number'
run_case 2 "planedecim --min-plane -1 $TMP/one.ply" "" "planedecim: --min-plane: "
run_case 2 "planedecim --outline $TMP/one.ply" "" "planedecim: "
# A closed thin box without a camera (tests/data/pancake_gen.py): its top
# one patch, its sides and bottom 30 faces, fewer than --min-free.  They
# joined the top as a speck, the whole box became one patch with no
# outline, and the box vanished (0 faces out).  Two-sided: the bottom faces
# away from the top's plane and stays free-form; watertight in, out.
run_case 0 "planedecim -o $TMP/pancake.ply tests/data/closed_pancake.ply"
check_num "closed box: faces kept" "$(info faces "$TMP/pancake.ply")" ">" 0
check_num "closed box: watertight" "$(info border_edges "$TMP/pancake.ply")" == 0
check_num "closed box: one piece" "$(info components "$TMP/pancake.ply")" == 1
check_num "closed box: manifold" "$(info non_manifold_edges "$TMP/pancake.ply")" == 0

# A board thinner than its noise, its two sides two patches facing apart
# that meet along their whole outline (tests/data/board_gen.py; a carved
# fusion of the 7-Scenes frames holds such a board).  Both polygons spanned
# the one outline in the same triangles, one copy of each was dropped as a
# duplicate, and the board came out as 2 faces with 4 border edges.  Now a
# rim of free-form faces between them: watertight, both sides planes.
run_case 0 "planedecim -v -o $TMP/board.ply tests/data/thin_board.ply 2>$TMP/board.err"
check_num "thin board: watertight" "$(info border_edges "$TMP/board.ply")" == 0
check_num "thin board: manifold" "$(info non_manifold_edges "$TMP/board.ply")" == 0
check_num "thin board: no duplicate faces" "$(info duplicate_faces "$TMP/board.ply")" == 0
check_num "thin board: both sides planes" "$(report unclean_patches "$TMP/board.err")" == 0
check_num "thin board: seam faces free-form" "$(report seam_faces "$TMP/board.err")" ">" 0

# A cut of a carved fusion's segmentation, closed again (a fan of free-form
# faces over each border of the cut; tests/data/carve_cut_gen.py, from the
# 20 7-Scenes frames fused at 1 cm with a sigma per vertex).  A patch
# (33) goes free-form in the rounds; vertices where it met another (37)
# had been projected onto its plane, stayed there, 1-2 cm off 37's plane,
# and were torn from 37: 8 border edges (68 faces).  Now they are projected
# again onto 37's plane: watertight, and every vertex of one patch's faces
# (beside free-form ones or none) on that patch's plane.
run_case 0 "planedecim -v -o $TMP/cut.ply tests/data/carve_cut.ply 2>$TMP/cut.err"
check_num "carved cut: watertight" "$(info border_edges "$TMP/cut.ply")" == 0
check_num "carved cut: manifold" "$(info non_manifold_edges "$TMP/cut.ply")" == 0
check_num "carved cut: one piece" "$(info components "$TMP/cut.ply")" == 1
check_num "carved cut: no degenerate faces" "$(info degenerate_faces "$TMP/cut.ply")" == 0
check_num "carved cut: no duplicate faces" "$(info duplicate_faces "$TMP/cut.ply")" == 0
check_num "carved cut: vertices projected again" "$(report reprojected "$TMP/cut.err")" ">" 0
check_num "carved cut: none torn" "$(report torn "$TMP/cut.err")" == 0
run_case 0 "planedecim -a -o $TMP/cut.txt tests/data/carve_cut.ply"
# the farthest vertex of one patch's faces from that patch's plane, in mm
# (152 faces: 0.0001; 1-2 cm where they were left on the plane gone)
check_num "carved cut: one patch's vertices on its plane (mm)" "$(awk '
	/^element/ && !h { cnt[$2] = $3; next }
	/^end_header/ { h = 1; vi = fi = pi = 0; next }
	!h { next }
	vi < cnt["vertex"] { x[vi] = $1; y[vi] = $2; z[vi++] = $3; next }
	fi < cnt["face"] { fi++; k = $1; p = $(k + 2); if (p < 0) next
		for (i = 2; i <= k + 1; i++)
			if (!($i in lab)) lab[$i] = p
			else if (lab[$i] != p) lab[$i] = -2
		next }
	pi < cnt["plane"] { nx[pi] = $1; ny[pi] = $2; nz[pi] = $3; d[pi++] = $4 }
	END { w = 0
		for (v in lab) if ((p = lab[v]) >= 0) {
			r = nx[p] * x[v] + ny[p] * y[v] + nz[p] * z[v] + d[p]
			if (r < 0) r = -r
			if (r > w) w = r
		}
		printf "%.6f", w * 1000 }' "$TMP/cut.txt")" "<" 1
# near the input: mean 3.6 mm, max 21 mm (200000 points on the model)
meshdist -p -s 200000 "$TMP/cut.ply" tests/data/carve_cut.ply >"$TMP/cut.dist"
check_num "carved cut: mean distance to the input (mm)" "$(figure mean "$TMP/cut.dist")" "<" 5
check_num "carved cut: largest distance to the input (mm)" "$(figure max "$TMP/cut.dist")" "<" 30

run_case 2 "planedecim -Z $TMP/one.ply" "" "planedecim: -Z: "
run_case 2 "planedecim $TMP/one.ply $TMP/one.ply" "" "planedecim: too many operands"
run_case 0 "planedecim --help | head -n 1 | grep -q '^usage: planedecim '"
run_case 0 "planedecim --version | grep -q '^planedecim (facet) '"
finish
