# chain_check.awk - check a simpchain wireframe against its labelled input,
# for tests/cmd/simpchain.sh.
#
#   awk -f tests/data/chain_check.awk input.ply wireframe.ply
#
# Both files ascii PLY; the input's faces carry "int patch" as their last
# property (vertex_indices first).  Prints "key value" lines:
#   edges       rows of the edge element
#   patches     planes of the wireframe (labels must be below this)
#   bad_labels  edges whose patch1 is not in [0, patches), patch2 not in
#               [-1, patches), or patch1 == patch2
#   bad_index   edges with a vertex index out of range or twice
#   dup_pairs   vertex pairs that appear on more than one edge
#   unbalanced  (patch, vertex) pairs whose in- and out-degree differ,
#               patch1's edges taken as they run, patch2's reversed
#   boundary    input vertices on a boundary edge of some patch (an edge
#               walked by one face of a patch, or by faces of two labels
#               one of which is a patch)
#   max_dist    largest distance of such a vertex from the nearest
#               wireframe edge (every boundary point must lie within the
#               tolerance of the simplified boundary)
function hdr(line) {
	split(line, w, " ")
	if (w[1] == "element") { en[ne] = w[2]; ec[ne] = w[3]; np_[ne] = 0; ne++ }
	else if (w[1] == "property") pn[ne - 1, np_[ne - 1]++] = w[NF]
}
FNR == 1 { file++; ne = 0; body = 0 }
!body { if ($1 == "end_header") { body = 1; e = 0; r = 0 } else hdr($0); next }
{
	while (r >= ec[e]) { e++; r = 0 }
	if (file == 1) {
		if (en[e] == "vertex") { ix[r] = $1; iy[r] = $2; iz[r] = $3 }
		else if (en[e] == "face") {
			n = $1; lab = $NF
			for (k = 2; k <= n + 1; k++) {
				a = $k; b = (k == n + 1) ? $2 : $(k + 1)
				key = (a + 0 < b + 0) ? a "," b : b "," a
				cnt[key]++
				if (cnt[key] == 1) l1[key] = lab
				else if (lab != l1[key]) l2[key] = lab
			}
		}
	} else {
		if (en[e] == "vertex") { wx[r] = $1; wy[r] = $2; wz[r] = $3; nwv = r + 1 }
		else if (en[e] == "plane") npl = r + 1
		else if (en[e] == "edge") { v1[r] = $1; v2[r] = $2; p1[r] = $3; p2[r] = $4; nwe = r + 1 }
	}
	r++
}
function segdist(px, py, pz, a, b,   dx, dy, dz, t, l2, ex, ey, ez) {
	dx = wx[b] - wx[a]; dy = wy[b] - wy[a]; dz = wz[b] - wz[a]
	l2 = dx * dx + dy * dy + dz * dz
	t = l2 > 0 ? ((px - wx[a]) * dx + (py - wy[a]) * dy + (pz - wz[a]) * dz) / l2 : 0
	if (t < 0) t = 0
	if (t > 1) t = 1
	ex = wx[a] + t * dx - px; ey = wy[a] + t * dy - py; ez = wz[a] + t * dz - pz
	return sqrt(ex * ex + ey * ey + ez * ez)
}
END {
	bad = badi = dup = unb = 0
	for (i = 0; i < nwe; i++) {
		if (!(p1[i] >= 0 && p1[i] < npl && p2[i] >= -1 && p2[i] < npl && p1[i] != p2[i])) bad++
		if (!(v1[i] >= 0 && v1[i] < nwv && v2[i] >= 0 && v2[i] < nwv && v1[i] != v2[i])) badi++
		key = (v1[i] + 0 < v2[i] + 0) ? v1[i] "," v2[i] : v2[i] "," v1[i]
		if (seen[key]++) dup++
		deg[p1[i], v1[i]]++; deg[p1[i], v2[i]]--
		if (p2[i] >= 0) { deg[p2[i], v2[i]]++; deg[p2[i], v1[i]]-- }
	}
	for (k in deg) if (deg[k] != 0) unb++
	nb = 0; maxd = 0
	for (key in cnt) {
		isb = (cnt[key] == 1 && l1[key] >= 0) || ((key in l2) && (l1[key] >= 0 || l2[key] >= 0))
		if (!isb) continue
		split(key, ab, ",")
		bv[ab[1]] = 1; bv[ab[2]] = 1
	}
	for (v in bv) {
		nb++
		best = -1
		for (i = 0; i < nwe; i++) {
			d = segdist(ix[v], iy[v], iz[v], v1[i], v2[i])
			if (best < 0 || d < best) best = d
		}
		if (best > maxd) maxd = best
	}
	print "edges", nwe
	print "patches", npl
	print "bad_labels", bad
	print "bad_index", badi
	print "dup_pairs", dup
	print "unbalanced", unb
	print "boundary", nb
	printf "max_dist %.9g\n", maxd
}
