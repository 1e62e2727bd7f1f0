/* test_bvh - the BVH's closest point equals brute force on thousands of
 * seeded random queries over random meshes (soups, noisy grids, degenerate
 * and pathological sets), the distances of hand-computed scenes (a cube and
 * its offset, a sphere above a plane).
 *
 * Its ray casts (fct_bvh_raycast): hand-computed hits, both sides, limits
 * and misses; watertightness (rays through shared edges and vertices of
 * closed meshes never escape); and agreement with brute force, hit for hit
 * and bit for bit, on thousands of seeded random rays over soups, height
 * fields and axis-parallel rays grazing box faces. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "check.h"
#include "geom/geom.h"
#include "core/rng.h"
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

/* Ray casts -------------------------------------------------------------- */

static void build_or_abort(struct fct_bvh *b, const struct soup *s)
{
	struct fct_err err;
	if (fct_bvh_build(b, s->xyz, s->tri, s->ntri, &err))
		abort();
}

/* Hand-computed cases on the triangle (0,0,0), (1,0,0), (0,1,0). */
static void test_ray_single(void)
{
	double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
	uint32_t tri[3] = {0, 1, 2};
	struct soup s = {xyz, tri, 3, 1};
	struct fct_bvh b;
	build_or_abort(&b, &s);
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
	build_or_abort(&b, &sl);
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
static void test_ray_watertight(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 21);
	double centre[3] = {0.3, -0.2, 0.1};
	struct soup s;
	make_sphere(&s, 5, centre);   /* 8192 triangles */
	struct fct_bvh b;
	build_or_abort(&b, &s);
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
static int compare_brute_rays(const struct soup *s, struct fct_rng *r, int n, int *hits)
{
	struct fct_bvh b;
	build_or_abort(&b, s);
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

static void test_ray_brute(void)
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
		CHECK_INT(compare_brute_rays(&s, &r, 4000, &hits), 0);
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
		CHECK_INT(compare_brute_rays(&s, &r, 6000, &hits), 0);
		CHECK_MSG(hits > 1000, "only %d hits", hits);
		soup_free(&s);
	}
}

/* A grid seen straight down through its vertices and edge midpoints: every
 * ray hits, at the exact height. */
static void test_ray_grid_exact(void)
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
	build_or_abort(&b, &s);
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
	test_soup();
	test_grid();
	test_pathological();
	test_limits();
	test_deterministic();
	test_cube();
	test_sphere_plane();
	test_fan();
	test_ray_single();
	test_ray_watertight();
	test_ray_brute();
	test_ray_grid_exact();
	CHECK_DONE();
}
