# chain_label.awk - label the faces of a noiseless mesh with the true planes
# of a synthetic scene, for the simpchain tests: what segplanes would write if
# it were perfect.
#
#   awk -f tests/data/chain_label.awk planes.txt mesh.ply > labelled.ply
#
# planes.txt: one plane per line, "nx ny nz d" (the i-th is patch i), as in
# the plane element of mkscene's scene.ply.  mesh.ply: ascii PLY of
# triangles whose vertices lie on the scene's surfaces (dm2mesh of a
# noiseless mkscene view in the world frame: within 1e-5 of the truth).
# A vertex lies on every plane within eps = 1e-4 of it; a face gets the
# lowest plane holding all three of its corners, else the lowest holding
# two, else -1 (a curved surface, or a face across two planes' edge).  The
# output is the mesh with face property int patch and the plane element.
BEGIN { eps = 1e-4; np = 0 }
FNR == NR { n[np] = $1 " " $2 " " $3; nx[np] = $1; ny[np] = $2; nz[np] = $3; d[np] = $4; np++; next }
!body {
	if ($1 == "element" && $2 == "vertex") nv = $3
	if ($1 == "element" && $2 == "face") { nf = $3; inface = 1; print; next }
	if (inface && ($1 == "element" || $1 == "end_header")) { print "property int patch"; inface = 0 }
	if ($1 == "end_header") {
		print "element plane " np
		print "property double nx"; print "property double ny"; print "property double nz"
		print "property double d"; print "property int count"; print "property double rms"
		print; body = 1; v = 0; f = 0; next
	}
	print; next
}
v < nv {
	on[v] = ""
	for (p = 0; p < np; p++) {
		e = nx[p] * $1 + ny[p] * $2 + nz[p] * $3 + d[p]
		if (e < eps && e > -eps) on[v] = on[v] " " p " "
	}
	v++; print; next
}
f < nf {
	lab = -1; two = -1
	for (p = 0; p < np && lab < 0; p++) {
		k = (index(on[$2], " " p " ") > 0) + (index(on[$3], " " p " ") > 0) + (index(on[$4], " " p " ") > 0)
		if (k == 3) lab = p
		else if (k == 2 && two < 0) two = p
	}
	if (lab < 0) lab = two
	f++; print $0 " " lab
	if (f == nf) for (p = 0; p < np; p++) print nx[p], ny[p], nz[p], d[p], 0, 0
	next
}
