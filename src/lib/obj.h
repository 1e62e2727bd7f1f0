/* obj.h - Wavefront OBJ reader and writer.
 *
 * Reads v (with optional r g b), vt, vn, f with v, v/vt, v//vn, v/vt/vn and
 * negative (relative) indices, polygons, g/o/usemtl/mtllib.  OBJ indexes
 * positions, texture coordinates and normals separately; facet's meshes have
 * one index per vertex, so a position used with two different vt/vn becomes
 * two vertices (the first use keeps the position's own index, so a file that
 * uses matching indices -- as facet writes them -- keeps its vertex order and
 * count).  vt becomes vertex s t, vn becomes nx ny nz, vertex colours become
 * uchar red green blue.  mtllib/usemtl with a map_Kd become TextureFile
 * comments (one per textured material, in order of first use) and, when more
 * than one is used, an int face property texnumber. */
#ifndef FCT_OBJ_H
#define FCT_OBJ_H

#include <stdio.h>

#include "mesh.h"
#include "reader.h"

/* Read an OBJ file.  dir is the folder that relative mtllib and map_Kd paths
 * are resolved against, and TextureFile paths are given relative to (NULL
 * for the current folder).  Refuses input without any vertex. */
int fct_obj_read(struct fct_mesh *m, struct fct_reader *r, const char *dir, struct fct_err *err);

/* Write m as OBJ to f.  When m has s t and a TextureFile, a material library
 * is written to mtl (which may be NULL to skip it) and referred to as
 * mtl_name (a file name relative to the OBJ file); TextureFile paths are
 * written as map_Kd unchanged. */
int fct_obj_write(const struct fct_mesh *m, FILE *f, const char *mtl_name, FILE *mtl,
                  struct fct_err *err);

/* Would fct_obj_write want a material library for m? */
int fct_obj_wants_mtl(const struct fct_mesh *m);

#endif
