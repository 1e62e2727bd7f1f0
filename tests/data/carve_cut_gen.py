# tests/data/carve_cut_gen.py - writes tests/data/carve_cut.ply from
# segplanes' output for a carved fusion (python3 carve_cut_gen.py
# 2-patches.ply carve_cut.ply; planarize --keep DIR writes 2-patches.ply):
# the faces with every corner in the box below, less those at a vertex
# where the cut's border passes twice, the largest piece of them, and each
# border loop of the cut capped by a fan of free-form faces (patch -1) to
# its centroid: a closed mesh again, with its labels, planes and sigma.
# Made from the carved tsdfuse of the 20 7-Scenes kitchen frames at 1 cm
# with a sigma per vertex (2391294 faces, watertight).
import struct, sys
from collections import defaultdict

BOX = (-1.48, 0.34, 2.07, -1.08, 0.74, 2.47)
T = {'char': 'b', 'uchar': 'B', 'short': 'h', 'ushort': 'H', 'int': 'i', 'uint': 'I', 'float': 'f',
     'double': 'd', 'int8': 'b', 'uint8': 'B', 'int32': 'i', 'uint32': 'I', 'float32': 'f', 'float64': 'd'}


def read_ply(path):
    """Binary little-endian PLY: {element: {property: [values]}}."""
    f = open(path, 'rb')
    elems = []
    while True:
        w = f.readline().decode('latin1').split()
        if w == ['end_header']:
            break
        if w and w[0] == 'element':
            elems.append((w[1], int(w[2]), []))
        elif w and w[0] == 'property':
            elems[-1][2].append((w[4], w[2], w[3]) if w[1] == 'list' else (w[2], w[1], None))
    data, off, out = f.read(), 0, {}
    for name, n, props in elems:
        cols = {p[0]: [] for p in props}
        if all(p[2] is None for p in props):
            fmt = '<' + ''.join(T[p[1]] for p in props)
            for row in struct.iter_unpack(fmt, data[off:off + struct.calcsize(fmt) * n]):
                for p, x in zip(props, row):
                    cols[p[0]].append(x)
            off += struct.calcsize(fmt) * n
        else:
            for _ in range(n):
                for p in props:
                    if p[2] is None:
                        cols[p[0]].append(struct.unpack_from('<' + T[p[1]], data, off)[0])
                        off += struct.calcsize(T[p[1]])
                    else:
                        k = struct.unpack_from('<' + T[p[1]], data, off)[0]
                        off += struct.calcsize(T[p[1]])
                        cols[p[0]].append(struct.unpack_from('<%d%s' % (k, T[p[2]]), data, off))
                        off += k * struct.calcsize(T[p[2]])
        out[name] = cols
    return out


d = read_ply(sys.argv[1])
V, F, L, P = d['vertex'], d['face']['vertex_indices'], d['face']['patch'], d['plane']
X = list(zip(V['x'], V['y'], V['z']))
inside = [all(BOX[i] <= p[i] <= BOX[3 + i] for i in range(3)) for p in X]
faces = {i for i, f in enumerate(F) if all(inside[v] for v in f)}
while True:
    half = {(f[j], f[(j + 1) % 3]) for f in (F[i] for i in faces) for j in range(3)}
    border = [(a, b) for a, b in half if (b, a) not in half]
    starts = defaultdict(int)
    for a, _ in border:
        starts[a] += 1
    parent = {}

    def root(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for i in faces:
        for v in F[i]:
            parent[root(v)] = root(F[i][0])
    size = defaultdict(int)
    for i in faces:
        size[root(F[i][0])] += 1
    big = max(size, key=size.get)
    drop = {i for i in faces if root(F[i][0]) != big or any(starts[v] > 1 for v in F[i])}
    if not drop:
        break
    faces -= drop
faces = sorted(faces)
nxt = dict(border)
seen, loops = set(), []
for a in sorted(nxt):
    loop = []
    while a not in seen:
        seen.add(a)
        loop.append(a)
        a = nxt[a]
    if loop:
        loops.append(loop)
used = sorted({v for i in faces for v in F[i]})
new = {v: k for k, v in enumerate(used)}
verts = [X[v] + (V['sigma'][v],) for v in used]
tris = [(tuple(new[v] for v in F[i]), L[i]) for i in faces]
for loop in loops:
    c = len(verts)
    verts.append(tuple(sum(X[v][i] for v in loop) / len(loop) for i in range(3)) +
                 (sum(V['sigma'][v] for v in loop) / len(loop),))
    tris += [((c, new[loop[(j + 1) % len(loop)]], new[loop[j]]), -1) for j in range(len(loop))]
out = open(sys.argv[2], 'wb')
head = ['ply', 'format binary_little_endian 1.0',
        'comment cut from segplanes of the carved 7-Scenes kitchen fusion at 1 cm with sigma (tests/data/carve_cut_gen.py)',
        'element vertex %d' % len(verts), 'property float x', 'property float y', 'property float z',
        'property float sigma', 'element face %d' % len(tris), 'property list uchar int vertex_indices',
        'property int patch', 'element plane %d' % len(P['nx']), 'property double nx', 'property double ny',
        'property double nz', 'property double d', 'property int count', 'property double rms', 'end_header']
out.write(('\n'.join(head) + '\n').encode())
for v in verts:
    out.write(struct.pack('<4f', *v))
for t, lab in tris:
    out.write(struct.pack('<B3ii', 3, t[0], t[1], t[2], lab))
for i in range(len(P['nx'])):
    out.write(struct.pack('<4did', P['nx'][i], P['ny'][i], P['nz'][i], P['d'][i], P['count'][i], P['rms'][i]))
