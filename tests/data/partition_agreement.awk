# awk -f partition_agreement.awk A.ply B.ply: the share of the faces of two
# ascii PLY meshes of the same faces in the same order (segplanes -a) whose
# patch labels agree: each patch of A counts the faces of its most common
# label in B.
FNR == 1 { file++; h = 0; n = 0 }
/^end_header/ { h = 1; next }
h && NF == 5 && $1 == 3 {
	n++
	if (file == 1) a[n] = $5
	else { pairs[a[n] SUBSEP $5]++; total++ }
}
END {
	for (k in pairs) { split(k, p, SUBSEP); if (pairs[k] > best[p[1]]) best[p[1]] = pairs[k] }
	for (l in best) agree += best[l]
	printf "%.4f\n", total ? agree / total : 0
}
