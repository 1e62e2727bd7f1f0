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
 * Points and weights.  By default each face contributes its corners, one
 * point of weight 1 per corner: a vertex shared by j faces of a patch
 * counts j times (in a regular triangle grid an interior vertex counts 6
 * times, a vertex on the patch's outline fewer).  A patch's moments are then
 * the plain sum of its faces', so the fit of a union is O(1).  With area
 * weighting each face contributes the exact moments of its surface (a
 * polygon as the fan of triangles from its first corner), weight = area, so
 * a region sampled twice as densely does not pull the plane twice as hard
 * (section 7); a face of zero area has no weight.
 *
 * The fit (eq. 1): the plane through the weighted centroid whose normal is
 * the eigenvector of the smallest eigenvalue of the scatter matrix
 * S = sum w (p - c)(p - c)^T; that eigenvalue is the patch's summed squared
 * residual sse, and its rms is sqrt(sse / sum w).  Moments are kept central
 * (weight, centroid, scatter about it) and combined by the parallel-axis
 * rule, so large coordinates lose no precision.
 *
 * Local noise.  For each face, the least mean square of its union with one
 * of its neighbours, then the least of that over the face and its
 * neighbours (a face across a crease, all of whose pairs fold, gets the
 * noise of the planes beside it): e_f^2, zero on exact planes.  Times 47
 * (the ratio of a typical pair's mean square to that statistic, measured on
 * noisy planes), its median over the faces is E^2: the paper's E-bar, the
 * scale of noise and curvature, reported as `noise`.  With a viewpoint (data
 * from a depth sensor), E^2 is at least 0.3 times the upper quartile of the
 * pairs' mean squares: sensors quantise depth, and the plateaus of equal
 * depth make most adjacent pairs exactly coplanar (60 to 70% of them in
 * TUM and 7-Scenes frames), which hides the noise from each face's least
 * pair but not from the quartile.
 *
 * Phase 1, clusters.  Greedy merging by the sse of the union, which can
 * only grow as a part grows, so a queued key is a lower bound: pop, cost
 * again, push back if it grew, else merge; the order is exactly greedy.
 * (A pair that is the least of both its faces' merges before anything
 * touches them, so those are merged in one pass first: the same result.)  A
 * union is refused for good past 64 faces, past max_rms, or when its mean
 * square exceeds 2^2 times the largest of E^2, the parts' own mean squares
 * and the lesser of the parts' mean e_f^2.  Each cluster's noise is then
 * nu^2 = (sse + 8 w e^2) / (w + 8 w) with w the mean face weight and e^2 the
 * cluster's mean e_f^2: its own residual at a scale where a plane is a
 * plane, leaning on the local figure while it is small.  Clusters follow
 * the noise where it varies (a Kinect's grows as depth squared).
 *
 * Phase 2, patches.  The cost of merging patches a and b is how far, in
 * mean square, the smaller one moves from its own plane to the plane of
 * the union, relative to the noise of the larger:
 *     t = (sse(a u b) - sse(a) - sse(b)) / (w_small nu_large^2),
 * nu^2 being the weighted mean of the patch's clusters' noise (and at
 * least (1e-7 times the bounding-box diagonal)^2, so exact data compare).
 * t is dimensionless: the result does not change when the input is
 * rotated, moved or scaled (up to floating-point ties, broken by index).
 * It is not monotone, so the queue's lazy re-evaluation (merge the popped
 * pair unless its cost grew) is greedy up to stale keys; the automatic
 * criterion therefore ends with sweeps that cost afresh every adjacent pair
 * whose patches changed, until one merges nothing.
 *
 * Stop criteria:
 *   target > 0     stop at that many patches (T_N of the paper), in either
 *                  phase;
 *   target == 0    automatic: stop when the cheapest merge has t > factor^2,
 *                  i.e. the smaller part would move by more than factor
 *                  times the noise (the paper's threshold as a multiple of
 *                  E-bar, made local);
 *   max_rms        in both modes a union of rms above max_rms is never made
 *                  (a hard bound in the units of the coordinates).
 * Then, in the automatic mode and when min_faces > 1, each patch of fewer
 * faces is absorbed into the adjacent patch of at least min_faces faces
 * that fits it best (least increase of sse, never past max_rms): specks of
 * noise and the faces across creases.  The host keeps its plane.  Small
 * patches next to small ones only, such as a cube's faces, stay.
 *
 * The queue is a radix heap with a prefetching front (see segment.c);
 * patches are a union-find, so no adjacency list is kept or merged and a
 * merge is O(1): the run is O(F log F) at worst, about a microsecond a face.
 *
 * Output.  Patches are numbered 0, 1, ... in the order of their smallest
 * face index.  Each plane is the fit above, or, when the points were
 * measured along rays from a viewpoint (use_viewpoint), the least-squares
 * plane in inverse distance along those rays, which has no error in the
 * variables when the noise lies along the rays (the orthogonal fit is then
 * biased, by a degree and more for small far planes of a Kinect frame).  Its
 * normal points to the side the patch's faces face (the sum of their vector
 * areas); rms is the residual of the points the plane was fitted to
 * (absorbed faces excluded); count is the number of distinct vertices of
 * the patch's faces. */
#ifndef FCT_SEGMENT_H
#define FCT_SEGMENT_H

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"
#include "planes.h"

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
	const double *sigma;  /* m->nv noise figures (metres; NULL: estimated E-bar) */
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
	double noise;         /* E-bar: sqrt(47 median e_f^2) */
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

/* The plane fitted to the scatter of weighted points: centroid c, central
 * scatter s = {sxx, syy, szz, sxy, syz, sxz}.  Writes the
 * unit normal (eigenvector of the smallest eigenvalue, by Jacobi rotations)
 * and d = -n.c into pl, and returns the smallest eigenvalue.  pl->count and
 * pl->rms are left alone.  A scatter of rank < 2 gives a normal all the
 * same (some unit vector orthogonal to its spread). */
double fct_plane_fit(struct fct_plane *pl, const double c[3], const double s[6]);

/* The smallest eigenvalue of the symmetric positive semi-definite 3x3
 * matrix s = {sxx, syy, szz, sxy, syz, sxz}, 0 for a singular one: a root of
 * the characteristic polynomial, so its absolute error is of the order of
 * 1e-16 l1^2 / l2 (l1 >= l2 the other two eigenvalues); Jacobi rotations
 * when the eigenvalues are nearly equal. */
double fct_sym3_min_eigenvalue(const double s[6]);

#endif
