/* test_raycast - the BVH's ray casts (fct_bvh_raycast): hand-computed hits,
 * both sides, limits and misses; watertightness (rays through shared edges
 * and vertices of closed meshes never escape); and agreement with brute
 * force, hit for hit and bit for bit, on thousands of seeded random rays
 * over soups, height fields and axis-parallel rays grazing box faces. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "geom.h"
#include "rng.h"
#include "soup.h"

static void build(struct fct_bvh *b, const struct soup *s)
{
	struct fct_err err;
	if (fct_bvh_build(b, s->xyz, s->tri, s->ntri, &err))
		abort();
}

/* Hand-computed cases on the triangle (0,0,0), (1,0,0), (0,1,0). */
static void test_single(void)
{
	double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
	uint32_t tri[3] = {0, 1, 2};
	struct soup s = {xyz, tri, 3, 1};
	struct fct_bvh b;
	build(&b, &s);
	struct fct_bvh_ray_hit h;
	double o[3] = {0.25, 0.125, 2}, down[3] = {0, 0, -1};
	CHECK(fct_bvh_raycast(&b, o, down, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 2, 0);
	CHECK_NEAR(h.u, 0.25, 1e-15);
	CHECK_NEAR(h.v, 0.125, 1e-15);
	CHECK_INT(h.id, 0);
	/* t is in units of |dir|. */
	double down2[3] = {0, 0, -4};
	CHECK(fct_bvh_raycast(&b, o, down2, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 0.5, 0);
	/* From below: both sides are hit. */
	double ob[3] = {0.25, 0.125, -3}, up[3] = {0, 0, 1};
	CHECK(fct_bvh_raycast(&b, ob, up, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 3, 0);
	/* An oblique ray: from (1, 1, 1) towards (0.2, 0.3, 0) hits at t = 1. */
	double oo[3] = {1, 1, 1}, dd[3] = {-0.8, -0.7, -1};
	CHECK(fct_bvh_raycast(&b, oo, dd, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 1, 1e-15);
	CHECK_NEAR(h.u, 0.2, 1e-15);
	CHECK_NEAR(h.v, 0.3, 1e-15);
	/* Limits: [tmin, tmax] is closed. */
	CHECK(fct_bvh_raycast(&b, o, down, 0, 2, &h) == 1);
	CHECK(fct_bvh_raycast(&b, o, down, 2, 2, &h) == 1);
	CHECK(fct_bvh_raycast(&b, o, down, 0, nextafter(2, 0), &h) == 0);
	CHECK(fct_bvh_raycast(&b, o, down, nextafter(2, 3), INFINITY, &h) == 0);
	CHECK(fct_bvh_raycast(&b, o, down, 3, 1, &h) == 0);
	/* Negative t: the hit behind the origin, when the range asks for it. */
	CHECK(fct_bvh_raycast(&b, o, up, -10, 0, &h) == 1);
	CHECK_NEAR(h.t, -2, 0);
	CHECK(fct_bvh_raycast(&b, o, up, -INFINITY, -2, &h) == 1);
	CHECK(fct_bvh_raycast(&b, o, up, -INFINITY, nextafter(-2, -3), &h) == 0);
	/* Misses: pointing away, outside the triangle, parallel to its plane
	 * (even inside it: seen edge-on it has no area), a bad direction. */
	CHECK(fct_bvh_raycast(&b, o, up, 0, INFINITY, &h) == 0);
	double o2[3] = {0.6, 0.6, 1};
	CHECK(fct_bvh_raycast(&b, o2, down, 0, INFINITY, &h) == 0);
	double oin[3] = {-1, 0.25, 0}, along[3] = {1, 0, 0};
	CHECK(fct_bvh_raycast(&b, oin, along, 0, INFINITY, &h) == 0);
	double zero[3] = {0, 0, 0}, nan[3] = {0, NAN, -1}, inf[3] = {0, 0, -INFINITY};
	CHECK(fct_bvh_raycast(&b, o, zero, 0, INFINITY, &h) == 0);
	CHECK(fct_bvh_raycast(&b, o, nan, 0, INFINITY, &h) == 0);
	CHECK(fct_bvh_raycast(&b, o, inf, 0, INFINITY, &h) == 0);
	CHECK(fct_bvh_raycast(&b, nan, down, 0, INFINITY, &h) == 0);
	CHECK(fct_bvh_raycast(&b, o, down, NAN, INFINITY, &h) == 0);
	/* Corners and edges of a lone triangle count as inside. */
	double corner[3] = {1, 0, 5}, edge[3] = {0.5, 0.5, 5};
	CHECK(fct_bvh_raycast(&b, corner, down, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 5, 0);
	CHECK(fct_bvh_raycast(&b, edge, down, 0, INFINITY, &h) == 1);
	CHECK_NEAR(h.t, 5, 0);
	CHECK_NEAR(h.u, 0.5, 0);
	CHECK_NEAR(h.v, 0.5, 0);
	fct_bvh_free(&b);

	/* A degenerate triangle is never hit; an empty tree neither. */
	double line[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
	struct soup sl = {line, tri, 3, 1};
	build(&b, &sl);
	double ol[3] = {0.5, 0, 1};
	CHECK(fct_bvh_raycast(&b, ol, down, 0, INFINITY, &h) == 0);
	fct_bvh_free(&b);
	CHECK(fct_bvh_build(&b, NULL, NULL, 0, NULL) == 0);
	CHECK(fct_bvh_raycast(&b, o, down, 0, INFINITY, &h) == 0);
	fct_bvh_free(&b);
}

/* A closed mesh: a geodesic sphere (an octahedron split n times, corners
 * pushed to the unit sphere) with random centre offset, all triangles
 * sharing exact corner coordinates. */
static void make_sphere(struct soup *s, int levels, const double centre[3])
{
	size_t ntri = 8, nv = 6;
	for (int l = 0; l < levels; l++)
		ntri *= 4;
	nv = 3 * ntri;   /* every triangle its own corners, copied exactly */
	soup_alloc(s, nv, ntri);
	double *t = malloc(sizeof *t * 9 * ntri), *u = malloc(sizeof *u * 9 * ntri);
	if (!t || !u)
		abort();
	static const double oct[8][9] = {
		{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 1, 0, -1, 0, 0, 0, 0, 1},
		{-1, 0, 0, 0, -1, 0, 0, 0, 1}, {0, -1, 0, 1, 0, 0, 0, 0, 1},
		{0, 1, 0, 1, 0, 0, 0, 0, -1}, {-1, 0, 0, 0, 1, 0, 0, 0, -1},
		{0, -1, 0, -1, 0, 0, 0, 0, -1}, {1, 0, 0, 0, -1, 0, 0, 0, -1},
	};
	memcpy(t, oct, sizeof oct);
	size_t n = 8;
	for (int l = 0; l < levels; l++) {
		for (size_t i = 0; i < n; i++) {
			const double *a = t + 9 * i, *b = a + 3, *c = a + 6;
			double ab[3], bc[3], ca[3];
			for (int k = 0; k < 3; k++) {
				ab[k] = 0.5 * (a[k] + b[k]);
				bc[k] = 0.5 * (b[k] + c[k]);
				ca[k] = 0.5 * (c[k] + a[k]);
			}
			/* Normalise the same way whichever triangle asks: the
			 * midpoint of (a, b) equals that of (b, a) exactly. */
			double *m[3] = {ab, bc, ca};
			for (int j = 0; j < 3; j++) {
				double r = sqrt(fct_v3_dot(m[j], m[j]));
				for (int k = 0; k < 3; k++)
					m[j][k] /= r;
			}
			double *o = u + 36 * i;
			memcpy(o, a, 24), memcpy(o + 3, ab, 24), memcpy(o + 6, ca, 24);
			memcpy(o + 9, ab, 24), memcpy(o + 12, b, 24), memcpy(o + 15, bc, 24);
			memcpy(o + 18, ca, 24), memcpy(o + 21, bc, 24), memcpy(o + 24, c, 24);
			memcpy(o + 27, ab, 24), memcpy(o + 30, bc, 24), memcpy(o + 33, ca, 24);
		}
		n *= 4;
		double *tmp = t;
		t = u;
		u = tmp;
	}
	for (size_t i = 0; i < 3 * ntri; i++) {
		for (int k = 0; k < 3; k++)
			s->xyz[3 * i + k] = t[3 * i + k] + centre[k];
		s->tri[i] = (uint32_t)i;
	}
	free(t);
	free(u);
}

/* Rays from inside a closed mesh never escape: aimed at random directions,
 * exactly at corners, and at points on shared edges. */
static void test_watertight(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 21);
	double centre[3] = {0.3, -0.2, 0.1};
	struct soup s;
	make_sphere(&s, 5, centre);   /* 8192 triangles */
	struct fct_bvh b;
	build(&b, &s);
	int escaped = 0, brute_differs = 0, total = 0;
	for (int i = 0; i < 60000; i++) {
		double o[3], target[3], d[3];
		for (int k = 0; k < 3; k++)
			o[k] = centre[k] + 0.5 * (fct_rng_uniform(&r) - 0.5);
		const double *v = s.xyz + 3 * fct_rng_below(&r, s.nv);
		const double *w = s.xyz + 3 * fct_rng_below(&r, s.nv);
		switch (i % 3) {
		case 0:   /* exactly at a corner, shared by 4 to 6 triangles */
			memcpy(target, v, sizeof target);
			break;
		case 1: { /* on an edge: the midpoint of a triangle's side */
			size_t t = fct_rng_below(&r, s.ntri), j = fct_rng_below(&r, 3);
			const double *a = s.xyz + 3 * (size_t)s.tri[3 * t + j];
			const double *c = s.xyz + 3 * (size_t)s.tri[3 * t + (j + 1) % 3];
			double f = fct_rng_uniform(&r);
			for (int k = 0; k < 3; k++)
				target[k] = a[k] + f * (c[k] - a[k]);
			break;
		}
		default:
			for (int k = 0; k < 3; k++)
				target[k] = w[k] + fct_rng_normal(&r);
		}
		fct_v3_sub(d, target, o);
		struct fct_bvh_ray_hit h1, h2;
		total++;
		int f1 = fct_bvh_raycast(&b, o, d, 0, INFINITY, &h1);
		int f2 = i % 20 ? f1 : fct_bvh_raycast_brute(&b, o, d, 0, INFINITY, &h2);
		if (i % 20)
			h2 = h1;
		escaped += !f1;
		if (f1 != f2 || (f1 && (h1.t != h2.t || h1.tri != h2.tri || h1.u != h2.u)))
			brute_differs++;
		if (f1) {
			/* The hit is on the sphere (to its flatness) and inside its triangle. */
			double p[3], q[3];
			fct_v3_axpy(p, o, h1.t, d);
			const struct fct_bvh_tri *t = &b.tris[h1.tri];
			double ww = 1 - h1.u - h1.v;
			for (int k = 0; k < 3; k++)
				q[k] = ww * t->a[k] + h1.u * t->b[k] + h1.v * t->c[k];
			if (fct_v3_dist2(p, q) > 1e-26 || h1.u < -1e-15 || h1.v < -1e-15 || ww < -1e-15)
				brute_differs++;
		}
	}
	CHECK_MSG(escaped == 0, "%d of %d rays escaped the closed sphere", escaped, total);
	CHECK_MSG(brute_differs == 0, "%d of %d rays differ from brute force", brute_differs, total);
	fct_bvh_free(&b);
	soup_free(&s);
}

/* Compare tree and brute force on n random rays aimed near the soup's
 * vertices (half) or anywhere (half), some of them axis-parallel from
 * origins on vertex coordinates (rays along box faces); returns differences. */
static int compare_brute(const struct soup *s, struct fct_rng *r, int n, int *hits)
{
	struct fct_bvh b;
	build(&b, s);
	int bad = 0;
	for (int i = 0; i < n; i++) {
		double o[3], d[3];
		const double *v = s->xyz + 3 * fct_rng_below(r, s->nv);
		for (int k = 0; k < 3; k++)
			o[k] = 4 * fct_rng_uniform(r) - 1.5;
		if (i % 4 == 3) {   /* axis-parallel, through a vertex's coordinates */
			int k = (int)fct_rng_below(r, 3);
			memcpy(o, v, sizeof o);
			o[k] = -2;
			d[0] = d[1] = d[2] = 0;
			d[k] = 1;
		} else if (i % 2) {
			for (int k = 0; k < 3; k++)
				d[k] = v[k] + 0.01 * fct_rng_normal(r) - o[k];
		} else {
			for (int k = 0; k < 3; k++)
				d[k] = fct_rng_normal(r);
		}
		double tmin = i % 5 == 0 ? 0.5 * fct_rng_uniform(r) : 0;
		double tmax = i % 7 == 0 ? 2 * fct_rng_uniform(r) : INFINITY;
		if (i % 11 == 0) {   /* backwards: a range of negative t */
			tmin = i % 2 ? -INFINITY : -3;
			tmax = -0.1 * fct_rng_uniform(r);
		}
		struct fct_bvh_ray_hit h1, h2;
		int f1 = fct_bvh_raycast(&b, o, d, tmin, tmax, &h1);
		int f2 = fct_bvh_raycast_brute(&b, o, d, tmin, tmax, &h2);
		*hits += f1;
		if (f1 != f2 || (f1 && (h1.t != h2.t || h1.id != h2.id || h1.tri != h2.tri ||
		                        h1.u != h2.u || h1.v != h2.v))) {
			if (bad++ < 5)
				CHECK_MSG(0, "ray %d: tree %d t %.17g id %u, brute %d t %.17g id %u", i, f1,
				          f1 ? h1.t : 0, f1 ? h1.id : 0, f2, f2 ? h2.t : 0, f2 ? h2.id : 0);
		}
	}
	fct_bvh_free(&b);
	return bad;
}

static void test_brute(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 22);
	/* Soups of small random triangles in the unit cube. */
	for (int round = 0; round < 3; round++) {
		size_t n = round == 0 ? 3 : round == 1 ? 200 : 4000;
		struct soup s;
		soup_alloc(&s, 3 * n, n);
		for (size_t i = 0; i < n; i++) {
			double c[3] = {fct_rng_uniform(&r), fct_rng_uniform(&r), fct_rng_uniform(&r)};
			for (int j = 0; j < 3; j++) {
				for (int k = 0; k < 3; k++)
					s.xyz[9 * i + 3 * j + k] = c[k] + 0.05 * fct_rng_normal(&r);
				s.tri[3 * i + j] = (uint32_t)(3 * i + j);
			}
		}
		int hits = 0;
		CHECK_INT(compare_brute(&s, &r, 4000, &hits), 0);
		CHECK_MSG(hits > 400, "only %d hits", hits);
		soup_free(&s);
	}
	/* A height field with shared edges, and axis-aligned grid triangles
	 * whose boxes are flat (rays along their faces). */
	for (int flat = 0; flat < 2; flat++) {
		size_t n = 50;
		struct soup s;
		soup_alloc(&s, n * n, 2 * (n - 1) * (n - 1));
		for (size_t y = 0; y < n; y++)
			for (size_t x = 0; x < n; x++) {
				double *v = s.xyz + 3 * (y * n + x);
				v[0] = (double)x / (double)(n - 1);
				v[1] = (double)y / (double)(n - 1);
				v[2] = flat ? 0.5 : 0.02 * fct_rng_normal(&r);
			}
		size_t t = 0;
		for (size_t y = 0; y + 1 < n; y++)
			for (size_t x = 0; x + 1 < n; x++) {
				uint32_t a = (uint32_t)(y * n + x), b = a + 1, c = a + (uint32_t)n, d = c + 1;
				uint32_t q[6] = {a, b, d, a, d, c};
				memcpy(s.tri + 3 * t, q, sizeof q);
				t += 2;
			}
		int hits = 0;
		CHECK_INT(compare_brute(&s, &r, 6000, &hits), 0);
		CHECK_MSG(hits > 1000, "only %d hits", hits);
		soup_free(&s);
	}
}

/* A grid seen straight down through its vertices and edge midpoints: every
 * ray hits, at the exact height. */
static void test_grid_exact(void)
{
	size_t n = 9;
	struct soup s;
	soup_alloc(&s, n * n, 2 * (n - 1) * (n - 1));
	for (size_t y = 0; y < n; y++)
		for (size_t x = 0; x < n; x++) {
			double *v = s.xyz + 3 * (y * n + x);
			v[0] = (double)x * 0.1, v[1] = (double)y * 0.1, v[2] = 1;
		}
	size_t t = 0;
	for (size_t y = 0; y + 1 < n; y++)
		for (size_t x = 0; x + 1 < n; x++) {
			uint32_t a = (uint32_t)(y * n + x), b = a + 1, c = a + (uint32_t)n, d = c + 1;
			uint32_t q[6] = {a, b, d, a, d, c};
			memcpy(s.tri + 3 * t, q, sizeof q);
			t += 2;
		}
	struct fct_bvh b;
	build(&b, &s);
	int missed = 0, wrong = 0;
	for (size_t y = 0; y < 2 * n - 1; y++)
		for (size_t x = 0; x < 2 * n - 1; x++) {
			double o[3] = {(double)x * 0.05, (double)y * 0.05, 3}, d[3] = {0, 0, -1};
			struct fct_bvh_ray_hit h;
			if (!fct_bvh_raycast(&b, o, d, 0, INFINITY, &h))
				missed++;
			else if (h.t != 2)
				wrong++;
			/* Slanted through the same point, inside the grid (on
			 * its border the rounded ray may pass just outside). */
			if (x == 0 || y == 0 || x == 2 * n - 2 || y == 2 * n - 2)
				continue;
			double d2[3] = {0.3, -0.2, -1}, o2[3] = {o[0] - 0.6, o[1] + 0.4, 3};
			if (!fct_bvh_raycast(&b, o2, d2, 0, INFINITY, &h))
				missed++;
			else if (fabs(h.t - 2) > 1e-15)
				wrong++;
		}
	CHECK_INT(missed, 0);
	CHECK_INT(wrong, 0);
	fct_bvh_free(&b);
	soup_free(&s);
}

int main(void)
{
	test_single();
	test_watertight();
	test_brute();
	test_grid_exact();
	CHECK_DONE();
}
