/* test_geom - closest points on segments and triangles against hand-computed
 * answers: every Voronoi region of a triangle, the same after a rigid motion,
 * and degenerate triangles (collinear, two or three corners equal, slivers);
 * fct_fmax against fmax's rules for NaN. */
#include <math.h>

#include <stdlib.h>

#include "check.h"
#include "geom/geom.h"

/* The triangle (0,0,0) (1,0,0) (0,1,0) in the plane z = 0. */
static const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0};

struct region_case {
	double p[3], q[3], d2;
	enum fct_tri_region region;
};

/* One point in each of the seven regions, with its closest point by hand. */
static const struct region_case cases[] = {
	{{-1, -1, 1}, {0, 0, 0}, 3, FCT_TRI_A},
	{{2, -1, 0}, {1, 0, 0}, 2, FCT_TRI_B},
	{{-1, 2, 0.5}, {0, 1, 0}, 2.25, FCT_TRI_C},
	{{0.25, -2, 3}, {0.25, 0, 0}, 13, FCT_TRI_AB},
	{{1, 1, -1}, {0.5, 0.5, 0}, 1.5, FCT_TRI_BC},         /* (1,1) onto x + y = 1 */
	{{-0.5, 0.25, 0}, {0, 0.25, 0}, 0.25, FCT_TRI_CA},
	{{0.25, 0.25, -2}, {0.25, 0.25, 0}, 4, FCT_TRI_FACE},
	{{0.2, 0.3, 0}, {0.2, 0.3, 0}, 0, FCT_TRI_FACE},      /* on the face */
	{{0.5, 0, 0}, {0.5, 0, 0}, 0, FCT_TRI_AB},            /* on an edge */
};

static void test_regions(void)
{
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		const struct region_case *c = &cases[i];
		double q[3];
		enum fct_tri_region r;
		double d2 = fct_closest_on_triangle(c->p, A, B, C, q, &r);
		CHECK_NEAR(d2, c->d2, 1e-15);
		CHECK_INT(r, c->region);
		for (int k = 0; k < 3; k++)
			CHECK_NEAR(q[k], c->q[k], 1e-15);
		/* The corner order must not matter for the distance. */
		CHECK_NEAR(fct_closest_on_triangle(c->p, B, C, A, q, NULL), c->d2, 1e-15);
		CHECK_NEAR(fct_closest_on_triangle(c->p, C, B, A, q, NULL), c->d2, 1e-15);
	}
}

/* A rigid motion: the cyclic permutation (x,y,z) -> (z,x,y), exact, then a
 * rotation by 30 degrees about z and a shift, which round.  Distances and
 * regions must survive it. */
static void move(const double x[3], double y[3])
{
	double c = sqrt(3.0) / 2, s = 0.5;
	double u[3] = {x[2], x[0], x[1]};
	y[0] = c * u[0] - s * u[1] + 10;
	y[1] = s * u[0] + c * u[1] - 3;
	y[2] = u[2] + 0.5;
}

static void test_moved(void)
{
	double a[3], b[3], c[3];
	move(A, a);
	move(B, b);
	move(C, c);
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		double p[3], q[3], want[3];
		enum fct_tri_region r;
		move(cases[i].p, p);
		move(cases[i].q, want);
		CHECK_NEAR(fct_closest_on_triangle(p, a, b, c, q, &r), cases[i].d2, 1e-12);
		CHECK_INT(r, cases[i].region);
		CHECK_NEAR(fct_v3_dist2(q, want), 0, 1e-24);
	}
}

static void test_segment(void)
{
	double a[3] = {1, 1, 1}, b[3] = {3, 1, 1}, q[3];
	double p1[3] = {2, 4, 5};   /* inside: (2,1,1), 9 + 16 */
	CHECK_NEAR(fct_closest_on_segment(p1, a, b, q), 25, 0);
	CHECK_NEAR(q[0], 2, 0);
	double p2[3] = {0, 1, 2};   /* before a: 1 + 1 */
	CHECK_NEAR(fct_closest_on_segment(p2, a, b, q), 2, 0);
	CHECK_NEAR(q[0], 1, 0);
	double p3[3] = {5, 0, 1};   /* past b: 4 + 1 */
	CHECK_NEAR(fct_closest_on_segment(p3, a, b, q), 5, 0);
	CHECK_NEAR(q[0], 3, 0);
	/* A segment of length zero is a point. */
	CHECK_NEAR(fct_closest_on_segment(p1, a, a, q), 1 + 9 + 16, 0);
	CHECK_NEAR(q[0] + q[1] + q[2], 3, 0);
}

static void test_degenerate(void)
{
	double q[3];
	enum fct_tri_region r;
	/* Collinear corners, the middle one last: the segment from 0 to 2. */
	double a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {1, 0, 0};
	CHECK(fct_triangle_degenerate(a, b, c));
	double p1[3] = {1.5, 1, 0};
	CHECK_NEAR(fct_closest_on_triangle(p1, a, b, c, q, &r), 1, 0);
	CHECK_INT(r, FCT_TRI_DEGENERATE);
	CHECK_NEAR(q[0], 1.5, 1e-15);
	double p2[3] = {3, 0, 1};
	CHECK_NEAR(fct_closest_on_triangle(p2, a, b, c, q, NULL), 2, 0);
	double p3[3] = {-1, 0, 0};
	CHECK_NEAR(fct_closest_on_triangle(p3, c, b, a, q, NULL), 1, 0);
	/* Two corners equal: the segment (0,0,0)-(0,0,2). */
	double z[3] = {0, 0, 2}, p4[3] = {1, 0, 1};
	CHECK(fct_triangle_degenerate(a, a, z));
	CHECK_NEAR(fct_closest_on_triangle(p4, a, a, z, q, NULL), 1, 0);
	CHECK_NEAR(q[2], 1, 1e-15);
	CHECK_NEAR(fct_closest_on_triangle(p4, z, a, a, q, NULL), 1, 0);
	/* Three corners equal: a point. */
	double o[3] = {1, 1, 1}, p5[3] = {1, 1, 3};
	CHECK(fct_triangle_degenerate(o, o, o));
	CHECK_NEAR(fct_closest_on_triangle(p5, o, o, o, q, &r), 4, 0);
	CHECK_INT(r, FCT_TRI_DEGENERATE);
	CHECK_NEAR(q[0] + q[1] + q[2], 3, 0);
	/* A sliver 1e-14 wide counts as its edges; the answer moves by < 1e-14. */
	double s[3] = {0.5, 1e-14, 0}, p6[3] = {0.5, 0.5, 0};
	double e[3] = {1, 0, 0};
	CHECK(fct_triangle_degenerate(a, e, s));
	CHECK_NEAR(fct_closest_on_triangle(p6, a, e, s, q, NULL), 0.25, 2e-14);
	/* A thin triangle 1e-6 wide is still a face: p lies right above it. */
	double t[3] = {0.5, 1e-6, 0}, p7[3] = {0.5, 0.5e-6, 1};
	CHECK(!fct_triangle_degenerate(a, e, t));
	CHECK_NEAR(fct_closest_on_triangle(p7, a, e, t, q, &r), 1, 1e-15);
	CHECK_INT(r, FCT_TRI_FACE);
}

/* fct_fmax is fmax: the larger, and a NaN gives way to the other operand. */
static void test_fmax(void)
{
	double nan = NAN;
	CHECK_NEAR(fct_fmax(2, 3), 3, 0);
	CHECK_NEAR(fct_fmax(3, 2), 3, 0);
	CHECK_NEAR(fct_fmax(nan, 1), 1, 0);
	CHECK_NEAR(fct_fmax(1, nan), 1, 0);
	CHECK(fct_fmax(nan, nan) != fct_fmax(nan, nan));
	CHECK(fct_fmax(-INFINITY, nan) == -INFINITY);
}

static void test_area(void)
{
	double a[3] = {1, 2, 3}, b[3] = {4, 2, 3}, c[3] = {1, 2, 7};   /* legs 3 and 4 */
	CHECK_NEAR(fct_triangle_area2(a, b, c), 12, 0);
	CHECK_NEAR(fct_triangle_area2(a, a, c), 0, 0);
	double x[3] = {1, 2, 0}, y[3] = {4, 5, 6}, r[3];
	fct_v3_cross(r, x, y);      /* (2*6 - 0*5, 0*4 - 1*6, 1*5 - 2*4) */
	CHECK_NEAR(r[0], 12, 0);
	CHECK_NEAR(r[1], -6, 0);
	CHECK_NEAR(r[2], -3, 0);
	CHECK_NEAR(fct_v3_dot(x, y), 14, 0);
}

/* fct_select_kth against a sort, on arrays with many ties and on runs
 * sorted either way (where a first-element pivot goes quadratic). */
static void test_select(void)
{
	enum { N = 301 };
	double a[N], b[N];
	unsigned x = 12345;
	for (int pass = 0; pass < 200; pass++) {
		size_t n = 1 + (size_t)pass % N;
		for (size_t i = 0; i < n; i++) {
			x = x * 1103515245u + 12345u;
			a[i] = pass % 3 == 0 ? (double)(x >> 28) : pass % 3 == 1 ? (double)i : -(double)i;
		}
		memcpy(b, a, n * sizeof *a);
		qsort(b, n, sizeof *b, fct_cmp_double);
		size_t k = (size_t)pass * 7 % n;
		double c[N];
		memcpy(c, a, n * sizeof *a);
		CHECK(fct_select_kth(c, n, k) == b[k]);
		memcpy(c, a, n * sizeof *a);
		CHECK(fct_select_kth(c, n, n / 2) == b[n / 2]);
	}
}

/* Squared distances from lines by hand: off a line along x, on its
 * extension beyond b, from a tilted line, and from a line whose two points
 * coincide (the distance from that point). */
static void test_line_distance(void)
{
	double a[3] = { 0, 0, 0 }, b[3] = { 2, 0, 0 }, p[3] = { 1, 3, 4 }, q[3] = { 5, 0, 0 };
	CHECK_NEAR(fct_v3_line_distance2(p, a, b), 25, 0);
	CHECK_NEAR(fct_v3_line_distance2(q, a, b), 0, 0);
	double c[3] = { 1, 1, 0 }, r[3] = { 1, 0, 0 };
	CHECK_NEAR(fct_v3_line_distance2(r, a, c), 0.5, 1e-15);
	CHECK_NEAR(fct_v3_line_distance2(p, b, b), 1 + 9 + 16, 0);
}

int main(void)
{
	test_line_distance();
	test_select();
	test_regions();
	test_moved();
	test_segment();
	test_degenerate();
	test_fmax();
	test_area();
	CHECK_DONE();
}
