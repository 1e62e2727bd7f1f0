/* qem.h - triangle mesh decimation by quadric edge collapse: Garland and
 * Heckbert, "Surface Simplification Using Quadric Error Metrics", SIGGRAPH
 * 1997, with the area weighting and boundary constraint planes of Garland's
 * thesis (1999, sec. 3.3 and 4.1).  The baseline the planar pipeline of Kang
 * et al. is compared with (issue 4, item 6).
 *
 * Quadrics.  Every triangle contributes the quadric of its plane, weighted
 * by its area, to each of its three corners; every border edge (an edge of
 * one triangle) adds to both its ends the quadric of the plane through the
 * edge perpendicular to its triangle, weighted by border_weight times the
 * squared edge length, which holds the border in place except for sliding
 * along itself.  The cost of collapsing an edge (a, b) is Q(x) for the
 * quadric Q = Q_a + Q_b and the new position x: the solution of the 3x3
 * system grad Q = 0 when it is well posed (|det A| > 1e-9 trace(A)^3, and x
 * no farther from the edge's midpoint than the edge is long), otherwise the
 * best of the endpoints, the midpoint and the minimum of Q on the segment.
 * The endpoints are tried first and kept on ties, so vertices that need not
 * move keep their input coordinates bit for bit.  Positions are held
 * relative to the centre of the bounding box, so large coordinates lose no
 * precision in Q.
 *
 * The quadric distance of a collapse is the larger of sqrt(Qf(x) / W), Qf
 * the face-plane part of Q and W the area it carries (the area-weighted RMS
 * distance of x from the planes of the input faces the new vertex stands
 * for), and sqrt(Qb(x) / Wb) for the border planes and their weights (the
 * weighted RMS distance of x from the border lines it stands for).  When a
 * triangular hole is closed, the border planes of its corners that are no
 * longer on a border are dropped.
 *
 * Order.  Edges wait in an indexed 4-ary heap keyed by cost plus 1e-6 (W_a +
 * W_b) |b - a|^2, ties going to the lower vertex numbers, so the result is
 * the same on every run.  The small second term orders collapses that cost
 * nothing (on a plane, up to rounding) by size, so a plane is thinned
 * evenly rather than one vertex swallowing its neighbours in index order;
 * elsewhere it only reorders collapses whose distances to their planes are
 * within 1e-3 edge lengths of each other.  After a collapse the edges of the
 * kept vertex are costed again and moved in the heap, and the edges of the
 * removed vertex renamed or, where doubled, dropped.  A refused edge leaves
 * the heap until one of its ends changes.  When the heap runs dry before the
 * target, edges refused earlier may have become possible, so it is built
 * again from every edge, as long as the last pass collapsed anything (at
 * most 64 passes).
 *
 * A collapse is refused when
 *  - an end is locked: a vertex on a non-manifold edge (three or more
 *    triangles); locked vertices never move, so non-manifold edges stay as
 *    they were.  Vertices where fans of triangles meet (pinches) are not
 *    locked: the link condition keeps their fans apart;
 *  - it breaks the link condition (Dey, Edelsbrunner, Guha and Nekhayev
 *    1999): the vertices adjacent to both ends must be exactly the opposite
 *    corners of the edge's triangles, no two triangles may hang off both
 *    ends through them (which would fold a tetrahedron flat), an interior
 *    edge must not join two border vertices and a border triangle whose
 *    other two edges are border too is not collapsed (a component never
 *    vanishes).  With close_holes, a border edge of a triangular hole (the
 *    one other common neighbour h joined to both ends by border edges) may
 *    be collapsed, zipping the hole shut, unless triangles (a, c, h) and
 *    (b, c, h) would fold together; each such collapse changes the
 *    topology (one boundary loop fewer);
 *  - it turns a surviving triangle around it by 90 degrees or more, or
 *    leaves it with no area (|n| <= 1e-12 of its longest edge squared);
 *  - its ends hold more than 512 triangles between them (so no fan grows
 *    until every change to it costs its whole size);
 *  - it would take the face count below the target (so the result has the
 *    target count exactly, or one more when only interior collapses, which
 *    remove two triangles, remain: always so on a closed mesh, whose count
 *    is even);
 *  - its quadric distance exceeds max_error.
 *
 * Properties.  The vertex kept is the end nearer the new position (the
 * lower index on a tie), with its row of every property; float and double
 * scalar properties (s t, nx ny nz, confidence, ...) are then interpolated
 * along the edge at the projection of the new position (nx ny nz
 * renormalised), integer ones (red green blue, ...) and lists stay those of
 * the kept end.  A triangle that survives keeps its face row (a patch label,
 * say); faces of more than three corners are first fanned from their first
 * corner, each triangle with the face's row.  Triangles with a repeated
 * corner, and faces of fewer than three, are dropped first.  Vertices used
 * by no face are kept as they are.  Other elements are carried through,
 * except an `edge` element, whose vertex numbers would be stale, which is
 * removed.
 *
 * Held borders (hold_borders; the free-form surface of the planar model,
 * planemodel.h, whose borders are where the planes' polygons join it): a
 * vertex on no border edge is inside, on two a border vertex, on another
 * number (or flagged in corner) a corner.  A corner is never removed nor
 * moved; a border vertex is removed only along its border (into the other
 * end of a border edge), onto the best point of that edge (its ends, its
 * midpoint, the minimum along it), so a border's vertices stay a subset of
 * its samples, each where it was or on a segment between two of them; an
 * inside vertex goes as usual, or into a border vertex or corner.  With a
 * viewpoint (use_viewpoint), no triangle may turn to face the other way as
 * seen from it: one view's surface is a height field over its image.  The
 * border planes then measure a border's distance in units of border_tol
 * edge lengths (of the edge each plane came from): a border is known to a
 * sample, not to the depth's noise.
 *
 * Noise (sigma, one figure per vertex): each triangle's quadric is weighted
 * by 1 / sigma_t^2, so the quadric distance and max_error are in units of
 * the noise.  sigma_t^2 is its corners' mean sigma^2, or with a viewpoint
 * (the samples were measured along rays from it) the noise across the
 * triangle's plane, sigma^2 cos^2 a + l^2 sin^2 a for the angle a between
 * its normal and the ray to it and l its mean edge length: a depth sensor
 * measures along its rays, and across them a sample is known to a pixel's
 * footprint (so the steep faces of a crease or an occluding edge are not
 * held to the noise of the depth).
 *
 * Cost: O(F log F) time. */
#ifndef FCT_QEM_H
#define FCT_QEM_H

#include <stddef.h>

#include "core/err.h"
#include "core/mesh.h"

struct fct_qem_params {
	size_t target_faces;    /* stop at this many triangles (0: only max_error stops) */
	double max_error;       /* largest quadric distance of a collapse; <= 0: no bound */
	double border_weight;   /* weight of the border planes (default 1; 0: free borders) */
	int close_holes;        /* let collapses close triangular holes (default 0) */
	int hold_borders;       /* borders held (see above; default 0) */
	double border_tol;      /* held borders: distances in these many edge lengths (1) */
	const unsigned char *corner;   /* held borders: NULL, or 1 for vertices kept */
	const double *sigma;    /* NULL, or each vertex's noise (see above) */
	int use_viewpoint;      /* with sigma: the samples were measured along rays ... */
	double viewpoint[3];    /* ... from this point */
	int use_centre;         /* compute relative to centre, not the bounding box's centre, */
	double centre[3];       /* so that a piece of a mesh decimated alone (with its
	                         * vertices in the same order) gets the mesh's results bit for bit */
};

struct fct_qem_stats {
	size_t vertices_in, faces_in;   /* faces_in: triangles after fanning and dropping */
	size_t vertices_out, faces_out;
	size_t dropped;                 /* degenerate triangles dropped at the start */
	size_t locked;                  /* vertices locked as non-manifold */
	size_t collapses;
	size_t refused_topology;        /* link condition or border rules */
	size_t refused_flip;            /* a triangle would turn over or vanish */
	size_t refused_error;           /* beyond max_error */
	size_t last_refused[3];         /* topology, flip and error refused in the last pass (what
	                                 * one more pass, which would collapse nothing, refuses) */
	size_t passes;                  /* heap builds */
	size_t holes_closed;
	size_t corners;                 /* held borders: vertices kept as corners */
	double max_error;               /* largest quadric distance of a collapse done */
	double max_cost;                /* largest Q(x) of a collapse done (area x length^2) */
};

/* Defaults: no target, no error bound, border weight 1, holes kept. */
void fct_qem_params_default(struct fct_qem_params *p);

/* Decimate m in place (see above).  st (may be NULL) gets the figures.
 * Fails with -1 and a message on a vertex that is not finite
 * ("vertex N: coordinate is not finite"), out of memory, or more triangles
 * after fanning than 32-bit indices hold; m is then unchanged, unless
 * memory ran out while the result was being written into it. */
int fct_qem_decimate(struct fct_mesh *m, const struct fct_qem_params *p,
                     struct fct_qem_stats *st, struct fct_err *err);

/* The point fct_qem_decimate computes relative to without use_centre: the
 * centre of m's bounding box (the origin for no vertex).  Fails as it does
 * on a coordinate that is not finite. */
int fct_qem_centre(double centre[3], const struct fct_mesh *m, struct fct_err *err);

#endif
