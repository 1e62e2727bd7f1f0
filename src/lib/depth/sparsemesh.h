/* sparsemesh.h - sparse 3-D points with image coordinates (structure from
 * motion, stereo features) to a mesh: Kang et al. sec. 2 and 7 connect them
 * by the Delaunay triangulation of their image coordinates.
 *
 * Input, as text: one point per line, "u v x y z" (pixel coordinates, then
 * the point in the camera frame), blank lines and lines starting with '#'
 * ignored; or a PLY file whose vertex element has properties u v x y z. */
#ifndef FCT_SPARSEMESH_H
#define FCT_SPARSEMESH_H

#include <stdio.h>

#include "io/camera.h"
#include "core/mesh.h"

struct fct_image_points {
	size_t n;
	double *uv;              /* 2 per point */
	double *xyz;             /* 3 per point */
};

/* Read points from path ("-" or NULL: stdin) / from an open stream called
 * name.  0 or -1. */
int fct_image_points_read_file(struct fct_image_points *pts, const char *path,
                               struct fct_err *err);
int fct_image_points_read_stream(struct fct_image_points *pts, FILE *f, const char *name,
                                 struct fct_err *err);
void fct_image_points_free(struct fct_image_points *pts);

struct fct_sparse_params {
	/* An edge whose depth changes by more than max_jump times the footprint
	 * of its length in the image is a discontinuity (as in gridmesh.h; needs
	 * a camera for the footprint). */
	double max_jump;
	double max_edge;         /* drop faces with a longer 3-D edge */
};

/* What fct_sparse_mesh left out, for reports. */
struct fct_sparse_stats {
	size_t duplicates;       /* points at the image position of an earlier one */
	size_t jump_faces;       /* Delaunay faces cut as depth discontinuities */
	size_t long_faces;       /* ... cut for an edge longer than max_edge */
};

/* Triangulate: vertices are the points in input order (repeated image
 * positions keep their first point; the others stay unused), faces the
 * Delaunay triangles that pass the tests, facing the camera (the camera may
 * be of kind NONE: no jump test, no s t).  With a camera of known size, s t
 * from the image coordinates as in depthmesh.h.  stats may be NULL.  0 or -1. */
int fct_sparse_mesh(struct fct_mesh *m, const struct fct_image_points *pts,
                    const struct fct_camera *cam, const struct fct_sparse_params *p,
                    struct fct_sparse_stats *stats, struct fct_err *err);

#endif
