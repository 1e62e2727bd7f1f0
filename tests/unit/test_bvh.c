/* test_bvh - the BVH's closest point equals brute force on thousands of
 * seeded random queries over random meshes (soups, noisy grids, degenerate
 * and pathological sets), the distances of hand-computed scenes (a cube and
 * its offset, a sphere above a plane). */
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "geom.h"
#include "rng.h"
#include "soup.h"

/* Helpers ------------------------------------------------------------------ */

/* Random queries in a box around [lo, hi]^3, half of them near vertices. */
static void random_query(struct fct_rng *r, const struct soup *s, double lo, double hi, double p[3])
{
	if (fct_rng_uniform(r) < 0.5) {
		const double *v = s->xyz + 3 * fct_rng_below(r, s->nv);
		for (int k = 0; k < 3; k++)
			p[k] = v[k] + 0.01 * (hi - lo) * fct_rng_normal(r);
	} else {
		for (int k = 0; k < 3; k++)
			p[k] = lo - 0.5 * (hi - lo) + 2 * (hi - lo) * fct_rng_uniform(r);
	}
}

/* Compare the tree with brute force on n queries; returns failures. */
static int compare_brute(const struct soup *s, struct fct_rng *r, int n, double lo, double hi)
{
	struct fct_bvh b;
	struct fct_err err;
	if (fct_bvh_build(&b, s->xyz, s->tri, s->ntri, &err)) {
		CHECK_MSG(0, "build: %s", err.msg);
		return 1;
	}
	CHECK(b.ntri == s->ntri);
	int bad = 0;
	for (int i = 0; i < n; i++) {
		double p[3];
		random_query(r, s, lo, hi, p);
		struct fct_bvh_hit h1, h2;
		int f1 = fct_bvh_closest(&b, p, INFINITY, &h1);
		int f2 = fct_bvh_closest_brute(&b, p, INFINITY, &h2);
		/* Ties may pick another triangle, never another distance. */
		if (!f1 || !f2 || fabs(h1.d2 - h2.d2) > 1e-12 * (1 + h2.d2) ||
		    fabs(fct_v3_dist2(p, h1.q) - h1.d2) > 1e-12 * (1 + h1.d2)) {
			if (bad++ < 5)
				CHECK_MSG(0, "query %d: tree %.17g, brute %.17g", i, h1.d2, h2.d2);
			continue;
		}
		/* The reported id names a triangle at that distance. */
		const uint32_t *t = s->tri + 3 * (size_t)h1.id;
		double q[3];
		double d2 = fct_closest_on_triangle(p, s->xyz + 3 * (size_t)t[0], s->xyz + 3 * (size_t)t[1],
		                                    s->xyz + 3 * (size_t)t[2], q, NULL);
		if (fabs(d2 - h1.d2) > 1e-12 * (1 + d2) && bad++ < 5)
			CHECK_MSG(0, "query %d: id %u is at %.17g, not %.17g", i, h1.id, d2, h1.d2);
	}
	CHECK_MSG(bad == 0, "%d of %d queries differ from brute force", bad, n);
	CHECK_MSG(b.depth < 128, "depth %d", b.depth);
	fct_bvh_free(&b);
	return bad;
}

/* BVH against brute force ---------------------------------------------------- */

static void test_soup(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 11);
	for (int round = 0; round < 3; round++) {
		size_t n = round == 0 ? 5 : round == 1 ? 300 : 3000;
		struct soup s;
		soup_alloc(&s, 3 * n, n);
		for (size_t i = 0; i < n; i++) {
			double c[3];
			for (int k = 0; k < 3; k++)
				c[k] = fct_rng_uniform(&r);
			for (int j = 0; j < 3; j++) {
				for (int k = 0; k < 3; k++)
					s.xyz[9 * i + 3 * j + k] = c[k] + 0.05 * fct_rng_normal(&r);
				s.tri[3 * i + j] = (uint32_t)(3 * i + j);
			}
		}
		compare_brute(&s, &r, 2000, 0, 1);
		soup_free(&s);
	}
}

/* A height field z = noise over an n x n grid: the typical scanned surface. */
static void test_grid(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 12);
	size_t n = 60;
	struct soup s;
	soup_alloc(&s, n * n, 2 * (n - 1) * (n - 1));
	for (size_t y = 0; y < n; y++)
		for (size_t x = 0; x < n; x++) {
			double *v = s.xyz + 3 * (y * n + x);
			v[0] = (double)x / (double)(n - 1);
			v[1] = (double)y / (double)(n - 1);
			v[2] = 0.01 * fct_rng_normal(&r);
		}
	size_t t = 0;
	for (size_t y = 0; y + 1 < n; y++)
		for (size_t x = 0; x + 1 < n; x++) {
			uint32_t a = (uint32_t)(y * n + x), b = a + 1, c = a + (uint32_t)n, d = c + 1;
			uint32_t q[6] = {a, b, d, a, d, c};
			memcpy(s.tri + 3 * t, q, sizeof q);
			t += 2;
		}
	compare_brute(&s, &r, 5000, 0, 1);
	soup_free(&s);
}

/* Degenerate and pathological sets: every triangle the same (no centroid
 * spread), many degenerate triangles, and sizes growing geometrically (SAH
 * splits off one triangle at a time; the depth must stay bounded). */
static void test_pathological(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 13);
	struct soup s;
	soup_alloc(&s, 3, 1000);
	double same[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
	memcpy(s.xyz, same, sizeof same);
	for (size_t i = 0; i < 1000; i++)
		s.tri[3 * i] = 0, s.tri[3 * i + 1] = 1, s.tri[3 * i + 2] = 2;
	compare_brute(&s, &r, 500, 0, 1);
	soup_free(&s);

	soup_alloc(&s, 400, 1000);
	for (size_t i = 0; i < 400; i++)
		for (int k = 0; k < 3; k++)   /* points on a few lines: many collinear triples */
			s.xyz[3 * i + k] = k == 0 ? (double)(i % 20) : (double)(i / 20 % 3);
	for (size_t i = 0; i < 1000; i++)
		for (int j = 0; j < 3; j++)
			s.tri[3 * i + j] = (uint32_t)(j == 2 && i % 3 == 0 ? s.tri[3 * i] : fct_rng_below(&r, 400));
	compare_brute(&s, &r, 3000, 0, 20);
	soup_free(&s);

	size_t n = 200;
	soup_alloc(&s, 3 * n, n);
	for (size_t i = 0; i < n; i++) {
		double x = pow(1.5, (double)i);
		double v[9] = {x, 0, 0, 2 * x, 0, 0, x, x, 0.5};
		memcpy(s.xyz + 9 * i, v, sizeof v);
		for (int j = 0; j < 3; j++)
			s.tri[3 * i + j] = (uint32_t)(3 * i + j);
	}
	struct fct_bvh b;
	struct fct_err err;
	CHECK(fct_bvh_build(&b, s.xyz, s.tri, n, &err) == 0);
	CHECK_MSG(b.depth <= 40 + 32, "depth %d", b.depth);
	int bad = 0;
	for (int i = 0; i < 2000; i++) {
		/* Near a random corner, scaled to its size: every scale is visited. */
		double p[3];
		const double *v = s.xyz + 3 * fct_rng_below(&r, s.nv);
		for (int k = 0; k < 3; k++)
			p[k] = v[k] * (1 + 0.1 * fct_rng_normal(&r));
		struct fct_bvh_hit h1, h2;
		fct_bvh_closest(&b, p, INFINITY, &h1);
		fct_bvh_closest_brute(&b, p, INFINITY, &h2);
		bad += fabs(h1.d2 - h2.d2) > 1e-12 * h2.d2;
	}
	fct_bvh_free(&b);
	CHECK_INT(bad, 0);
	soup_free(&s);
}

static void test_limits(void)
{
	struct fct_bvh b;
	struct fct_err err;
	struct fct_bvh_hit h;
	double p[3] = {0.25, 0.25, 2};
	/* No triangles: nothing is found, and freeing is safe. */
	CHECK(fct_bvh_build(&b, NULL, NULL, 0, &err) == 0);
	CHECK(fct_bvh_closest(&b, p, INFINITY, &h) == 0);
	fct_bvh_free(&b);
	fct_bvh_free(NULL);
	/* One triangle 2 below p: found within 2.0001, not within 2. */
	double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
	uint32_t tri[3] = {0, 1, 2};
	CHECK(fct_bvh_build(&b, xyz, tri, 1, &err) == 0);
	CHECK(fct_bvh_closest(&b, p, 4.0004, &h) == 1);
	CHECK_NEAR(h.d2, 4, 0);
	CHECK_INT(h.id, 0);
	CHECK(fct_bvh_closest(&b, p, 4, &h) == 0);
	/* So far away that the squared distance overflows: still an answer
	 * without a limit, none with one. */
	double far[3] = {1e300, 0, 0};
	CHECK(fct_bvh_closest(&b, far, INFINITY, &h) == 1);
	CHECK(isinf(h.d2));
	CHECK(fct_bvh_closest(&b, far, 1e308, &h) == 0);
	fct_bvh_free(&b);
	/* A corner that is not a number is refused with its index. */
	double bad[9] = {0, 0, 0, 1, NAN, 0, 0, 1, 0};
	CHECK(fct_bvh_build(&b, bad, tri, 1, &err) == -1);
	CHECK_STR(err.msg, "vertex 1: coordinate is not finite");
	CHECK(b.nodes == NULL && b.tris == NULL);
}

/* The same input gives the same tree, byte for byte. */
static void test_deterministic(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 14);
	struct soup s;
	soup_alloc(&s, 600, 2000);
	for (size_t i = 0; i < 3 * s.nv; i++)
		s.xyz[i] = fct_rng_uniform(&r);
	for (size_t i = 0; i < 3 * s.ntri; i++)
		s.tri[i] = (uint32_t)fct_rng_below(&r, s.nv);
	struct fct_bvh b1, b2;
	struct fct_err err;
	CHECK(fct_bvh_build(&b1, s.xyz, s.tri, s.ntri, &err) == 0);
	CHECK(fct_bvh_build(&b2, s.xyz, s.tri, s.ntri, &err) == 0);
	CHECK(b1.nnodes == b2.nnodes);
	CHECK(b1.nnodes >= 2 * s.ntri / 4 && b1.nnodes <= 2 * s.ntri);
	CHECK(!memcmp(b1.nodes, b2.nodes, sizeof *b1.nodes * b1.nnodes));
	CHECK(!memcmp(b1.tris, b2.tris, sizeof *b1.tris * b1.ntri));
	fct_bvh_free(&b1);
	fct_bvh_free(&b2);
	soup_free(&s);
}

/* Meshes --------------------------------------------------------------------- */

static void add_box(struct fct_mesh *m, double lo, double hi)
{
	struct fct_err err;
	for (int i = 0; i < 8; i++)
		fct_mesh_add_vertex(m, i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo, &err);
	static const uint32_t quads[6][4] = {
		{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}
	};
	for (int f = 0; f < 6; f++)
		fct_mesh_add_face(m, quads[f], 4, &err);
}

/* The unit cube against the cube offset outward by 0.1, [-0.1, 1.1]^3: every
 * corner of the unit cube is 0.1 from the nearest offset face, and every
 * corner of the offset cube is 0.1*sqrt(3) from the unit cube's corner. */
static void test_cube(void)
{
	struct fct_mesh a, b;
	struct fct_err err;
	fct_mesh_init(&a);
	fct_mesh_init(&b);
	add_box(&a, 0, 1);
	add_box(&b, -0.1, 1.1);
	struct fct_bvh ta, tb;
	CHECK(fct_bvh_build_mesh(&tb, &b, &err) == 0);
	CHECK(fct_bvh_build_mesh(&ta, &a, &err) == 0);
	CHECK_INT(tb.ntri, 12);
	for (size_t i = 0; i < 8; i++) {
		struct fct_bvh_hit h;
		CHECK(fct_bvh_closest(&tb, a.xyz + 3 * i, INFINITY, &h));
		CHECK_NEAR(sqrt(h.d2), 0.1, 1e-12);
		CHECK(h.id < 6);
		CHECK(fct_bvh_closest(&ta, b.xyz + 3 * i, INFINITY, &h));
		CHECK_NEAR(sqrt(h.d2), 0.1 * sqrt(3.0), 1e-12);
	}
	/* Points on the unit cube's faces are 0.1 from the offset cube too. */
	struct fct_rng r;
	fct_rng_seed(&r, 15);
	for (int i = 0; i < 1000; i++) {
		double p[3] = {fct_rng_uniform(&r), fct_rng_uniform(&r), fct_rng_uniform(&r)};
		p[i % 3] = (i / 3) % 2;
		struct fct_bvh_hit h;
		fct_bvh_closest(&tb, p, INFINITY, &h);
		if (fabs(sqrt(h.d2) - 0.1) > 1e-12) {
			CHECK_NEAR(sqrt(h.d2), 0.1, 1e-12);
			break;
		}
	}
	fct_bvh_free(&ta);
	fct_bvh_free(&tb);
	fct_mesh_free(&a);
	fct_mesh_free(&b);
}

/* Vertices of a latitude-longitude sphere of radius 1 centred 3 above the
 * plane z = 0: vertex i is z_i = 3 + cos(theta_i) from the plane, so with
 * latitudes symmetric about the equator the mean is 3, the maximum 4 (north
 * pole), the minimum 2, and the mean square 9 + mean(cos^2). */
static void test_sphere_plane(void)
{
	struct fct_mesh plane;
	struct fct_err err;
	fct_mesh_init(&plane);
	fct_mesh_add_vertex(&plane, -10, -10, 0, &err);
	fct_mesh_add_vertex(&plane, 10, -10, 0, &err);
	fct_mesh_add_vertex(&plane, 10, 10, 0, &err);
	fct_mesh_add_vertex(&plane, -10, 10, 0, &err);
	uint32_t quad[4] = {0, 1, 2, 3};
	fct_mesh_add_face(&plane, quad, 4, &err);
	struct fct_bvh t;
	CHECK(fct_bvh_build_mesh(&t, &plane, &err) == 0);
	int nlat = 17, nlon = 24, count = 0;
	double sum = 0, sum2 = 0, max = 0, min = INFINITY, cos2 = 0;
	for (int i = 0; i < nlat; i++) {
		double th = M_PI * i / (nlat - 1);
		for (int j = 0; j < nlon; j++) {
			double ph = 2 * M_PI * j / nlon;
			double p[3] = {sin(th) * cos(ph), sin(th) * sin(ph), 3 + cos(th)};
			struct fct_bvh_hit h;
			fct_bvh_closest(&t, p, INFINITY, &h);
			double d = sqrt(h.d2);
			sum += d;
			sum2 += d * d;
			max = fmax(max, d);
			min = fmin(min, d);
			cos2 += cos(th) * cos(th);
			count++;
		}
	}
	CHECK_NEAR(sum / count, 3, 1e-12);
	CHECK_NEAR(max, 4, 1e-15);
	CHECK_NEAR(min, 2, 1e-15);
	CHECK_NEAR(sum2 / count, 9 + cos2 / count, 1e-12);
	/* mean(cos^2) over the 17 latitudes pi*i/16: (17 + sum cos(2 pi i/16))/2 / 17
	 * = (17 + 1)/2 / 17 = 9/17, so the RMS distance is sqrt(9 + 9/17). */
	CHECK_NEAR(cos2 / count, 9.0 / 17, 1e-12);
	CHECK_NEAR(sqrt(sum2 / count), sqrt(9 + 9.0 / 17), 1e-12);
	fct_bvh_free(&t);
	fct_mesh_free(&plane);
}

static void test_fan(void)
{
	struct fct_mesh m;
	struct fct_err err;
	fct_mesh_init(&m);
	for (int i = 0; i < 6; i++)
		fct_mesh_add_vertex(&m, i, i * i, 0, &err);
	uint32_t pent[5] = {0, 1, 2, 3, 4}, tri[3] = {5, 4, 3};
	fct_mesh_add_face(&m, pent, 5, &err);
	fct_mesh_add_face(&m, tri, 3, &err);
	uint32_t *t, *face;
	size_t n;
	CHECK(fct_mesh_fan(&m, &t, &face, &n, &err) == 0);
	CHECK_INT(n, 4);
	static const uint32_t want[12] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 4, 3};
	static const uint32_t want_face[4] = {0, 0, 0, 1};
	CHECK(!memcmp(t, want, sizeof want));
	CHECK(!memcmp(face, want_face, sizeof want_face));
	free(t);
	free(face);
	fct_mesh_free(&m);
}

int main(void)
{
	test_soup();
	test_grid();
	test_pathological();
	test_limits();
	test_deterministic();
	test_cube();
	test_sphere_plane();
	test_fan();
	CHECK_DONE();
}
