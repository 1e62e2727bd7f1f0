#!/usr/bin/env python3
"""pv_gen.py - writes the projverts fixtures pv_*.ply (run from tests/data).

pv_tent.ply: two roof planes z = 2 + 0.5 x (patch 0, x < 0) and
z = 2 - 0.5 x (patch 1) meeting along the ridge x = 0, z = 2; vertices a
few centimetres off, ridge vertices off the ridge; a pinhole camera 100 x 80
(f 50, centre 49.5 39.5) whose pose shifts it to z = -1, s t, a red column.
pv_nocam / pv_nopatch / pv_noplane / pv_nost: the same without the camera
and pose, the patch property, the plane element, the s t columns.
pv_empty.ply: no vertices or faces, patch and plane declared.
pv_parallel.ply: planes z = 0 and 5 degrees from it (sin5 x + cos5 z =
0.02) meeting 0.229 from their shared edge, whose vertices sit 0.01 above
z = 0.
"""
import math

s5 = math.sqrt(1.25)
HDR_CAM = ("comment camera pinhole 100 80 50 50 49.5 39.5\n"
           "comment pose 1 0 0 0 0 1 0 0 0 0 1 -1\n"
           "comment TextureFile pv_tent.png\n")
VERTS = [(-1, -0.5, 1.52), (-1, 0.5, 1.47), (0.01, -0.5, 2.03),
         (-0.02, 0.5, 1.98), (1, -0.5, 1.49), (1, 0.5, 1.51)]
FACES = [(0, 2, 1), (1, 2, 3), (2, 4, 3), (3, 4, 5)]
LAB = [0, 0, 1, 1]
PLANES = [(0.5 / s5, 0, -1 / s5, 2 / s5, 2, 0.001),
          (-0.5 / s5, 0, -1 / s5, 2 / s5, 2, 0.002)]


def tent(name, cam=True, st=True, patch=True, plane=True):
    with open(name, "w") as f:
        f.write("ply\nformat ascii 1.0\n")
        if cam:
            f.write(HDR_CAM)
        f.write("element vertex 6\nproperty double x\nproperty double y\nproperty double z\n")
        if st:
            f.write("property float s\nproperty float t\n")
        f.write("property uchar red\n")
        f.write("element face 4\nproperty list uchar int vertex_indices\n")
        if patch:
            f.write("property int patch\n")
        if plane:
            f.write("element plane 2\nproperty double nx\nproperty double ny\n"
                    "property double nz\nproperty double d\nproperty int count\n"
                    "property double rms\n")
        f.write("end_header\n")
        for i, v in enumerate(VERTS):
            f.write("%r %r %r" % v)
            if st:
                f.write(" 0.25 0.75")
            f.write(" %d\n" % (10 * i))
        for fc, lab in zip(FACES, LAB):
            f.write("3 %d %d %d" % fc)
            if patch:
                f.write(" %d" % lab)
            f.write("\n")
        if plane:
            for p in PLANES:
                f.write("%r %r %r %r %d %r\n" % p)


tent("pv_tent.ply")
tent("pv_nocam.ply", cam=False)
tent("pv_nopatch.ply", patch=False)
tent("pv_noplane.ply", plane=False)
tent("pv_nost.ply", st=False)

with open("pv_empty.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
            "property float z\nelement face 0\nproperty list uchar int vertex_indices\n"
            "property int patch\nelement plane 0\nproperty double nx\nproperty double ny\n"
            "property double nz\nproperty double d\nend_header\n")

a = math.radians(5)
n2 = (math.sin(a), 0, math.cos(a))
zr = (0.02 - math.sin(a)) / math.cos(a)
V = [(-1, 0, 0), (-1, 1, 0), (0, 0, 0.01), (0, 1, 0.01), (1, 0, zr), (1, 1, zr)]
with open("pv_parallel.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\n"
            "property double z\nelement face 2\nproperty list uchar int vertex_indices\n"
            "property int patch\nelement plane 2\nproperty double nx\nproperty double ny\n"
            "property double nz\nproperty double d\nend_header\n")
    for v in V:
        f.write("%r %r %r\n" % v)
    f.write("4 0 2 3 1 0\n4 2 4 5 3 1\n")
    f.write("0 0 1 0\n%r %r %r %r\n" % (n2 + (-0.02,)))
