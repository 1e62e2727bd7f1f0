# colour_wall.awk - a dense mesh that carries its colour as vertex red green
# blue, for planarize's atlas baked from vertex colours (planarize_bake.sh,
# interop.sh): a wall z = 2 (x in [-1, 1], y in [-1, 0.6]) painted with a
# checkerboard of 0.2 m squares, blue and yellow, and a floor y = 0.6 (z in
# [1.2, 2]) with two red lines 6 cm wide (x = 0.5 (z - 1.2) and z = 1.6),
# vertices every 2 cm, seen by the 320x240 camera in the header from the
# origin.  Usage: awk -f colour_wall.awk >dense.ply
BEGIN {
	s = 0.02; nv = 0
	for (j = 0; j <= 80; j++) for (i = 0; i <= 100; i++) { x = -1 + i * s; y = -1 + j * s; z = 2
		cx = int((x + 1) / 0.2 + 1e-9); cy = int((y + 1) / 0.2 + 1e-9)
		c = (cx + cy) % 2 ? "40 60 170" : "235 215 90"
		v[nv++] = sprintf("%.4f %.4f %.4f %s", x, y, z, c) }
	for (j = 0; j <= 40; j++) for (i = 0; i <= 100; i++) { x = -1 + i * s; z = 2 - j * s; y = 0.6
		d = x - 0.5 * (z - 1.2); if (d < 0) d = -d; e = z - 1.6; if (e < 0) e = -e
		c = d < 0.03 || e < 0.03 ? "170 30 30" : "200 200 200"
		v[nv++] = sprintf("%.4f %.4f %.4f %s", x, y, z, c) }
	nf = 0
	for (p = 0; p < 2; p++) for (j = 0; j < (p ? 40 : 80); j++) for (i = 0; i < 100; i++) {
		a = p * 81 * 101 + j * 101 + i
		f[nf++] = sprintf("3 %d %d %d", a, a + 1, a + 101)
		f[nf++] = sprintf("3 %d %d %d", a + 1, a + 102, a + 101) }
	print "ply\nformat ascii 1.0\ncomment camera pinhole 320 240 240 240 159.5 119.5"
	print "element vertex " nv "\nproperty float x\nproperty float y\nproperty float z"
	print "property uchar red\nproperty uchar green\nproperty uchar blue"
	print "element face " nf "\nproperty list uchar int vertex_indices\nend_header"
	for (k = 0; k < nv; k++) print v[k]
	for (k = 0; k < nf; k++) print f[k] }
