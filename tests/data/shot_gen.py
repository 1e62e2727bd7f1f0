#!/usr/bin/env python3
"""Fixtures of the meshshot tests, written without facet's own code:
shot_atlas.png, a 48x32 RGB texture of six 16x16 cells in pure colours
(red, green, blue / yellow, cyan, magenta), and shot_cube.ply, the cube
[-1,1]^3 with each face (4 own vertices) mapped into one cell, inset by 3
texels so that bilinear lookups never reach a neighbouring cell:
face -z red, +z green, -x blue, +x yellow, -y cyan, +y magenta."""
import struct, zlib

COLS = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0), (0, 255, 255), (255, 0, 255)]

def png(path, w, h, rows):
    def chunk(t, d):
        c = struct.pack(">I", len(d)) + t + d
        return c + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    raw = b"".join(b"\0" + bytes(r) for r in rows)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(data)

rows = []
for y in range(32):
    r = []
    for x in range(48):
        r += COLS[(y // 16) * 3 + x // 16]
    rows.append(r)
png("shot_atlas.png", 48, 32, rows)

# Faces: (axis, sign); corners listed counter-clockwise seen from outside.
faces = [(2, -1), (2, 1), (0, -1), (0, 1), (1, -1), (1, 1)]
verts, tris = [], []
for i, (ax, sg) in enumerate(faces):
    u, v = [(1, 2), (2, 0), (0, 1)][ax]
    cell_x, cell_y = i % 3, i // 3          # cell row 0 is the top of the image
    s0, s1 = (16 * cell_x + 3) / 48, (16 * cell_x + 13) / 48
    t1, t0 = 1 - (16 * cell_y + 3) / 32, 1 - (16 * cell_y + 13) / 32
    base = len(verts)
    for a, b, s, t in [(-1, -1, s0, t0), (1, -1, s1, t0), (1, 1, s1, t1), (-1, 1, s0, t1)]:
        p = [0, 0, 0]
        p[ax], p[u], p[v] = sg, a, b
        verts.append((p, s, t))
    q = [base, base + 1, base + 2, base + 3]
    if sg < 0:
        q.reverse()
    tris.append(q)
with open("shot_cube.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\ncomment TextureFile shot_atlas.png\n")
    f.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(verts))
    f.write("property float s\nproperty float t\nproperty float distance\n")
    f.write("element face %d\nproperty list uchar int vertex_indices\nproperty int patch\n" % len(tris))
    f.write("end_header\n")
    for p, s, t in verts:
        f.write("%g %g %g %.9g %.9g %g\n" % (p[0], p[1], p[2], s, t, p[0] + p[1] + p[2]))
    for i, q in enumerate(tris):
        f.write("4 %d %d %d %d %d\n" % (q[0], q[1], q[2], q[3], i))
