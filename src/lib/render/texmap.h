/* texmap.h - a mesh's texture mapping as one array of coordinates per
 * face corner, read from and written to the two forms facet writes:
 * texture coordinates per face corner (the face list property "float
 * texcoord", 2 numbers per corner, as MeshLab reads and writes PLY), or per
 * vertex (s t, as OBJ's matching v/vt indices and dm2mesh's PLY carry
 * them), the int face property texnumber choosing among the TextureFile
 * comments (MeshLab's convention; -1: untextured).  Coordinates are
 * DESIGN.md's: s right, t up, in [0, 1] over the image. */
#ifndef FCT_TEXMAP_H
#define FCT_TEXMAP_H

#include <stdint.h>

#include "core/mesh.h"

/* The texture coordinates of every face corner: *st (malloc'd, 2 floats
 * per corner, corner c of the face rows being m->fvert[c]) from the face
 * list texcoord when present, else from the vertices' s t (or another name
 * of texcoord.h); *texnum
 * (malloc'd, one per face) from texnumber, 0 for every face without it.
 * Returns 1, or 0 when the mesh has neither form (*st and *texnum NULL),
 * or -1: a texcoord list whose length is not twice its face's size, or
 * out of memory. */
int fct_texmap_corners(const struct fct_mesh *m, float **st, int32_t **texnum,
                       struct fct_err *err);

/* Give m the texture coordinates st (2 per corner, as above) and, when
 * texnum is not NULL, the face property texnumber.  per_face = 1: the face
 * list texcoord (replacing one there), vertex s t removed.  per_face = 0:
 * vertex s t; a vertex whose corners disagree is copied once per further
 * pair of coordinates it takes (the first keeps its index, copies go after
 * the vertices in the order of the corners, with every vertex property),
 * the faces renumbered; vertices no face uses get 0 0.  0 or -1 (out of
 * memory, past 2^32 - 1 vertices). */
int fct_texmap_set_corners(struct fct_mesh *m, const float *st, const int32_t *texnum,
                           int per_face, struct fct_err *err);

#endif
