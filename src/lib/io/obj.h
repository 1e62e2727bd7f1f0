/* obj.h - Wavefront OBJ reader and writer.
 *
 * Reads v (with optional w, or with the common r g b extension), vt, vn, f
 * with v, v/vt, v//vn, v/vt/vn and negative (relative) indices, polygons of
 * any size (kept, not triangulated), g/o/s (ignored), usemtl/mtllib, line
 * continuations ("\" at a line's end; not in '#' comments, which end at
 * their line), '#' comments and a UTF-8 BOM; other statements (l, p, curv,
 * ...) are ignored.
 *
 * OBJ indexes positions, texture coordinates and normals separately; a
 * facet vertex is a position (its v line, in file order, used by a face or
 * not), never split by the vt / vn its corners name, since splitting would
 * disconnect the mesh (Blender's default export names a vn per face).
 * Where every position's corners name one vt (one vn) -- as files facet
 * writes, smooth-shaded exports and matching-index files do -- they become
 * vertex columns: vt float s t, vn float nx ny nz.  Where some position's
 * corners disagree, all faces carry them per corner instead, in the face's
 * vertex order: the face list "float texcoord" (2 per corner, MeshLab's
 * per-wedge texture coordinates) and "float corner_normal" (3 per corner);
 * a corner without one gets zeros.  v colours (0..1) become uchar red green
 * blue (rounded; a v without colour is black).  A position no face uses
 * takes vt / vn of its own index when the file has one per position; when
 * no face names a vn (or vt) at all and there is one per position, they are
 * taken by index for every vertex (point clouds).
 * Positions are float on disk (rounded to float) unless a coordinate has more
 * than 9 significant digits, which makes xyz_type double.
 *
 * mtllib/usemtl with a map_Kd (its last word, after any options) become
 * TextureFile comments, one per texture path in order of first use by a
 * face, unless the file already has a "# comment TextureFile" of that path.
 * An int face property texnumber (MeshLab's, -1 for faces without texture)
 * is added when one texture for all faces would be wrong: some face is
 * textured and some face is not on texture 0.  A material library that
 * cannot be opened is skipped.
 *
 * "# comment TEXT" and "# obj_info TEXT" lines become the mesh's comments,
 * so that camera, pose, TextureFile and provenance survive PLY -> OBJ -> PLY.
 * What OBJ cannot hold is lost on the way: other vertex and face properties
 * (confidence, patch, ...), other elements, and the double type of a
 * position that happens to print short.
 *
 * Errors: "FILE:LINE: what" (bad numbers, too few numbers, non-finite
 * positions, indices 0 or out of range, faces of fewer than 3 vertices, NUL
 * bytes or binary keywords), and "FILE: not a PLY or OBJ file (no vertex)"
 * for input without any v, binary junk before the first v included. */
#ifndef FCT_OBJ_H
#define FCT_OBJ_H

#include <stdio.h>

#include "core/mesh.h"
#include "io/reader.h"

/* Read an OBJ file into m (initialised by the caller; freed on failure).
 * dir is the folder that relative mtllib and TextureFile paths are resolved
 * against (map_Kd paths against the library's own folder), so that the
 * TextureFile paths are relative to the current folder (NULL: the current
 * folder).  Refuses input without any vertex. */
int fct_obj_read(struct fct_mesh *m, struct fct_reader *r, const char *dir, struct fct_err *err);

/* Write m as OBJ to f: "# facet", the comments as "# comment TEXT" /
 * "# obj_info TEXT", v (with r g b as float/255 when the mesh has uchar red
 * green blue), vt from the texture coordinates (texcoord.h: per face corner
 * from a face list texcoord, else one per vertex from s t or its other
 * names), vn from nx ny nz (per corner from a face list corner_normal), and
 * f with matching indices i/i/i.  Per-corner values are written once each,
 * in order of first use, and each corner names its own (f i/a/b), so that
 * what the reader made of an OBJ is written back as it was.  Numbers are
 * the shortest that read back to the same float (or double, for double
 * positions).  When m has texture coordinates and a TextureFile, a material
 * library is written to mtl (which may be NULL to skip it) and referred to
 * as mtl_name (a file name relative to the OBJ file; NULL writes no mtllib
 * or usemtl): one material_K per TextureFile with map_Kd the path
 * unchanged, faces choosing theirs by texnumber (an invalid texnumber uses
 * a material "untextured"). */
int fct_obj_write(const struct fct_mesh *m, FILE *f, const char *mtl_name, FILE *mtl,
                  struct fct_err *err);

/* Would fct_obj_write want a material library for m?  (Texture
 * coordinates, texcoord.h, and at least one TextureFile comment.) */
int fct_obj_wants_mtl(const struct fct_mesh *m);

#endif
