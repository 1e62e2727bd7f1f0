#!/usr/bin/env python3
"""Write the dm2mesh fixtures tests/data/dm_*.  Run from the top folder; the
outputs are committed, so this runs only when a fixture changes.  The images
use the independent PNG/PFM encoders of img_gen.py."""
import importlib.util
import math

spec = importlib.util.spec_from_file_location('img_gen', 'tests/data/img_gen.py')
img = importlib.util.module_from_spec(spec)
spec.loader.exec_module(img)

W, H = 8, 6

def text(path, s):
    with open(path, 'w') as f:
        f.write(s)

# Disparity 20 px everywhere but one hole (0) and one NaN: with baseline 0.1
# and focal 100 every vertex is at depth 0.1 * 100 / 20 = 0.5.
rows = [[20.0] * W for _ in range(H)]
rows[2][3] = 0.0
rows[4][6] = float('nan')
img.put('tests/data/dm_disp.pfm', img.pfm(rows, 1))

# A 16-bit depth map in millimetres of the plane z = 2 + 0.1 x (metres),
# seen by fx = fy = 10, cx = 3.5, cy = 2.5: depth at pixel u is
# 2 / (1 - 0.1 (u - 3.5) / 10), rounded to the millimetre; the two
# "no data" values 0 and 65535 in two corners.
rows = []
for v in range(H):
    r = []
    for u in range(W):
        r.append(round(2000 / (1 - 0.01 * (u - 3.5))))
    rows.append(r)
rows[0][0] = 0
rows[H - 1][W - 1] = 65535
img.put('tests/data/dm_plane16.png', img.png(rows, 16, 0))

# The camera of dm_plane16.png in the three file forms.
text('tests/data/dm_cam.json',
     '{\n\t"width" : 8,\n\t"height" : 6,\n\t"intrinsic_matrix" :\n\t[\n'
     '\t\t10.0,\n\t\t0.0,\n\t\t0.0,\n\t\t0.0,\n\t\t10.0,\n\t\t0.0,\n\t\t3.5,\n\t\t2.5,\n\t\t1.0\n\t]\n}\n')
text('tests/data/dm_K.txt', '1.0e+01 0 3.5e+00\n0 1.0e+01 2.5e+00\n0 0 1\n')
text('tests/data/dm_cam.txt', 'camera pinhole 8 6 10 10 3.5 2.5\n')
text('tests/data/dm_cam_big.txt', 'camera pinhole 640 480 10 10 3.5 2.5\n')

# A quarter turn about y and a shift: x_world = z_cam + 1, y = y + 2,
# z_world = -x_cam + 3.
text('tests/data/dm_pose.txt', '0 0 1 1\n0 1 0 2\n-1 0 0 3\n0 0 0 1\n')
text('tests/data/dm_pose_line.txt', 'pose 0 0 1 1 0 1 0 2 -1 0 0 3\n')
text('tests/data/dm_badpose.txt', '1 0 0 0\n0 2 0 0\n0 0 1 0\n0 0 0 1\n')
text('tests/data/dm_shortpose.txt', '1 0 0 0\n0 1 0 0\n')

# Sparse points: a 5 x 4 lattice in the image (jittered so that no four
# are cocircular) on the plane z = 4, one repeated image position, a
# comment and a blank line.  20 distinct points, 14 on the hull: 2n-2-h = 24.
lines = ['# u v x y z']
for j in range(4):
    for i in range(5):
        u = 10 * i + (0.5 if (i * 7 + j * 3) % 4 == 1 and 0 < i < 4 and 0 < j < 3 else 0)
        v = 10 * j
        lines.append('%g %g %.17g %.17g 4' % (u, v, (u - 20) / 100 * 4, (v - 15) / 100 * 4))
lines.append('')
lines.append('10 0 9 9 9')
text('tests/data/dm_points.txt', '\n'.join(lines) + '\n')
text('tests/data/dm_collinear.txt', ''.join('%d %d 0 0 1\n' % (i, 2 * i) for i in range(6)))
text('tests/data/dm_points_bad.txt', '1 2 3 4 5\n1 2 3 4\n')
text('tests/data/dm_points_nan.txt', '1 2 3 4 5\n1 2 nan 4 5\n')
ply = ['ply', 'format ascii 1.0', 'element vertex 4', 'property float u', 'property float v',
       'property float x', 'property float y', 'property float z', 'end_header',
       '0 0 -1 -1 5', '10 0 1 -1 5', '0 10 -1 1 5', '10 10 1 1 5']
text('tests/data/dm_points.ply', '\n'.join(ply) + '\n')
