/* delaunay_bench - time fct_delaunay on generated points, in process.
 *   delaunay_bench KIND N RUNS
 * KIND: uniform  N points uniform in a 4000 x 3000 image
 *       jgrid    a near-square grid of about N pixels, each moved by up to
 *                a quarter pixel (uniform), like detected features
 *       grid     the same grid exactly (every square cocircular: the
 *                predicates' exact stage on every tie)
 *       qsort    the reference: qsort of the N uniform points by (u, v)
 * Prints the median seconds over RUNS runs (%.4f) and the triangle count.
 * The points are generated once, outside the timing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "geom/delaunay.h"
#include "core/rng.h"

static int cmp_d(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

static int cmp_pt(const void *a, const void *b)
{
	const double *p = a, *q = b;
	if (p[0] != q[0])
		return p[0] < q[0] ? -1 : 1;
	return (p[1] > q[1]) - (p[1] < q[1]);
}

int main(int argc, char **argv)
{
	fct_cli_init("delaunay_bench");
	if (argc != 4)
		fct_usage_error("usage: delaunay_bench uniform|jgrid|grid|qsort N RUNS");
	const char *kind = argv[1];
	long n = fct_opt_long("N", argv[2], 3, 100000000);
	long runs = fct_opt_long("RUNS", argv[3], 1, 1000);
	struct fct_err err;
	double *uv = fct_alloc_array((size_t)n, 2 * sizeof *uv, &err);
	double *copy = uv ? fct_alloc_array((size_t)n, 2 * sizeof *copy, &err) : NULL;
	double *t = copy ? fct_alloc_array((size_t)runs, sizeof *t, &err) : NULL;
	if (!t)
		fct_die_err(&err);
	struct fct_rng r;
	fct_rng_seed(&r, 1);
	int grid = !strcmp(kind, "grid"), jgrid = !strcmp(kind, "jgrid");
	if (grid || jgrid) {
		long w = 1;
		while (w * w < n)
			w++;
		for (long i = 0; i < n; i++) {
			uv[2 * i] = (double)(i % w);
			uv[2 * i + 1] = (double)(i / w);
			if (jgrid) {
				uv[2 * i] += 0.5 * fct_rng_uniform(&r) - 0.25;
				uv[2 * i + 1] += 0.5 * fct_rng_uniform(&r) - 0.25;
			}
		}
	} else if (!strcmp(kind, "uniform") || !strcmp(kind, "qsort")) {
		for (long i = 0; i < n; i++) {
			uv[2 * i] = 4000 * fct_rng_uniform(&r);
			uv[2 * i + 1] = 3000 * fct_rng_uniform(&r);
		}
	} else {
		fct_usage_error("unknown KIND %s", kind);
	}
	size_t ntri = 0;
	for (long k = 0; k < runs; k++) {
		double t0 = fct_now();
		if (!strcmp(kind, "qsort")) {
			memcpy(copy, uv, (size_t)n * 2 * sizeof *uv);
			qsort(copy, (size_t)n, 2 * sizeof *copy, cmp_pt);
		} else {
			uint32_t *tri;
			if (fct_delaunay(&tri, &ntri, NULL, uv, (size_t)n, &err))
				fct_die_err(&err);
			free(tri);
		}
		t[k] = fct_now() - t0;
	}
	qsort(t, (size_t)runs, sizeof *t, cmp_d);
	printf("%.4f %zu\n", runs % 2 ? t[runs / 2] : 0.5 * (t[runs / 2 - 1] + t[runs / 2]), ntri);
	free(t);
	free(copy);
	free(uv);
	return 0;
}
