/* delaunay.h - Delaunay triangulation of points in the plane, exact.
 *
 * Used by dm2mesh --points: Kang, Johnson, Szeliski (DEC CRL 95/7) section 2
 * connects sparse 3-D points by the Delaunay triangulation of their image
 * coordinates.
 *
 * Every decision is taken with the exact predicates of predicates.h, so the
 * result is a true Delaunay triangulation of the distinct input points for
 * any finite input: no input point lies strictly inside the circumcircle of
 * any output triangle, and the triangles cover the convex hull of the points
 * exactly (points on a hull edge are vertices of it).  Where four or more
 * points are cocircular (a regular grid) any of the Delaunay triangulations
 * may come out; which one is fixed by the input alone, so the same input
 * always gives the same triangles in the same order.
 *
 * Orientation: every triangle (a, b, c) has fct_orient2d(a, b, c) > 0, i.e.
 * it is counter-clockwise in a frame with u right and v UP.  In an image
 * frame (u right, v down) that is clockwise as drawn on screen.  For a
 * pinhole camera (x right, y down, z forward, DESIGN.md) whose pixel (u, v)
 * sees a point, (b - a) x (c - a) of the 3-D points then points along +z,
 * away from the camera, when the surface faces the camera; a mesh whose
 * faces should point toward the camera writes (a, c, b). */
#ifndef FCT_DELAUNAY_H
#define FCT_DELAUNAY_H

#include <stddef.h>
#include <stdint.h>

#include "core/err.h"

/* The most points fct_delaunay accepts (triangle corners must fit in 32 bits). */
#define FCT_DELAUNAY_MAX_POINTS ((size_t)700000000)

/* Triangulate the n points uv[2i], uv[2i+1] (i = 0 .. n-1).
 *
 * On success returns 0 and sets *tri to a malloc'd array of 3 * *ntri
 * point indices (free it with free()), each triangle counter-clockwise as
 * described above and listed with its smallest index first.  When all the
 * distinct points are collinear, or there are fewer than three, *ntri is 0
 * (and *tri an allocated empty array): that is success, not an error.
 *
 * Duplicate points (equal u and equal v; 0 and -0 are equal) are used once,
 * by the lowest index among them; the others appear in no triangle.  Their
 * count is stored in *nduplicates when it is not NULL.  For n distinct
 * points, h of them on the convex hull's boundary and not all collinear,
 * *ntri = 2n - 2 - h.
 *
 * Fails (returns -1, err set, *tri NULL) for a NaN or infinite coordinate
 * ("point 17: coordinate is not finite"), more than FCT_DELAUNAY_MAX_POINTS
 * points, or out of memory.  Memory is about 100 bytes per point.  Expected
 * time O(n log n): points are inserted in a biased randomized order (Amenta,
 * Choi, Rote 2003) sorted along a Hilbert curve within each round, each
 * found by a visibility walk from the previous one and inserted by
 * Bowyer-Watson cavity retriangulation. */
int fct_delaunay(uint32_t **tri, size_t *ntri, size_t *nduplicates, const double *uv, size_t n,
                 struct fct_err *err);

#endif
