/* test_delaunay - fct_delaunay against independent checks: every triangle
 * counter-clockwise (exact orient2d); every edge shared by at most two
 * triangles, twice in opposite directions when inner; the empty-circle
 * property by brute force (all triangles against all points) on small
 * inputs and edge by edge (locally Delaunay, which implies Delaunay) on
 * large ones; the border edges walking the convex hull, computed here by a
 * monotone chain, with the triangle areas summing to the hull's area; the
 * Euler count 2n - 2 - h; duplicates used once, by their lowest index; and
 * the degenerate inputs: regular grids (cocircular everywhere), integer
 * points on a circle, collinear sets, n < 3, clusters, points on the hull's
 * edges, tiny and huge coordinates, NaN and infinity. */
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "geom/delaunay.h"
#include "geom/predicates.h"
#include "core/rng.h"

static const double *P(const double *uv, uint32_t i)
{
	return uv + 2 * (size_t)i;
}

static int cmp_u64(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return (x > y) - (x < y);
}

static int cmp_lex(const void *a, const void *b)
{
	const double *p = a, *q = b;
	if (p[0] != q[0])
		return p[0] < q[0] ? -1 : 1;
	return (p[1] > q[1]) - (p[1] < q[1]);
}

struct pidx {
	double x, y;
	size_t i;
};

static int cmp_pidx(const void *a, const void *b)
{
	const struct pidx *p = a, *q = b;
	if (p->x != q->x)
		return p->x < q->x ? -1 : 1;
	if (p->y != q->y)
		return p->y < q->y ? -1 : 1;
	return (p->i > q->i) - (p->i < q->i);
}

/* Convex hull of the distinct points, strictly convex, counter-clockwise
 * (Andrew's monotone chain with exact turns).  Returns its vertex count;
 * h holds coordinates, room for 2n + 2 points. */
static size_t hull(const double *uv, size_t n, double *h)
{
	double *s = malloc(2 * n * sizeof *s + 16);
	memcpy(s, uv, 2 * n * sizeof *s);
	qsort(s, n, 2 * sizeof *s, cmp_lex);
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		while (k >= 2 && fct_orient2d(h + 2 * (k - 2), h + 2 * (k - 1), s + 2 * i) <= 0)
			k--;
		memcpy(h + 2 * k++, s + 2 * i, 2 * sizeof *h);
	}
	for (size_t i = n - 1, t = k + 1; i-- > 0;) {
		while (k >= t && fct_orient2d(h + 2 * (k - 2), h + 2 * (k - 1), s + 2 * i) <= 0)
			k--;
		memcpy(h + 2 * k++, s + 2 * i, 2 * sizeof *h);
	}
	free(s);
	return k > 1 ? k - 1 : k;
}

/* Is p on the closed segment ab (given collinear)? */
static int on_segment(const double *a, const double *b, const double *p)
{
	return fct_orient2d(a, b, p) == 0 &&
	       p[0] >= fmin(a[0], b[0]) && p[0] <= fmax(a[0], b[0]) &&
	       p[1] >= fmin(a[1], b[1]) && p[1] <= fmax(a[1], b[1]);
}

struct verdict {
	size_t ntri, ndup;
	int ok;                 /* every structural check passed */
};

enum { AREA_SKIP, AREA_EXACT, AREA_NEAR };

/* Run fct_delaunay and check everything that does not need O(n^2); with
 * brute set, also the empty circle of every triangle against every point.
 * area: AREA_EXACT when coordinates are small integers (areas exact in
 * double), AREA_NEAR for a relative 1e-9, AREA_SKIP where areas under- or
 * overflow. */
static struct verdict check_dt(const double *uv, size_t n, int brute, int area_check, const char *what)
{
	struct verdict v = {0, 0, 0};
	uint32_t *tri;
	size_t nt, ndup;
	struct fct_err err;
	if (fct_delaunay(&tri, &nt, &ndup, uv, n, &err)) {
		CHECK_MSG(0, "%s: %s", what, err.msg);
		return v;
	}
	v.ntri = nt;
	v.ndup = ndup;
	int bad = 0;

	/* vertices: in range, used points distinct, each used point the lowest
	 * index among its copies, every distinct point used */
	char *used = calloc(n + 1, 1);
	for (size_t t = 0; t < 3 * nt; t++) {
		if (tri[t] >= n) {
			bad++;
			continue;
		}
		used[tri[t]] = 1;
	}
	double *s = malloc((2 * n + 2) * sizeof *s);
	size_t nd = 0;
	if (n > 0) {
		/* distinct points with the lowest index of each, via a sort of
		 * (point, index) */
		struct pidx *q = malloc(n * sizeof *q);
		for (size_t i = 0; i < n; i++) {
			q[i].x = uv[2 * i];
			q[i].y = uv[2 * i + 1];
			q[i].i = i;
		}
		qsort(q, n, sizeof *q, cmp_pidx);
		for (size_t i = 0; i < n; i++) {
			int first = i == 0 || q[i].x != q[i - 1].x || q[i].y != q[i - 1].y;
			if (first) {
				s[2 * nd] = q[i].x;
				s[2 * nd + 1] = q[i].y;
				nd++;
			}
			if (nt > 0 && used[q[i].i] != first)
				bad++;
		}
		free(q);
	}
	if (ndup != n - nd)
		bad++;

	/* orientation, edges */
	uint64_t *e = malloc((3 * nt + 1) * sizeof *e);
	double area = 0;
	for (size_t t = 0; t < nt && !bad; t++) {
		const uint32_t *c = tri + 3 * t;
		if (!(c[0] < c[1] && c[0] < c[2]))
			bad++;   /* smallest index first */
		if (fct_orient2d(P(uv, c[0]), P(uv, c[1]), P(uv, c[2])) <= 0)
			bad++;
		for (int k = 0; k < 3; k++)
			e[3 * t + (size_t)k] = (uint64_t)c[k] << 32 | c[(k + 1) % 3];
		const double *a = P(uv, c[0]), *b = P(uv, c[1]), *cc = P(uv, c[2]);
		area += 0.5 * ((b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]));
	}
	if (bad) {
		CHECK_MSG(0, "%s: %d bad vertices or triangles", what, bad);
		goto out;
	}
	qsort(e, 3 * nt, sizeof *e, cmp_u64);
	size_t nborder = 0;
	for (size_t i = 0; i < 3 * nt; i++) {
		if (i > 0 && e[i] == e[i - 1])
			bad++;   /* a directed edge twice: overlapping triangles */
		uint64_t twin = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
		if (!bsearch(&twin, e, 3 * nt, sizeof *e, cmp_u64))
			nborder++;
	}
	/* locally Delaunay: for each directed inner edge a->b of triangle
	 * (a, b, c), the apex d of the triangle on the other side is not
	 * strictly inside the circle of (a, b, c) */
	for (size_t t = 0; t < nt; t++) {
		const uint32_t *c = tri + 3 * t;
		for (int k = 0; k < 3; k++) {
			uint32_t a = c[k], b = c[(k + 1) % 3], apex = c[(k + 2) % 3];
			uint64_t twin = (uint64_t)b << 32 | a;
			uint64_t *f = bsearch(&twin, e, 3 * nt, sizeof *e, cmp_u64);
			if (!f)
				continue;
			size_t o = (size_t)(f - e);
			const uint32_t *oc = tri + 3 * (o / 3);
			uint32_t d = oc[(o % 3 + 2) % 3];
			if (fct_incircle(P(uv, a), P(uv, b), P(uv, apex), P(uv, d)) > 0)
				bad++;
		}
	}
	if (bad) {
		CHECK_MSG(0, "%s: %d edges not locally Delaunay or repeated", what, bad);
		goto out;
	}
	/* border = convex hull: every border edge has every point on its left
	 * or on it, and the points on the hull's boundary are exactly the
	 * border's vertices (count h) */
	double *h = malloc((2 * nd + 4) * sizeof *h);
	size_t nh = nd ? hull(s, nd, h) : 0;
	if (nt > 0) {
		for (size_t i = 0; i < 3 * nt; i++) {
			uint64_t twin = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
			if (bsearch(&twin, e, 3 * nt, sizeof *e, cmp_u64))
				continue;
			uint32_t a = (uint32_t)(e[i] >> 32), b = (uint32_t)e[i];
			/* a border edge lies on a hull edge */
			int found = 0;
			for (size_t j = 0; j < nh && !found; j++) {
				const double *x = h + 2 * j, *y = h + 2 * ((j + 1) % nh);
				found = on_segment(x, y, P(uv, a)) && on_segment(x, y, P(uv, b));
			}
			if (!found)
				bad++;
		}
		size_t onb = 0;
		for (size_t i = 0; i < nd; i++)
			for (size_t j = 0; j < nh; j++)
				if (on_segment(h + 2 * j, h + 2 * ((j + 1) % nh), s + 2 * i)) {
					onb++;
					break;
				}
		if (nborder != onb)
			bad++;
		/* Euler: 2n - 2 - h for n distinct points, h on the boundary */
		if (nt != 2 * nd - 2 - onb)
			bad++;
		double harea = 0;
		for (size_t j = 0; j < nh; j++) {
			const double *x = h + 2 * j, *y = h + 2 * ((j + 1) % nh);
			harea += 0.5 * (x[0] * y[1] - x[1] * y[0]);
		}
		if (area_check == AREA_EXACT ? area != harea :
		    area_check == AREA_NEAR ? !(fabs(area - harea) <= 1e-9 * fabs(harea)) : 0)
			bad++;
		CHECK_MSG(!bad, "%s: hull, Euler count or area wrong (border %zu, ntri %zu, area %.17g vs %.17g)",
		          what, nborder, nt, area, harea);
	} else {
		/* no triangle: the distinct points must be collinear */
		for (size_t i = 2; i < nd; i++)
			if (fct_orient2d(s, s + 2, s + 2 * i) != 0)
				bad++;
		CHECK_MSG(!bad, "%s: no triangles for points not collinear", what);
	}
	free(h);
	if (brute && !bad) {
		for (size_t t = 0; t < nt; t++) {
			const uint32_t *c = tri + 3 * t;
			for (size_t i = 0; i < n; i++)
				if (fct_incircle(P(uv, c[0]), P(uv, c[1]), P(uv, c[2]), P(uv, (uint32_t)i)) > 0)
					bad++;
		}
		CHECK_MSG(!bad, "%s: %d points inside circumcircles", what, bad);
	}
	v.ok = !bad;
out:
	free(e);
	free(s);
	free(used);
	free(tri);
	return v;
}


/* The triangles of uv as a sorted list of coordinate triples, rotated to
 * start at the lexicographically smallest corner: comparable across inputs
 * that number the same points differently. */
struct ctri {
	double c[6];
};

static int cmp_ctri(const void *a, const void *b)
{
	const struct ctri *x = a, *y = b;
	for (int k = 0; k < 6; k++)
		if (x->c[k] != y->c[k])
			return x->c[k] < y->c[k] ? -1 : 1;
	return 0;
}

static struct ctri *canonical(const double *uv, size_t n, size_t *nt)
{
	uint32_t *tri;
	struct fct_err err;
	if (fct_delaunay(&tri, nt, NULL, uv, n, &err))
		return NULL;
	struct ctri *c = malloc((*nt + 1) * sizeof *c);
	for (size_t t = 0; t < *nt; t++) {
		int m = 0;
		for (int k = 1; k < 3; k++)
			if (cmp_lex(P(uv, tri[3 * t + k]), P(uv, tri[3 * t + m])) < 0)
				m = k;
		for (int k = 0; k < 3; k++) {
			const double *q = P(uv, tri[3 * t + (m + k) % 3]);
			c[t].c[2 * k] = q[0];
			c[t].c[2 * k + 1] = q[1];
		}
	}
	qsort(c, *nt, sizeof *c, cmp_ctri);
	free(tri);
	return c;
}

static double *random_points(size_t n, uint64_t seed, double scale)
{
	struct fct_rng r;
	fct_rng_seed(&r, seed);
	double *uv = malloc((2 * n + 2) * sizeof *uv);
	for (size_t i = 0; i < 2 * n; i++)
		uv[i] = fct_rng_uniform(&r) * scale;
	return uv;
}

static void test_small(void)
{
	double ccw[6] = {0, 0, 1, 0, 0, 1}, cw[6] = {0, 0, 0, 1, 1, 0};
	uint32_t *tri;
	size_t nt, nd;
	struct fct_err err;
	CHECK(fct_delaunay(&tri, &nt, &nd, ccw, 3, &err) == 0);
	CHECK_INT(nt, 1);
	CHECK_INT(nd, 0);
	CHECK(tri[0] == 0 && tri[1] == 1 && tri[2] == 2);
	free(tri);
	CHECK(fct_delaunay(&tri, &nt, NULL, cw, 3, &err) == 0);
	CHECK_INT(nt, 1);
	CHECK(tri[0] == 0 && tri[1] == 2 && tri[2] == 1);
	free(tri);
	/* image frame: u right, v down; (0,0) (0,1) (1,0) is "ccw" here */
	double img[6] = {10, 10, 10, 11, 11, 10};
	CHECK(fct_delaunay(&tri, &nt, NULL, img, 3, &err) == 0);
	CHECK(nt == 1 && tri[0] == 0 && tri[1] == 2 && tri[2] == 1);
	free(tri);

	/* n < 3, and no uv at all */
	for (size_t n = 0; n < 3; n++) {
		tri = NULL;
		CHECK(fct_delaunay(&tri, &nt, &nd, ccw, n, &err) == 0);
		CHECK_INT(nt, 0);
		CHECK_INT(nd, 0);
		CHECK(tri != NULL);
		free(tri);
	}
	CHECK(fct_delaunay(&tri, &nt, &nd, NULL, 0, &err) == 0 && nt == 0);
	free(tri);
	double two[4] = {1, 2, 1, 2};
	CHECK(fct_delaunay(&tri, &nt, &nd, two, 2, &err) == 0 && nt == 0 && nd == 1);
	free(tri);

	/* a square: cocircular, two triangles either way */
	double sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
	struct verdict v = check_dt(sq, 4, 1, AREA_EXACT, "square");
	CHECK(v.ok && v.ntri == 2);
	/* a triangle with a point on an edge, and one inside */
	double tp[10] = {0, 0, 4, 0, 0, 4, 2, 0, 1, 1};
	v = check_dt(tp, 5, 1, AREA_EXACT, "triangle with edge point");
	CHECK(v.ok && v.ntri == 4);   /* 2*5 - 2 - 4 */
}

static void test_degenerate_sets(void)
{
	uint32_t *tri;
	size_t nt, nd;
	struct fct_err err;
	/* collinear, with repeats: y = 3x + 1 */
	double line[200];
	for (int i = 0; i < 100; i++) {
		int x = (i * 37) % 60;   /* 60 distinct x, 40 repeats */
		line[2 * i] = x;
		line[2 * i + 1] = 3 * x + 1;
	}
	CHECK(fct_delaunay(&tri, &nt, &nd, line, 100, &err) == 0);
	CHECK_INT(nt, 0);
	CHECK_INT(nd, 40);
	free(tri);
	/* all the same point */
	double same[20];
	for (int i = 0; i < 20; i++)
		same[i] = i % 2 ? -0.0 : 2.5;
	same[3] = 0.0;   /* -0 and 0 are one value */
	CHECK(fct_delaunay(&tri, &nt, &nd, same, 10, &err) == 0);
	CHECK_INT(nt, 0);
	CHECK_INT(nd, 9);
	free(tri);
	/* collinear except one point, given last */
	double fan[2 * 51];
	for (int i = 0; i < 50; i++) {
		fan[2 * i] = i * 0.5;
		fan[2 * i + 1] = -i * 0.25;
	}
	fan[100] = 3;
	fan[101] = 7;
	struct verdict v = check_dt(fan, 51, 1, AREA_EXACT, "line and one point");
	CHECK(v.ok && v.ntri == 49);

	/* NaN and infinity are refused with the point's index */
	double bad[8] = {0, 0, 1, 0, 0, NAN, 1, 1};
	tri = (uint32_t *)bad;
	CHECK(fct_delaunay(&tri, &nt, &nd, bad, 4, &err) == -1);
	CHECK_STR(err.msg, "point 2: coordinate is not finite");
	CHECK(tri == NULL);
	bad[5] = 0;
	bad[6] = -INFINITY;
	CHECK(fct_delaunay(&tri, &nt, &nd, bad, 4, &err) == -1);
	CHECK_STR(err.msg, "point 3: coordinate is not finite");
}

static void test_grids(void)
{
	/* integer grid: every square's four corners are cocircular */
	enum { K = 40 };
	double *g = malloc(2 * K * K * sizeof *g);
	for (int i = 0; i < K * K; i++) {
		g[2 * i] = i % K;
		g[2 * i + 1] = i / K;
	}
	struct verdict v = check_dt(g, K * K, 1, AREA_EXACT, "grid 40x40");
	CHECK(v.ok);
	CHECK_INT(v.ntri, 2 * (K - 1) * (K - 1));
	free(g);
	/* a larger grid, spacing 0.1 (coordinates round), shifted: not exactly
	 * a grid any more, but nearly cocircular everywhere */
	enum { L = 150 };
	g = malloc(2 * L * L * sizeof *g);
	for (int i = 0; i < L * L; i++) {
		g[2 * i] = 1000 + (i % L) * 0.1;
		g[2 * i + 1] = -300 + (i / L) * 0.1;
	}
	v = check_dt(g, L * L, 0, AREA_NEAR, "grid 150x150 step 0.1");
	CHECK(v.ok);
	free(g);
	/* integer grid in image coordinates, 300 x 200, with a hole of
	 * missing points and every third row twice */
	size_t n = 0;
	g = malloc(2 * 300 * 300 * sizeof *g);
	for (int y = 0; y < 200; y++)
		for (int rep = 0; rep < (y % 3 == 0 ? 2 : 1); rep++)
			for (int x = 0; x < 300; x++) {
				if (x > 100 && x < 150 && y > 50 && y < 120)
					continue;
				g[2 * n] = x;
				g[2 * n + 1] = y;
				n++;
			}
	v = check_dt(g, n, 0, AREA_EXACT, "grid 300x200 with hole and repeats");
	CHECK(v.ok);
	size_t distinct = 300 * 200 - 49 * 69;
	CHECK_INT(v.ndup, n - distinct);
	CHECK_INT(v.ntri, 2 * distinct - 2 - 2 * (299 + 199));
	free(g);
}

static void test_circle(void)
{
	/* integer points on x^2 + y^2 = 1105^2: 108 of them, all cocircular */
	double c[2 * 110];
	size_t n = 0;
	for (long x = -1105; x <= 1105; x++) {
		long y2 = 1105L * 1105 - x * x, y = lround(sqrt((double)y2));
		if (y * y != y2)
			continue;
		c[2 * n] = (double)x;
		c[2 * n + 1] = (double)y;
		n++;
		if (y) {
			c[2 * n] = (double)x;
			c[2 * n + 1] = (double)-y;
			n++;
		}
	}
	CHECK_INT(n, 108);
	struct verdict v = check_dt(c, n, 1, AREA_EXACT, "circle");
	CHECK(v.ok && v.ntri == n - 2);
	c[2 * n] = 0;   /* and its centre */
	c[2 * n + 1] = 0;
	v = check_dt(c, n + 1, 1, AREA_EXACT, "circle and centre");
	CHECK(v.ok && v.ntri == n);
}

static void test_random(void)
{
	double *uv = random_points(2000, 1, 1.0);
	struct verdict v = check_dt(uv, 2000, 1, AREA_NEAR, "random 2000");
	CHECK(v.ok && v.ndup == 0);
	free(uv);
	uv = random_points(100000, 2, 640.0);
	v = check_dt(uv, 100000, 0, AREA_NEAR, "random 100000");
	CHECK(v.ok);
	/* deterministic: the same input twice gives the same array */
	uint32_t *t1, *t2;
	size_t n1, n2;
	struct fct_err err;
	CHECK(fct_delaunay(&t1, &n1, NULL, uv, 100000, &err) == 0);
	CHECK(fct_delaunay(&t2, &n2, NULL, uv, 100000, &err) == 0);
	CHECK(n1 == n2 && !memcmp(t1, t2, 3 * n1 * sizeof *t1));
	free(t1);
	free(t2);
	free(uv);
}

/* Duplicates: the first copy is used; in general position the Delaunay
 * triangulation is unique, so the triangles (as coordinates) equal those of
 * the input without copies, and those of a reversed input. */
static void test_duplicates(void)
{
	enum { N = 3000, D = 1500 };
	double *uv = random_points(N + D, 3, 100.0);
	struct fct_rng r;
	fct_rng_seed(&r, 4);
	for (size_t i = N; i < N + D; i++) {
		size_t j = fct_rng_below(&r, N);
		uv[2 * i] = uv[2 * j];
		uv[2 * i + 1] = uv[2 * j + 1];
		/* swap the copy to a random place, before or after the original */
		size_t k = fct_rng_below(&r, i + 1);
		for (int q = 0; q < 2; q++) {
			double t = uv[2 * i + q];
			uv[2 * i + q] = uv[2 * k + q];
			uv[2 * k + q] = t;
		}
	}
	struct verdict v = check_dt(uv, N + D, 0, AREA_NEAR, "random with copies");
	CHECK(v.ok);
	size_t na, nb, nc;
	struct ctri *a = canonical(uv, N + D, &na);
	double *base = random_points(N, 3, 100.0);
	struct ctri *b = canonical(base, N, &nb);
	double *rev = malloc(2 * N * sizeof *rev);
	for (size_t i = 0; i < N; i++) {
		rev[2 * i] = base[2 * (N - 1 - i)];
		rev[2 * i + 1] = base[2 * (N - 1 - i) + 1];
	}
	struct ctri *c = canonical(rev, N, &nc);
	CHECK(a && b && c);
	CHECK_INT(v.ndup, D);
	CHECK(a && b && na == nb && !memcmp(a, b, na * sizeof *a));
	CHECK(b && c && nb == nc && !memcmp(b, c, nb * sizeof *b));
	free(a);
	free(b);
	free(c);
	free(rev);
	free(base);
	free(uv);
}

static void test_clusters_and_borders(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 5);
	enum { C = 5, M = 1500, F = 20 };
	double *uv = malloc(2 * (C * M + F) * sizeof *uv);
	size_t n = 0;
	for (int c = 0; c < C; c++) {
		double cx = fct_rng_uniform(&r) * 1000, cy = fct_rng_uniform(&r) * 1000;
		for (int i = 0; i < M; i++) {
			uv[2 * n] = cx + 1e-7 * fct_rng_normal(&r);
			uv[2 * n + 1] = cy + 1e-7 * fct_rng_normal(&r);
			n++;
		}
	}
	for (int i = 0; i < F; i++) {
		uv[2 * n] = fct_rng_uniform(&r) * 1e6 - 5e5;
		uv[2 * n + 1] = fct_rng_uniform(&r) * 1e6 - 5e5;
		n++;
	}
	struct verdict v = check_dt(uv, n, 0, AREA_NEAR, "clusters");
	CHECK(v.ok);
	free(uv);

	/* the border of a 100 x 100 square every unit, and integer points
	 * inside: h = 400 */
	uv = malloc(2 * 1000 * sizeof *uv);
	n = 0;
	for (int i = 0; i < 100; i++) {
		double side[4][2] = {{i, 0}, {100, i}, {100 - i, 100}, {0, 100 - i}};
		for (int k = 0; k < 4; k++) {
			uv[2 * n] = side[k][0];
			uv[2 * n + 1] = side[k][1];
			n++;
		}
	}
	for (int i = 0; i < 500; i++) {
		uv[2 * n] = 1 + (double)fct_rng_below(&r, 99);
		uv[2 * n + 1] = 1 + (double)fct_rng_below(&r, 99);
		n++;
	}
	v = check_dt(uv, n, 1, AREA_EXACT, "square border and inside");
	CHECK(v.ok);
	CHECK_INT(v.ntri, 2 * (n - v.ndup) - 2 - 400);
	free(uv);
}

/* Near-degenerate: points on two lines with perturbations of 2^-40 of
 * their size, and nearly cocircular points (a circle evaluated in floating
 * point); the tiny and the huge (the predicates' big-integer stage). */
static void test_near_degenerate(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 6);
	enum { N = 1200 };
	double *uv = malloc(2 * N * sizeof *uv);
	for (int i = 0; i < N; i++) {
		double t = fct_rng_uniform(&r) * 100;
		int which = i % 3;
		double jitter = (fct_rng_uniform(&r) - 0.5) * ldexp(t + 1, -40) * (i % 2);
		uv[2 * i] = t;
		uv[2 * i + 1] = (which == 0 ? 0.3 * t : which == 1 ? 100 - 0.7 * t : 0.3 * t + 1e-9) + jitter;
	}
	struct verdict v = check_dt(uv, N, 1, AREA_NEAR, "near lines");
	CHECK(v.ok);
	for (int i = 0; i < N; i++) {
		double th = 2 * M_PI * fct_rng_uniform(&r);
		uv[2 * i] = 3.7 + 1e4 * cos(th);
		uv[2 * i + 1] = -1.1 + 1e4 * sin(th);
	}
	v = check_dt(uv, N, 1, AREA_NEAR, "near circle");
	CHECK(v.ok);
	free(uv);

	uv = random_points(300, 8, 1.0);
	for (int i = 0; i < 600; i++)
		uv[i] = ldexp(uv[i], -1000);   /* exact: stays normal */
	v = check_dt(uv, 300, 1, AREA_SKIP, "tiny");
	CHECK(v.ok);
	for (int i = 0; i < 600; i++)
		uv[i] = ldexp(uv[i], 1900);    /* 2^900 */
	v = check_dt(uv, 300, 1, AREA_SKIP, "huge");
	CHECK(v.ok);
	free(uv);
}

int main(void)
{
	test_small();
	test_degenerate_sets();
	test_grids();
	test_circle();
	test_random();
	test_duplicates();
	test_clusters_and_borders();
	test_near_degenerate();
	CHECK_DONE();
}
