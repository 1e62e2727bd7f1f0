/* texcoord.h - a mesh's texture coordinates under the names other programs
 * write them, for the programs that draw or export a texture.
 *
 * Per vertex: s t (facet, Blender, trimesh), texture_u texture_v (MeshLab),
 * texture_s texture_t, u v; t (v) points up, as DESIGN.md's s t.  Per face
 * corner: the face list property texcoord, two numbers per corner in the
 * order of vertex_indices (MeshLab's wedge coordinates; cyl2planar's), the
 * face's texture chosen by an int face property texnumber (MeshLab's) among
 * the TextureFile comments.  The mesh keeps them under their own names;
 * only readers of texture coordinates look them up here. */
#ifndef FCT_TEXCOORD_H
#define FCT_TEXCOORD_H

#include "core/mesh.h"

/* The first pair of scalar vertex columns of the names above: 1 with *s
 * and *t set, 0 (both NULL) when there is none. */
int fct_texcoord_vertex(const struct fct_mesh *m, const struct fct_prop **s,
                        const struct fct_prop **t);

/* The face list texcoord when every face's list holds two numbers per
 * corner, or none (a face without texture); NULL otherwise. */
const struct fct_prop *fct_texcoord_face(const struct fct_mesh *m);

/* The same for any per-corner face list: the list called name when every
 * face's holds dim numbers per corner, or none; NULL otherwise (the OBJ
 * reader's corner_normal, 3 per corner). */
const struct fct_prop *fct_corner_list(const struct fct_mesh *m, const char *name, unsigned dim);

#endif
