/* pointdist.c - the distances of points to a mesh (see pointdist.h). */
#include "geom/pointdist.h"

#include <math.h>
#include <string.h>

#include "geom/bvh.h"

int fct_point_distances(struct fct_dist_stats *st, const double *xyz, size_t n,
                        const struct fct_mesh *m, struct fct_err *err)
{
	memset(st, 0, sizeof *st);
	struct fct_bvh tree;
	if (fct_bvh_build_mesh(&tree, m, err))
		return -1;
	double mean = 0, m2 = 0, max = 0;
	size_t count = 0;
	for (size_t i = 0; i < n && tree.ntri; i++) {
		struct fct_bvh_hit hit;
		if (!fct_bvh_closest(&tree, xyz + 3 * i, INFINITY, &hit))
			continue;
		double d = sqrt(hit.d2), delta = d - mean;
		count++;
		mean += delta / (double)count;
		m2 += delta * (d - mean);
		max = fmax(max, d);
	}
	fct_bvh_free(&tree);
	double var = count ? m2 / (double)count : 0;
	st->count = count;
	st->mean = mean;
	st->stdev = sqrt(var);
	st->rms = sqrt(mean * mean + var);
	st->max = max;
	return 0;
}
