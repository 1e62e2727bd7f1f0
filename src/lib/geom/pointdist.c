/* pointdist.c - the distances of points to a mesh (see pointdist.h). */
#include "geom/pointdist.h"

#include <math.h>
#include <string.h>

#include "geom/bvh.h"

void fct_dist_run_stats(struct fct_dist_stats *st, const struct fct_dist_run *r)
{
	double var = r->count ? r->m2 / (double)r->count : 0;
	st->count = r->count;
	st->mean = r->mean;
	st->stdev = sqrt(var);
	st->rms = sqrt(r->mean * r->mean + var);
	st->max = r->max;
}

int fct_point_distances(struct fct_dist_stats *st, const double *xyz, size_t n,
                        const struct fct_mesh *m, struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	struct fct_bvh tree;
	if (fct_bvh_build_mesh(&tree, m, err))
		return -1;
	struct fct_dist_run run = { 0 };
	for (size_t i = 0; i < n && tree.ntri; i++) {
		struct fct_bvh_hit hit;
		if (fct_bvh_closest(&tree, xyz + 3 * i, INFINITY, &hit))
			fct_dist_run_add(&run, sqrt(hit.d2));
	}
	fct_bvh_free(&tree);
	fct_dist_run_stats(st, &run);
	return 0;
}
