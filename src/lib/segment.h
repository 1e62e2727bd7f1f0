/* segment.h - planar segmentation of a mesh by global region growing: Kang,
 * Johnson and Szeliski, "Extraction of Concise and Realistic 3-D Models from
 * Real Data" (DEC CRL 95/7), section 2, after Hebert et al. (1995).
 *
 * Every face starts as a patch; the two adjacent patches whose union is
 * fitted best by one plane are merged, and so on, until a stop criterion
 * holds.  Two faces are adjacent when they share an edge (around a
 * non-manifold edge shared by k faces, every pair of them when k <= 8,
 * otherwise each face and the next in index order); faces that share only
 * a vertex are not.
 *
 * The points of a patch, and how they are weighted.  By default each face
 * contributes its corners, one point per corner, all of weight 1: a vertex
 * shared by j faces of a patch counts j times (in a regular triangle grid an
 * interior vertex counts 6 times, a vertex on the patch's outline fewer).
 * This makes a patch's moments the plain sum of its faces' moments, so the
 * fit of a union is O(1).  With area weighting each face contributes the
 * exact second moments of its surface (a polygon as the fan of triangles
 * from its first corner): weight = area, so a region sampled twice as
 * densely does not pull the plane twice as hard (Kang et al. section 7).
 * A face of zero area then has no weight.
 *
 * The fit (eq. 1): the plane through the weighted centroid c whose normal is
 * the eigenvector of the smallest eigenvalue lambda of the scatter matrix
 * S = sum w (p - c)(p - c)^T; the patch's mean square residual is
 * ms = lambda / sum w and its rms is sqrt(ms).  Moments are kept central
 * (weight, centroid, scatter about the centroid) and combined with the
 * parallel-axis rule, so large coordinates lose no precision.
 *
 * Noise scale.  Each face f gets a local noise figure e_f: the smallest rms
 * of the union of f with one of its adjacent faces (a face and a neighbour
 * are four points, so that rms is zero on an exact plane and of the order of
 * the noise on a noisy one; taking the smallest of a face's neighbours keeps
 * it low on faces next to a crease).  E (E-bar, the paper's estimate of
 * noise and curvature) is the median of e_f over the faces that have a
 * neighbour.  The noise of a union U is the weighted mean square of its e_f,
 * pulled toward E by a prior of 8 average faces:
 *     nu^2(U) = (sum_U w_f e_f^2 + 8 w E^2) / (sum_U w_f + 8 w)
 * (w: the mean face weight), and never less than (1e-7 * the diagonal of
 * the mesh's bounding box)^2, so exact data (rounding only) still compares.
 * Because nu follows the data region by region, noise that grows with depth
 * (a Kinect's, sigma ~ z^2) is judged locally, not by one global figure.
 *
 * The merge cost of two patches is the ratio r^2 = ms(union) / nu^2(union),
 * dimensionless: the result is invariant to rotation, translation and
 * uniform scale of the input (apart from floating-point ties, which are
 * broken by face index).  The pairs wait in a priority queue with lazy
 * re-evaluation: a popped pair is costed again from the current patches and
 * pushed back when the cost grew; otherwise it is merged.  Patches are held
 * in a union-find, so a merge touches no adjacency list.  The cost of a union
 * can also fall as a part grows (it is a ratio of means, not a sum), so a
 * queued key is not always a lower bound; with the automatic criterion the
 * run therefore ends with sweeps that cost every remaining adjacent pair
 * afresh and merge again, until a sweep merges nothing.
 *
 * Stop criteria:
 *   target > 0      stop at that many patches (T_N of the paper);
 *   target == 0     automatic: stop when the cheapest merge has r > factor,
 *                   i.e. its rms exceeds factor times its noise nu (the
 *                   paper's threshold as a fraction of E, made local);
 *   max_rms         in both modes, a pair whose union has rms > max_rms is
 *                   never merged (a hard bound in the mesh's units).
 * Then, when min_faces > 1, a patch of fewer faces is absorbed into the
 * adjacent patch whose union with it has the smallest rms (specks left by
 * noise spikes), regardless of the criterion, but never across max_rms.
 *
 * Patches are numbered 0, 1, ... in the order of their smallest face index.
 * Each plane's normal points to the side the patch's faces face: it agrees
 * with the sum of the faces' vector areas (their winding). */
#ifndef FCT_SEGMENT_H
#define FCT_SEGMENT_H

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"
#include "planes.h"

/* The defaults of factor (the automatic criterion) and min_faces. */
#define FCT_SEGMENT_FACTOR 3.0
#define FCT_SEGMENT_MIN_FACES 8

struct fct_segment_params {
	long target;          /* T_N: stop at this many patches; 0: automatic */
	double factor;        /* automatic: merge while rms <= factor * nu */
	double max_rms;       /* never merge beyond this rms (HUGE_VAL: no bound) */
	int area_weighted;    /* 1: area-weighted surface moments; 0: corners */
	long min_faces;       /* absorb patches of fewer faces (0 or 1: none) */
	int use_viewpoint;    /* 1: the points were measured along rays from viewpoint */
	double viewpoint[3];
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
	double noise;         /* E: the median local noise e_f */
	double max_rms;       /* largest patch rms */
	double mean_rms;      /* patch rms averaged over faces */
	double last_ratio;    /* r of the last merge */
	double seconds;       /* wall-clock time of fct_segment */
};

/* target 0, factor FCT_SEGMENT_FACTOR, max_rms HUGE_VAL, corners, min_faces 0. */
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

/* The plane fitted to the scatter of weighted points: w (total weight),
 * centroid c, central scatter s = {sxx, syy, szz, sxy, syz, sxz}.  Writes the
 * unit normal (eigenvector of the smallest eigenvalue, by Jacobi rotations)
 * and d = -n.c into pl, and returns the smallest eigenvalue.  pl->count and
 * pl->rms are left alone.  A scatter of rank < 2 gives a normal all the
 * same (some unit vector orthogonal to its spread). */
double fct_plane_fit(struct fct_plane *pl, double w, const double c[3], const double s[6]);

/* The smallest eigenvalue of the symmetric positive semi-definite 3x3
 * matrix s = {sxx, syy, szz, sxy, syz, sxz}, 0 for a singular one: a root of
 * the characteristic polynomial, so its absolute error is of the order of
 * 1e-16 l1^2 / l2 (l1 >= l2 the other two eigenvalues); Jacobi rotations
 * when the eigenvalues are nearly equal. */
double fct_sym3_min_eigenvalue(const double s[6]);

#endif
