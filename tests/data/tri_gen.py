#!/usr/bin/env python3
"""Write the tripatch fixtures tests/data/tri_*.ply (hand-made wireframes in
simpchain's format: vertices, the edge element vertex1 vertex2 patch1 patch2
with patch1 on the left seen from the side the plane normal points to, the
plane element).  Run from the top folder; the outputs are committed.
tri_hole.ply is written by hand and not here."""


def ply(path, comments, verts, edges, planes, st=False, vertex_only=False):
    out = ['ply', 'format ascii 1.0'] + ['comment ' + c for c in comments]
    out += ['element vertex %d' % len(verts), 'property float x', 'property float y',
            'property float z']
    if st:
        out += ['property float s', 'property float t']
    if not vertex_only:
        out += ['element edge %d' % len(edges), 'property int vertex1', 'property int vertex2',
                'property int patch1', 'property int patch2']
    if planes is not None:
        out += ['element plane %d' % len(planes), 'property double nx', 'property double ny',
                'property double nz', 'property double d', 'property int count',
                'property double rms']
    out.append('end_header')
    out += [' '.join('%g' % x for x in v) for v in verts]
    if not vertex_only:
        out += [' '.join('%d' % x for x in e) for e in edges]
    if planes is not None:
        out += [' '.join('%g' % x for x in p) + ' 10 0' for p in planes]
    with open(path, 'w') as f:
        f.write('\n'.join(out) + '\n')


def loop(vs, patch, other):
    """Edges around vs in order, patch on the left, other beyond."""
    return [(vs[i], vs[(i + 1) % len(vs)], patch, other) for i in range(len(vs))]


Z = [(0, 0, 1, 0)]

# A 10 x 10 square (patch 0, z = 0) with two square holes filled by patches
# 1 and 2, with image coordinates of a camera 640 x 480 looking down -z from
# above (s = x / 10, t = y / 10: counter-clockwise in s t too).  Patch 0:
# 12 corners, 2 holes: 14 triangles; patches 1 and 2: 2 each.
P = [(0, 0), (10, 0), (10, 10), (0, 10), (2, 2), (4, 2), (4, 4), (2, 4),
     (6, 6), (8, 6), (8, 8), (6, 8)]
verts = [(x, y, 0, x / 10, y / 10) for x, y in P]
edges = loop([0, 1, 2, 3], 0, -1) + loop([4, 5, 6, 7], 1, 0) + loop([8, 9, 10, 11], 2, 0)
ply('tests/data/tri_two_holes.ply',
    ['two square holes in a square, with s t', 'camera pinhole 640 480 500 500 319.5 239.5'],
    verts, edges, Z * 3, st=True)

# An L of six corners (patch 0): 4 triangles of total area 3.
ply('tests/data/tri_L.ply', ['an L'],
    [(0, 0, 0), (2, 0, 0), (2, 1, 0), (1, 1, 0), (1, 2, 0), (0, 2, 0)],
    loop([0, 1, 2, 3, 4, 5], 0, -1), Z)

# A unit square whose s t cross (a bow tie, area not zero): the s t loop is
# not simple, the plane projection is; tripatch falls back to the plane.
ply('tests/data/tri_bowtie_st.ply', ['a square whose image coordinates cross'],
    [(0, 0, 0, 0.1, 0.1), (2, 0, 0, 0.9, 0.1), (2, 2, 0, 0.1, 0.8), (0, 2, 0, 0.9, 0.9)],
    loop([0, 1, 2, 3], 0, -1), Z, st=True)

# Patch 0 is two unit squares meeting at the corner (1,1) (the patch touches
# itself at one vertex); patch 1 fills the other two squares of the 2 x 2.
V = [(x, y, 0) for y in range(3) for x in range(3)]
edges = [(0, 1, 0, -1), (1, 4, 0, 1), (4, 3, 0, 1), (3, 0, 0, -1),
         (4, 5, 0, 1), (5, 8, 0, -1), (8, 7, 0, -1), (7, 4, 0, 1),
         (1, 2, 1, -1), (2, 5, 1, -1), (7, 6, 1, -1), (6, 3, 1, -1)]
ply('tests/data/tri_touch.ply', ['two squares of one patch touching at a vertex'], V, edges, Z * 2)

# A square with an extra edge of patch 0 leading nowhere (an open chain).
ply('tests/data/tri_open.ply', ['a square and a dangling edge'],
    [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 2, 0)],
    loop([0, 1, 2, 3], 0, -1) + [(2, 4, 0, -1)], Z)

# Bad inputs: no edge element; an edge of patch 5 with one plane; nothing.
ply('tests/data/tri_noedge.ply', ['vertices only'], [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], Z,
    vertex_only=True)
ply('tests/data/tri_badpatch.ply', ['an edge of a patch that is not a plane'],
    [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 0, -1), (1, 2, 5, -1), (2, 0, 0, -1)], Z)
ply('tests/data/tri_empty.ply', ['no vertices, no edges'], [], [], Z)
