# tests/data/board_gen.py - writes tests/data/thin_board.ply (python3 board_gen.py > thin_board.ply).
# A board thinner than any noise, as a fused scan's two sides of it come
# out of segplanes: a 10x10 grid on top (inner vertices at z = +0.002,
# wound to +z, patch 0) and below (z = -0.002, wound to -z, patch 1), the
# border ring shared: closed, and the two patches meet along their whole
# outline with no rim between them.
n = 10
V = []; F = []
def vid(x, y, z):
    V.append((x, y, z)); return len(V) - 1
top = [[None] * (n + 1) for _ in range(n + 1)]
bot = [[None] * (n + 1) for _ in range(n + 1)]
for j in range(n + 1):
    for i in range(n + 1):
        border = i in (0, n) or j in (0, n)
        top[j][i] = vid(i * 0.05, j * 0.05, 0 if border else 0.002)
        bot[j][i] = top[j][i] if border else vid(i * 0.05, j * 0.05, -0.002)
for j in range(n):
    for i in range(n):
        # the diagonal away from the two corners where it would join three
        # border vertices (a triangle both sides would share)
        flip = (i, j) in ((n - 1, 0), (0, n - 1))
        for g, l, w in ((top, 0, 1), (bot, 1, -1)):
            a, b, c, d = g[j][i], g[j][i + 1], g[j + 1][i], g[j + 1][i + 1]
            tris = [(a, b, c), (b, d, c)] if flip else [(a, b, d), (a, d, c)]
            for t in tris:
                F.append((t[0], t[1], t[2], l) if w > 0 else (t[0], t[2], t[1], l))
print("ply\nformat ascii 1.0\ncomment a board thinner than its noise: two patches facing apart, one outline")
print("element vertex %d\nproperty float x\nproperty float y\nproperty float z" % len(V))
print("element face %d\nproperty list uchar int vertex_indices\nproperty int patch" % len(F))
print("element plane 2\nproperty double nx\nproperty double ny\nproperty double nz\nproperty double d\nproperty int count\nproperty double rms")
print("end_header")
for x, y, z in V: print("%g %g %g" % (x, y, z))
for a, b, c, l in F: print("3 %d %d %d %d" % (a, b, c, l))
print("0 0 1 -0.001 %d 0.001" % ((n + 1) ** 2))
print("0 0 -1 -0.001 %d 0.001" % ((n + 1) ** 2))
