/* segmesh.h - segment a mesh as it travels on the pipe (segplanes,
 * planarize): fct_segment with what the mesh's header and properties say
 * about its data, the result stored back in the mesh.  Kang, Johnson and
 * Szeliski (DEC CRL 95/7), section 2. */
#ifndef FCT_SEGMESH_H
#define FCT_SEGMESH_H

#include "core/mesh.h"
#include "planar/segment.h"

/* Segment m (segment.h) with p, and with what m carries: a camera comment
 * makes the planes fitted along the rays from the camera's centre (the
 * pose's translation, else the origin) unless tls; without one, vertices
 * at bit-identical positions are merged first, the faces kept as they are
 * (fct_mesh_weld_exact: a triangle soup made one surface; stats->welded);
 * the vertex property
 * sigma (a scalar) gives every vertex's noise, overriding p->sigma.  Then m
 * gets the face property patch and the plane element (planes.h).  stats
 * may be NULL.  0, or -1 with a message: no faces (an empty mesh or a
 * point cloud), a malformed camera or pose comment, what fct_segment
 * refuses, lack of memory. */
int fct_segment_mesh(struct fct_mesh *m, const struct fct_segment_params *p, int tls,
                     struct fct_segment_stats *stats, struct fct_err *err);

#endif
