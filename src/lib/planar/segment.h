/* segment.h - planar segmentation of a mesh by global region growing: Kang,
 * Johnson and Szeliski, "Extraction of Concise and Realistic 3-D Models from
 * Real Data" (DEC CRL 95/7), section 2 and eq. 1, after Hebert et al. (1995).
 *
 * Every face starts as a patch; the two adjacent patches whose union is
 * fitted best by one plane are merged, and so on, until a criterion stops
 * it.  Two faces are adjacent when they share an edge (around a non-manifold
 * edge of k faces, every pair of them when k <= 8, otherwise each face and
 * the next in index order); faces that share only a vertex are not.
 *
 * Noise.  Every bound is in units of the data's noise: each vertex's sigma
 * (the expected deviation of its position along its ray: dm2mesh's vertex
 * property from the sensor's noise model, noise.h), or, when the mesh has
 * none, the noise its data show (fct_noise_estimate_vertices: plane fits
 * over neighbourhoods of several rings, above any quantisation plateau), or
 * for a mesh too small to tell, the floor of exact data (1e-7 of its
 * bounding box's diagonal).  Never from one-ring residuals: quantised depth
 * comes in plateaus of equal depth, exact planes along the optical axis.
 *
 * Points and weights.  Each face contributes its corners, each weighted by
 * 1 / sigma^2 of its vertex (a vertex shared by j faces of a patch counts j
 * times), or with area weighting the exact moments of its surface weighted
 * by its corners' mean 1 / sigma^2 (section 7's uneven density).  A patch's
 * moments (weight, centroid, scatter about it, kept central and combined by
 * the parallel-axis rule) are then the sum of its faces', so the fit of a
 * union is O(1).  The fit (eq. 1): the plane through the weighted centroid
 * whose normal is the eigenvector of the least eigenvalue of the scatter;
 * that eigenvalue is the patch's chi^2, the sum of its points' squared
 * residuals in units of their noise, and chi^2 / n (n its corners) its mean.
 *
 * Phase 1, clusters.  Greedy merging by the chi^2 of the union, which can
 * only grow as a part grows, so a queued key is a lower bound: pop, cost
 * again, push back if it grew, else merge; the order is exactly greedy.  A
 * union is refused for good past 64 faces, past max_rms, or when its mean
 * chi^2 exceeds 2^2.
 *
 * Phase 2, patches.  The cost of merging patches a and b is how far, in
 * mean square and in units of the noise, the points of the smaller one
 * move from its own plane to the plane of the union:
 *     t = (chi^2(a u b) - chi^2(a) - chi^2(b)) / n_small,
 * and a union is made only while its mean chi^2 stays within fit^2 (its
 * points consistent with one plane and their noise: quantisation's
 * plateaus of a slanted wall included, whose staircase about the true
 * plane is what sigma's quantisation term is).  t is dimensionless: the
 * result does not change when the input is rotated, moved or scaled (up to
 * floating-point ties, broken by index).  It is not monotone, so the
 * queue's lazy re-evaluation is greedy up to stale keys; the automatic
 * criterion ends with sweeps that cost afresh every adjacent pair whose
 * patches changed, until one merges nothing.
 *
 * Stop criteria:
 *   target > 0     stop at that many patches (T_N of the paper), in either
 *                  phase (the fit test is not applied then);
 *   target == 0    automatic: stop when the cheapest merge has t > factor^2;
 *   max_rms        in both modes a union of rms above max_rms is never made
 *                  (a hard bound in the units of the coordinates);
 *   two-sided      without a viewpoint (use_viewpoint 0: a fused scan, a
 *                  mesh of another tool) no union of patches facing
 *                  opposite ways (their vector areas' dot product below
 *                  0) is made in either mode, and a face turned away from
 *                  its patch's plane is infinitely far from it (peeled,
 *                  never grown or settled into): both sides of a board
 *                  thinner than the noise fit one plane, and one patch of
 *                  both would fold over itself in it.  A view's mesh
 *                  faces its viewpoint but where noise flips a face.
 * Then, in the automatic mode and when min_faces > 1, each patch of fewer
 * faces is absorbed into the adjacent patch of at least min_faces faces
 * whose plane fits it best, while the union still passes the fit test and
 * its points move by at most max_dev sigma (mean square); the host's plane
 * is fitted again.
 *
 * The guarantee, and free-form faces.  Each patch's plane is fitted again
 * to its faces, and a face whose distance from it (its centroid's, each
 * corner in units of its sigma) exceeds max_dev leaves the patch: free-form
 * (label -1, no plane fits it within the noise), for two rounds.  Then the
 * patches grow back into the free-form faces their planes fit within
 * max_dev (region growing leaves faces along a crease to whichever side got
 * there first), and each face on a boundary between two patches moves to
 * the one whose plane it is nearer (so that boundaries run along the
 * planes' lines, not in teeth on either side).  A patch narrower than
 * min_extent sigma (a strip a few samples wide fits any plane and says
 * nothing of the surface), and one of fewer than min_faces faces when some
 * patch reaches that size (a curved surface cut into facets), is free-form
 * too.  Last, the planes are fitted again and the faces beyond max_dev
 * peeled, until a fit peels none (at most four times); the planes written
 * are those of the last fit.  So no face of a patch lies farther than
 * max_dev sigma from its plane.
 * * The queue is a radix heap with a prefetching front (see segment.c);
 * patches are a union-find, so no adjacency list is kept or merged and a
 * merge is O(1): the run is O(F log F) at worst, about a microsecond a face.
 *
 * Output.  Patches are numbered 0, 1, ... in the order of their smallest
 * face index; free-form faces are -1.  Each plane is the fit above, or,
 * when the points were measured along rays from a viewpoint (use_viewpoint),
 * the least-squares plane in inverse distance along those rays, each point
 * weighted by s^4 / sigma^2 (1/s has deviation sigma / s^2), which has no
 * error in the variables when the noise lies along the rays (the orthogonal
 * fit is then biased, by a degree and more for small far planes of a Kinect
 * frame).  Its normal points to the side the patch's faces face (the sum of
 * their vector areas); rms is the residual of its corners (metres); count is
 * the number of distinct vertices of the patch's faces. */
#ifndef FCT_SEGMENT_H
#define FCT_SEGMENT_H

#include <stddef.h>
#include <stdint.h>

#include "core/mesh.h"
#include "geom/planes.h"

/* The defaults of factor (the automatic criterion) and min_faces. */
#define FCT_SEGMENT_FACTOR 3.0
#define FCT_SEGMENT_FIT 1.5
#define FCT_SEGMENT_MAX_DEV 3.0
#define FCT_SEGMENT_MIN_EXTENT 10.0
#define FCT_SEGMENT_MIN_FACES 8

struct fct_segment_params {
	long target;          /* T_N: stop at this many patches; 0: automatic */
	double factor;        /* automatic: merge while t <= factor^2 (see above) */
	double fit;           /* a patch's mean squared residual stays within fit^2 sigma^2 */
	double max_dev;       /* no face farther than max_dev sigma from its plane (free-form) */
	double min_extent;    /* a patch narrower than min_extent sigma is free-form (0: none) */
	const double *sigma;  /* m->nv noise figures (metres; NULL: estimated from the data) */
	double max_rms;       /* never merge beyond this rms (HUGE_VAL: no bound) */
	int area_weighted;    /* 1: area-weighted surface moments; 0: corners */
	long min_faces;       /* absorb patches of fewer faces (0 or 1: none) */
	int use_viewpoint;    /* the points were measured along rays from ... */
	double viewpoint[3];  /* ... this point: fit the planes accordingly */
};

struct fct_segment_stats {
	size_t patches;       /* patches at the end */
	size_t adjacencies;   /* adjacent face pairs */
	size_t merges;        /* merges of the region growing, both phases */
	size_t clusters;      /* patches after phase 1 */
	size_t absorbed;      /* small patches absorbed afterwards */
	size_t evaluations;   /* union fits computed */
	size_t repushes;      /* pairs pushed back because their cost grew */
	size_t sweeps;        /* fresh passes after the first (automatic) */
	double noise;         /* the vertices' median sigma */
	double max_rms;       /* largest patch rms */
	double mean_rms;      /* patch rms averaged over faces */
	double last_ratio;    /* sqrt(t) of the last merge of phase 2 */
	int noise_estimated;  /* sigma was estimated from the data (noise.h) */
	size_t peeled;        /* faces that left their patch, farther than max_dev sigma */
	size_t grown;         /* free-form faces a neighbouring patch's plane took */
	size_t settled;       /* boundary faces moved to the nearer plane beside them */
	size_t narrow_faces;  /* faces of patches too narrow to be planes */
	size_t free_faces;    /* faces of no patch at the end (free-form) */
	double seconds;       /* wall-clock time of fct_segment */
	size_t welded;        /* fct_segment_mesh: vertices merged into others at their position */
};

/* target 0, factor FCT_SEGMENT_FACTOR, max_rms HUGE_VAL, corners,
 * min_faces FCT_SEGMENT_MIN_FACES, no viewpoint. */
void fct_segment_params_default(struct fct_segment_params *p);

/* Segment m into planar patches.  patch (m->nf entries, the caller's) gets
 * each face's label in [0, *nplanes); *planes gets a malloc'd array of the
 * patches' planes (count: the distinct vertices of the patch; rms as above),
 * to be freed by the caller; stats may be NULL.  A mesh without faces gives
 * no patches (*planes NULL).  Fails (returning -1, with nothing allocated)
 * on non-finite coordinates, more than INT32_MAX faces, or lack of memory. */
int fct_segment(int32_t *patch, struct fct_plane **planes, size_t *nplanes,
                const struct fct_mesh *m, const struct fct_segment_params *p,
                struct fct_segment_stats *stats, struct fct_err *err);

#endif
