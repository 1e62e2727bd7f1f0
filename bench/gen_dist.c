/* gen_dist - bench inputs for meshdist: a closed bumpy sphere (a UV grid
 * of N x 2N quads split into triangles, radius 1 with ripples of 5%) and,
 * with -p, the same vertices moved along random directions by 1% of the
 * mean edge length, the "points near the surface" a distance query meets
 * when comparing a mesh with a noisy copy of itself.  Binary PLY on stdout.
 *   gen_dist [-p] [N]        (default N 400: 319,202 vertices, 638,400 triangles)
 * And the reference meshdist is measured against: brute force, every
 * triangle of B for each of K vertices of A taken evenly; prints queries/s.
 *   gen_dist -b K A B */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geom/bvh.h"
#include "cli/cli.h"
#include "geom/geom.h"
#include "io/meshio.h"
#include "core/rng.h"

static void surface(double u, double v, double p[3])
{
	/* u in [0, 1]: pole to pole; v in [0, 1): around. */
	double th = M_PI * u, ph = 2 * M_PI * v;
	double r = 1 + 0.05 * sin(7 * th) * cos(5 * ph);
	p[0] = r * sin(th) * cos(ph);
	p[1] = r * sin(th) * sin(ph);
	p[2] = r * cos(th);
}

static int brute(int argc, char **argv)
{
	if (argc != 5)
		fct_usage_error("usage: gen_dist -b K A B");
	long k = fct_opt_long("K", argv[2], 1, 1000000);
	struct fct_mesh a, b;
	struct fct_err err;
	struct fct_bvh t;
	if (fct_mesh_read_file(&a, argv[3], NULL, &err) || fct_mesh_read_file(&b, argv[4], NULL, &err) ||
	    fct_bvh_build_mesh(&t, &b, &err))
		fct_die_err(&err);
	if (a.nv == 0 || t.ntri == 0)
		fct_die(1, "empty mesh");
	double t0 = fct_now(), sum = 0;
	for (long i = 0; i < k; i++) {
		struct fct_bvh_hit h;
		fct_bvh_closest_brute(&t, a.xyz + 3 * ((size_t)i * a.nv / (size_t)k), INFINITY, &h);
		sum += h.d2;
	}
	double dt = fct_now() - t0;
	printf("%.0f\n", dt > 0 ? (double)k / dt : 0);
	fct_report("sum_d2", "%.17g", sum);
	fct_bvh_free(&t);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
	return 0;
}

int main(int argc, char **argv)
{
	fct_cli_init("gen_dist");
	if (argc > 1 && !strcmp(argv[1], "-b"))
		return brute(argc, argv);
	int perturb = argc > 1 && !strcmp(argv[1], "-p");
	long n = argc > 1 + perturb ? fct_opt_long("N", argv[1 + perturb], 4, 4000) : 400;
	long m2 = 2 * n;
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	double p[3];
	/* Rows 1..n-1 are rings of m2 vertices; the poles are single vertices. */
	surface(0, 0, p);
	if (fct_mesh_add_vertex(&m, p[0], p[1], p[2], &err) < 0)
		fct_die_err(&err);
	for (long i = 1; i < n; i++)
		for (long j = 0; j < m2; j++) {
			surface((double)i / (double)n, (double)j / (double)m2, p);
			if (fct_mesh_add_vertex(&m, p[0], p[1], p[2], &err) < 0)
				fct_die_err(&err);
		}
	surface(1, 0, p);
	if (fct_mesh_add_vertex(&m, p[0], p[1], p[2], &err) < 0)
		fct_die_err(&err);
	uint32_t south = (uint32_t)(m.nv - 1);
#define RING(i, j) ((uint32_t)(1 + ((i) - 1) * m2 + ((j) % m2)))
	for (long j = 0; j < m2; j++) {
		uint32_t t[3] = {0, RING(1, j), RING(1, j + 1)};
		if (fct_mesh_add_face(&m, t, 3, &err) < 0)
			fct_die_err(&err);
	}
	for (long i = 1; i + 1 < n; i++)
		for (long j = 0; j < m2; j++) {
			uint32_t a = RING(i, j), b = RING(i, j + 1), c = RING(i + 1, j), d = RING(i + 1, j + 1);
			uint32_t t0[3] = {a, c, d}, t1[3] = {a, d, b};
			if (fct_mesh_add_face(&m, t0, 3, &err) < 0 || fct_mesh_add_face(&m, t1, 3, &err) < 0)
				fct_die_err(&err);
		}
	for (long j = 0; j < m2; j++) {
		uint32_t t[3] = {RING(n - 1, j), south, RING(n - 1, j + 1)};
		if (fct_mesh_add_face(&m, t, 3, &err) < 0)
			fct_die_err(&err);
	}
	if (perturb) {
		/* 1% of the mean edge length, over each face's three edges. */
		double sum = 0;
		for (size_t f = 0; f < m.nf; f++) {
			const uint32_t *v = m.fvert + m.fstart[f];
			for (int k = 0; k < 3; k++)
				sum += sqrt(fct_v3_dist2(m.xyz + 3 * (size_t)v[k], m.xyz + 3 * (size_t)v[(k + 1) % 3]));
		}
		double step = 0.01 * sum / (3.0 * (double)m.nf);
		struct fct_rng r;
		fct_rng_seed(&r, 42);
		for (size_t i = 0; i < 3 * m.nv; i++)
			m.xyz[i] += step * fct_rng_normal(&r) / sqrt(3.0);
	}
	if (fct_mesh_write_file(&m, NULL, 0, &err))
		fct_die_err(&err);
	fct_mesh_free(&m);
	return 0;
}
