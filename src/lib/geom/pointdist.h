/* pointdist.h - how far points lie from a mesh's surface: the distance of
 * each to its nearest face, summed up (Kang, Johnson and Szeliski, DEC CRL
 * 95/7, Table 1: a model's error against the dense mesh's vertices, as
 * planarize -v reports it). */
#ifndef FCT_POINTDIST_H
#define FCT_POINTDIST_H

#include <stddef.h>

#include "core/err.h"
#include "core/mesh.h"

struct fct_dist_stats {
	size_t count;           /* points measured */
	double mean, stdev;     /* the population standard deviation */
	double rms, max;        /* rms^2 = mean^2 + stdev^2 */
};

/* Distances summed up as they come, by Welford's update, which keeps the
 * variance exact when every distance is the same (a constant offset gives
 * stdev 0).  Zero-initialise. */
struct fct_dist_run {
	size_t count;
	double mean, m2, max;
};

static inline void fct_dist_run_add(struct fct_dist_run *r, double d)
{
	r->count++;
	double delta = d - r->mean;
	r->mean += delta / (double)r->count;
	r->m2 += delta * (d - r->mean);
	if (d > r->max)
		r->max = d;
}

/* The figures of r (all 0 when it has none). */
void fct_dist_run_stats(struct fct_dist_stats *st, const struct fct_dist_run *r);

/* The distances of the n points xyz (3 per point) to m's faces (polygons
 * fanned into triangles, fct_bvh_build_mesh), summed up by
 * fct_dist_run_add.  A mesh without faces
 * measures no point (count 0, all figures 0).  0, or -1 on error. */
int fct_point_distances(struct fct_dist_stats *st, const double *xyz, size_t n,
                        const struct fct_mesh *m, struct fct_err *err);

#endif
