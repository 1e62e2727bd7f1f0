# tests/data/pancake_gen.py - writes tests/data/closed_pancake.ply (python3 pancake_gen.py > closed_pancake.ply).
# A closed thin box ("pancake"): a 6x6 grid on top (z = 0.01, wound to +z,
# patch 0), its bottom one quad (z = 0, wound to -z) and four side strips:
# 50 faces under the top, fewer than planedecim's --min-free 64.
n = 6
V = []; F = []
def vid(x, y, z):
    V.append((x, y, z)); return len(V) - 1
top = [[vid(i * 0.1, j * 0.1, 0.01) for i in range(n + 1)] for j in range(n + 1)]
for j in range(n):
    for i in range(n):
        a, b, c, d = top[j][i], top[j][i + 1], top[j + 1][i], top[j + 1][i + 1]
        F.append((a, b, d, 0)); F.append((a, d, c, 0))
# the border of the top, counter-clockwise seen from +z
ring = [top[0][i] for i in range(n)] + [top[j][n] for j in range(n)] + \
       [top[n][i] for i in range(n, 0, -1)] + [top[j][0] for j in range(n, 0, -1)]
L = n * 0.1
corner = {(0, 0): vid(0, 0, 0), (1, 0): vid(L, 0, 0), (1, 1): vid(L, L, 0), (0, 1): vid(0, L, 0)}
def base_of(k):   # the bottom corner below ring vertex k's side
    side = k // n
    return [corner[(0, 0)], corner[(1, 0)], corner[(1, 1)], corner[(0, 1)]][side], \
           [corner[(1, 0)], corner[(1, 1)], corner[(0, 1)], corner[(0, 0)]][side]
m = len(ring)
for k in range(m):
    a, b = ring[k], ring[(k + 1) % m]
    s, e = base_of(k)
    # the strip below edge a-b: triangles down to the side's base line, facing outwards
    F.append((b, a, s, -1))
    F.append((b, s, e, -1)) if (k + 1) % n == 0 else None
# bottom: the quad's two triangles, facing -z
c00, c10, c11, c01 = corner[(0, 0)], corner[(1, 0)], corner[(1, 1)], corner[(0, 1)]
F.append((c00, c11, c10, -1)); F.append((c00, c01, c11, -1))
print("ply\nformat ascii 1.0\ncomment a closed thin box: its top one patch, the rest fewer faces than --min-free")
print("element vertex %d\nproperty float x\nproperty float y\nproperty float z" % len(V))
print("element face %d\nproperty list uchar int vertex_indices\nproperty int patch" % len(F))
print("element plane 1\nproperty double nx\nproperty double ny\nproperty double nz\nproperty double d\nproperty int count\nproperty double rms")
print("end_header")
for x, y, z in V: print("%g %g %g" % (x, y, z))
for a, b, c, l in F: print("3 %d %d %d %d" % (a, b, c, l))
print("0 0 1 -0.01 %d 0" % ((n + 1) ** 2))
