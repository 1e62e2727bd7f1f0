#!/usr/bin/env python3
"""tests/cmd/interop.py MODULE SPEC... - read files facet wrote with another
program's reader (open3d, pymeshlab, trimesh or bpy, Blender's) and check
what it got.

Each SPEC is "path:ref:kind", ref an ascii PLY of the same mesh (meshconv -a)
whose numbers are the truth, kind one of
  mesh      vertices and triangles as in ref, the same positions;
  st        also the vertex s t as texture coordinates and the TextureFile
            image loaded (Open3D reads no texture coordinates from PLY);
  corner    also the per-corner face texcoord lists, one image per view;
  wire      vertices only (an edge element, no faces);
  obj       an OBJ with its .mtl: positions, vt (per vertex, or per corner
            when ref has no s t) and the image.
Prints "PASS name" or "FAIL name: why" per check, for tests/cmd/interop.sh
to count; a reader that crashes ends the process, which the shell counts as
a failure too."""
import os
import sys

import numpy as np


def read_ascii_ply(path):
    """(vertex columns, faces, face columns, comments) of an ascii PLY."""
    with open(path) as f:
        lines = f.read().split('\n')
    elems, comments, i = [], [], 1
    while lines[i] != 'end_header':
        w = lines[i].split()
        if w[0] == 'element':
            elems.append((w[1], int(w[2]), []))
        elif w[0] == 'property':
            elems[-1][2].append((w[-1], w[1] == 'list'))
        elif w[0] == 'comment':
            comments.append(lines[i][8:])
        i += 1
    i += 1
    out = {}
    for name, count, props in elems:
        rows = []
        for _ in range(count):
            vals, w, k = {}, lines[i].split(), 0
            for pname, is_list in props:
                if is_list:
                    n = int(w[k])
                    vals[pname] = [float(x) for x in w[k + 1:k + 1 + n]]
                    k += n + 1
                else:
                    vals[pname] = float(w[k])
                    k += 1
            rows.append(vals)
            i += 1
        out[name] = rows
    return out, comments


def check(name, ok, why=''):
    print(('PASS %s' % name) if ok else ('FAIL %s: %s' % (name, why)))
    sys.stdout.flush()


def close(a, b, tol):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a.shape == b.shape and (a.size == 0 or float(np.max(np.abs(a - b))) <= tol)


def same_points(a, b, tol):
    """As many points, each of a within tol of a point of b (each axis)."""
    if a.shape != b.shape:
        return False
    for i in range(0, len(a), 256):
        d = np.abs(a[i:i + 256, None, :] - b[None, :, :]).max(axis=2).min(axis=1)
        if not np.all(d <= tol):
            return False
    return True


def main():
    module = sys.argv[1]
    for spec in sys.argv[2:]:
        path, refpath, kind = spec.rsplit(':', 2)
        ref, comments = read_ascii_ply(refpath)
        xyz = np.array([[v['x'], v['y'], v['z']] for v in ref['vertex']])
        faces = [f['vertex_indices'] for f in ref.get('face', [])]
        ntri = sum(len(f) - 2 for f in faces)
        textures = [c.split(None, 1)[1] for c in comments if c.startswith('TextureFile')]
        tag = '%s %s' % (module, os.path.basename(path))
        scale = 1e-6 * max(1.0, float(np.max(np.abs(xyz))))
        if module == 'open3d':
            import open3d as o3d
            m = o3d.io.read_triangle_mesh(path, enable_post_processing=False)
            v = np.asarray(m.vertices)
            if kind == 'obj':      # Open3D numbers OBJ vertices in the order faces use them
                # (and parses them a float's last bit apart: two nearly
                # equal x may sort apart, so each is matched to its nearest)
                v, want = np.unique(v, axis=0), np.unique(xyz, axis=0)
                check(tag + ' vertices', same_points(v, want, scale), 'got %s, want %s' % (v.shape, want.shape))
            else:
                check(tag + ' vertices', close(v, xyz, scale), 'got %s, want %s' % (v.shape, xyz.shape))
            check(tag + ' triangles', len(m.triangles) == ntri, '%d, want %d' % (len(m.triangles), ntri))
            if kind == 'obj':
                check(tag + ' uvs and image', m.has_triangle_uvs() and len(m.textures) >= 1,
                      'uvs %s, %d textures' % (m.has_triangle_uvs(), len(m.textures)))
        elif module == 'pymeshlab':
            import pymeshlab
            ms = pymeshlab.MeshSet()
            ms.load_new_mesh(path)
            m = ms.current_mesh()
            v = m.vertex_matrix()
            nf = m.face_number()
            if kind == 'obj':     # MeshLab keeps OBJ vertices as they are used
                check(tag + ' vertices', m.vertex_number() >= len(xyz), str(m.vertex_number()))
            else:
                check(tag + ' vertices', close(v, xyz, scale), 'got %s, want %s' % (v.shape, xyz.shape))
            check(tag + ' faces', nf == (ntri if kind != 'wire' else 0), '%d, want %d' % (nf, ntri))
            tex = list(m.textures().keys())
            if kind == 'st':
                st = np.array([[r['s'], r['t']] for r in ref['vertex']])
                check(tag + ' s t', m.has_vertex_tex_coord() and close(m.vertex_tex_coord_matrix(), st, 1e-7),
                      'no vertex texture coordinates')
            if kind == 'corner':
                want = np.array([c for f in ref['face'] for c in zip(f['texcoord'][0::2], f['texcoord'][1::2])])
                check(tag + ' corner texcoords', m.has_wedge_tex_coord() and
                      close(m.wedge_tex_coord_matrix(), want, 1e-7), 'no wedge texture coordinates')
            if kind in ('st', 'corner', 'obj'):
                want = [os.path.basename(t) for t in textures]
                check(tag + ' textures', sorted(os.path.basename(t) for t in tex) == sorted(want),
                      'got %s, want %s' % (tex, want))
        elif module == 'trimesh':
            import trimesh
            if kind == 'wire':
                print('SKIP %s: trimesh 5 stacks every edge column (vertex1 vertex2 patch1 '
                      'patch2) and refuses the wireframe' % tag)
                continue
            t = trimesh.load(path, process=False)
            if kind == 'corner':      # trimesh splits the corners into vertices
                check(tag + ' triangles', len(t.faces) == ntri, '%d, want %d' % (len(t.faces), ntri))
            elif kind == 'obj' and 's' not in ref['vertex'][0]:
                check(tag + ' triangles', len(t.faces) == ntri, '%d, want %d' % (len(t.faces), ntri))
            elif kind == 'obj':
                check(tag + ' vertices', close(t.vertices, xyz, scale), 'got %s' % (t.vertices.shape,))
            else:
                check(tag + ' vertices', close(t.vertices, xyz, scale), 'got %s, want %s' % (t.vertices.shape, xyz.shape))
                check(tag + ' triangles', len(t.faces) == ntri, '%d, want %d' % (len(t.faces), ntri))
            if kind in ('st', 'obj'):
                uv = getattr(t.visual, 'uv', None)
                if 's' in ref['vertex'][0]:
                    st = np.array([[r['s'], r['t']] for r in ref['vertex']])
                    check(tag + ' uv', uv is not None and close(uv, st, 1e-6), 'no uv')
                else:              # texcoord per corner (viewtex): trimesh splits the vertices
                    check(tag + ' uv', uv is not None and len(uv) == len(t.vertices), 'no uv')
                img = getattr(getattr(t.visual, 'material', None), 'image', None)
                check(tag + ' image', img is not None, 'TextureFile image not loaded')
        elif module == 'bpy':
            import bpy
            if kind == 'wire':
                print('SKIP %s: Blender imports a PLY\'s faces, not its edge element' % tag)
                continue
            bpy.ops.wm.read_factory_settings(use_empty=True)
            if kind == 'obj':
                bpy.ops.wm.obj_import(filepath=os.path.abspath(path))
            else:
                bpy.ops.wm.ply_import(filepath=os.path.abspath(path))
            objs = [o for o in bpy.context.scene.objects if o.type == 'MESH']
            if not objs:
                check(tag + ' mesh', False, 'no mesh object')
                continue
            m = objs[0].data
            v = np.array([tuple(x.co) for x in m.vertices])
            if kind in ('obj', 'corner'):     # Blender splits an OBJ's vertices by use
                v, want = np.unique(v, axis=0), np.unique(xyz, axis=0)
            else:
                want = xyz
            check(tag + ' vertices', close(v, want, scale), 'got %s, want %s' % (v.shape, want.shape))
            check(tag + ' faces', len(m.polygons) == len(faces), '%d, want %d' % (len(m.polygons), len(faces)))
            if kind == 'obj':      # Blender ignores TextureFile in PLY, reads map_Kd
                imgs = [i for i in bpy.data.images if i.size[0] > 0]
                check(tag + ' uvs and image', len(m.uv_layers) >= 1 and len(imgs) >= 1,
                      '%d uv layers, %d images' % (len(m.uv_layers), len(imgs)))
        else:
            sys.exit('interop.py: unknown module ' + module)


main()
