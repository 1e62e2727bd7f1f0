# regions_purity.awk REGIONS MESH: for each region of REGIONS (lines "name
# x1,y1 x2,y2 ..."), the faces of MESH (ascii PLY in its camera's frame,
# face property patch last, "comment camera pinhole W H fx fy cx cy") whose
# centroid projects inside the polygon: prints "name faces patch share",
# patch the label most of them carry (-1 free-form counts as a label) and
# share its fraction of them.
function inside(px, py, n, xs, ys,    i, j, c) {
	c = 0
	for (i = 1; i <= n; i++) {
		j = i == 1 ? n : i - 1
		if ((ys[i] > py) != (ys[j] > py) &&
		    px < (xs[j] - xs[i]) * (py - ys[i]) / (ys[j] - ys[i]) + xs[i])
			c = !c
	}
	return c
}
FNR == 1 { file++ }
file == 1 {
	if ($0 ~ /^#/ || NF < 4) next
	nr++; name[nr] = $1; np[nr] = NF - 1
	for (k = 2; k <= NF; k++) { split($k, xy, ","); X[nr, k - 1] = xy[1]; Y[nr, k - 1] = xy[2] }
	next
}
!h {
	if ($1 == "comment" && $2 == "camera" && $3 == "pinhole") { fx = $6; fy = $7; cx = $8; cy = $9 }
	if ($1 == "element") { el = $2; cnt[el] = $3 }
	if ($1 == "end_header") h = 1
	next
}
vi < cnt["vertex"] { vx[vi] = $1; vy[vi] = $2; vz[vi] = $3; vi++; next }
fi < cnt["face"] {
	fi++
	sx = sy = sz = 0
	for (k = 2; k <= $1 + 1; k++) { sx += vx[$k]; sy += vy[$k]; sz += vz[$k] }
	if (sz <= 0) next
	u = fx * sx / sz + cx; v = fy * sy / sz + cy
	for (r = 1; r <= nr; r++) {
		for (k = 1; k <= np[r]; k++) { xs[k] = X[r, k]; ys[k] = Y[r, k] }
		if (inside(u, v, np[r], xs, ys)) { T[r]++; C[r, $NF]++; L[r, $NF] = 1 }
	}
}
END {
	for (r = 1; r <= nr; r++) {
		best = ""; bc = -1
		for (key in L) {
			split(key, q, SUBSEP)
			if (q[1] == r && (C[r, q[2]] > bc || (C[r, q[2]] == bc && q[2] + 0 < best + 0))) { bc = C[r, q[2]]; best = q[2] }
		}
		printf "%s %d %s %.4f\n", name[r], T[r], best, T[r] ? bc / T[r] : 0
	}
}
