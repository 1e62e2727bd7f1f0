/* planemodel.h - what the planar model makes of a segmentation before its
 * decimation (planedecim; qem.h's "Planes"): patches too small to be planes
 * become free-form, specks of free-form faces inside a patch join it, and
 * small holes inside a patch are filled in its plane.  Kang, Johnson and
 * Szeliski (DEC CRL 95/7) model the planes of a room; noise leaves specks
 * and holes in them that a concise model should not keep. */
#ifndef FCT_PLANEMODEL_H
#define FCT_PLANEMODEL_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "mesh.h"
#include "planes.h"

struct fct_tidy_stats {
	size_t small_faces;   /* faces of patches too small, made free-form */
	size_t speck_faces;   /* free-form faces of specks, given to the patch around them */
};

/* Tidy a segmentation for the planar model: patches of fewer than min_plane
 * faces become free-form (-1), too small to be worth a plane of their own;
 * then each piece of free-form faces (joined across edges) of fewer than
 * min_free faces whose only neighbouring patch is one patch joins it:
 * specks of outliers inside a plane, which the model puts on the plane.
 * patch: m->nf labels, changed in place. */
int fct_patches_tidy(int32_t *patch, const struct fct_mesh *m, size_t min_plane, size_t min_free,
                     struct fct_tidy_stats *st, struct fct_err *err);

/* Fill the holes of the mesh inside one patch: each border loop of at most
 * max_edges edges whose faces are all in one patch p >= 0 and which bounds
 * a hole (the loop, projected on p's plane, turns clockwise about its
 * normal, against the faces' winding) is triangulated in that plane
 * (fct_polytri, greedy) and the triangles appended to m as faces of patch
 * p.  *patch (m->nf labels, malloc'd) is grown to match.  Loops through a
 * vertex on more than one border loop, and loops the triangulation refuses
 * (self-crossing in the plane), are left open.  *filled gets the holes
 * filled; 0, or -1 out of memory. */
int fct_fill_plane_holes(struct fct_mesh *m, int32_t **patch, const struct fct_plane *planes,
                         size_t nplanes, size_t max_edges, size_t *filled, struct fct_err *err);

#endif
