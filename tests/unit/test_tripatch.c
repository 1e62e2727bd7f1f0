/* test_tripatch - polytri and tripatch against independent checks.
 *
 * polytri: hand cases with known answers (the shorter diagonal of a convex
 * quadrilateral for the greedy method, the Delaunay one for --cdt; a square
 * with one and two square holes; an L; a hole touching the outer boundary at
 * a vertex); every result checked for n + 2h - 2 triangles, all
 * counter-clockwise, areas summing to the loops' area to 1e-12, no centroid
 * outside the region or in a hole, every edge used once per side with loop
 * edges on the region's side only; the greedy result equal, edge for edge,
 * to a brute-force run of the paper's pseudo-code (all O(n^2) segments,
 * sorted, each added unless it crosses one taken) on random star-shaped
 * polygons with holes; CDT edges locally Delaunay (empty circle across every
 * unconstrained edge); long boundaries (20000-vertex zig-zag strip, comb,
 * circle) within the candidate budget; non-simple loops refused, and cut
 * into ears by the repair.
 *
 * tripatch: wireframes built here: chaining of outer loops and holes,
 * orientation against the plane normal (also mirrored s t), the fallback
 * from non-simple s t to the plane, a patch touching itself at a vertex,
 * open chains, slits, and the bad inputs. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "planes.h"
#include "polytri.h"
#include "predicates.h"
#include "rng.h"
#include "tripatch.h"

/* A polygon under construction: points and loops. */
struct poly {
	double *xy;
	size_t np, npcap;
	uint32_t lstart[64];
	uint32_t *lv;
	size_t nl, nlv, lvcap;
};

static void poly_init(struct poly *p)
{
	memset(p, 0, sizeof *p);
}

static void poly_free(struct poly *p)
{
	free(p->xy), free(p->lv);
}

static uint32_t pt(struct poly *p, double x, double y)
{
	if (p->np == p->npcap) {
		p->npcap = p->npcap ? 2 * p->npcap : 64;
		p->xy = realloc(p->xy, 2 * p->npcap * sizeof *p->xy);
	}
	p->xy[2 * p->np] = x, p->xy[2 * p->np + 1] = y;
	return (uint32_t)p->np++;
}

static void lvadd(struct poly *p, uint32_t v)
{
	if (p->nlv == p->lvcap) {
		p->lvcap = p->lvcap ? 2 * p->lvcap : 64;
		p->lv = realloc(p->lv, p->lvcap * sizeof *p->lv);
	}
	p->lv[p->nlv++] = v;
}

/* Close the loop made of the vertices added since the last one. */
static void endloop(struct poly *p)
{
	p->lstart[++p->nl] = (uint32_t)p->nlv;
}

/* A loop of new points. */
static void loop_pts(struct poly *p, const double *c, size_t n)
{
	for (size_t i = 0; i < n; i++)
		lvadd(p, pt(p, c[2 * i], c[2 * i + 1]));
	endloop(p);
}

static int in_loop(const double *xy, const uint32_t *lv, size_t n, const double *q)
{
	int in = 0;
	for (size_t i = 0, j = n - 1; i < n; j = i++) {
		const double *a = &xy[2 * (size_t)lv[i]], *b = &xy[2 * (size_t)lv[j]];
		if ((a[1] > q[1]) != (b[1] > q[1]) && q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0])
			in = !in;
	}
	return in;
}

static int in_region(const struct poly *p, const double *q)
{
	int in = 0;
	for (size_t l = 0; l < p->nl; l++)
		in ^= in_loop(p->xy, p->lv + p->lstart[l], p->lstart[l + 1] - p->lstart[l], q);
	return in;
}

struct ekey {
	uint32_t a, b;   /* directed */
};

static int ekey_cmp(const void *x, const void *y)
{
	const struct ekey *p = x, *q = y;
	uint32_t pa = p->a < p->b ? p->a : p->b, pb = p->a < p->b ? p->b : p->a;
	uint32_t qa = q->a < q->b ? q->a : q->b, qb = q->a < q->b ? q->b : q->a;
	if (pa != qa)
		return pa < qa ? -1 : 1;
	if (pb != qb)
		return pb < qb ? -1 : 1;
	return p->a < q->a ? -1 : p->a > q->a;
}

static int is_loop_edge(const struct poly *p, uint32_t a, uint32_t b)
{
	for (size_t l = 0; l < p->nl; l++) {
		size_t s = p->lstart[l], n = p->lstart[l + 1] - s;
		for (size_t k = 0; k < n; k++)
			if (p->lv[s + k] == a && p->lv[s + (k + 1) % n] == b)
				return 1;
	}
	return 0;
}

/* Every property of a triangulation of p that does not depend on the
 * method; returns 1 when all hold (each is also a check). */
static int check_valid(const struct poly *p, const uint32_t *t, size_t nt, size_t want)
{
	int ok = 1;
	CHECK_INT(nt, want);
	ok &= nt == want;
	double at = 0, al = 0, aabs = 0;
	size_t bad_orient = 0, bad_centroid = 0;
	for (size_t k = 0; k < nt; k++) {
		const double *a = &p->xy[2 * (size_t)t[3 * k]], *b = &p->xy[2 * (size_t)t[3 * k + 1]],
		             *c = &p->xy[2 * (size_t)t[3 * k + 2]];
		bad_orient += !(fct_orient2d(a, b, c) > 0);
		double a2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
		at += a2, aabs += fabs(a2);
		double g[2] = { (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3 };
		bad_centroid += !in_region(p, g);
	}
	for (size_t l = 0; l < p->nl; l++)
		al += fct_polytri_loop_area2(p->xy, p->lv + p->lstart[l], p->lstart[l + 1] - p->lstart[l]);
	CHECK_INT(bad_orient, 0);
	CHECK_INT(bad_centroid, 0);
	CHECK_MSG(fabs(at - al) <= 1e-12 * aabs, "area %.17g vs loops %.17g", at / 2, al / 2);
	ok &= bad_orient == 0 && bad_centroid == 0 && fabs(at - al) <= 1e-12 * aabs;
	/* Edges: an inner edge twice, opposite ways; a loop edge once, its way. */
	struct ekey *e = malloc((3 * nt + 1) * sizeof *e);
	for (size_t k = 0; k < nt; k++)
		for (int q = 0; q < 3; q++)
			e[3 * k + q] = (struct ekey){ t[3 * k + q], t[3 * k + (q + 1) % 3] };
	qsort(e, 3 * nt, sizeof *e, ekey_cmp);
	size_t bad_edge = 0, loop_edges = 0;
	for (size_t k = 0; k < 3 * nt;) {
		size_t j = k + 1;
		while (j < 3 * nt && !ekey_cmp(&(struct ekey){ e[k].a < e[k].b ? e[k].a : e[k].b, e[k].a < e[k].b ? e[k].b : e[k].a },
		                               &(struct ekey){ e[j].a < e[j].b ? e[j].a : e[j].b, e[j].a < e[j].b ? e[j].b : e[j].a }))
			j++;
		if (j - k == 1) {
			bad_edge += !is_loop_edge(p, e[k].a, e[k].b);
			loop_edges++;
		} else if (j - k == 2) {
			bad_edge += e[k].a != e[k + 1].b || is_loop_edge(p, e[k].a, e[k].b) || is_loop_edge(p, e[k].b, e[k].a);
		} else {
			bad_edge++;
		}
		k = j;
	}
	free(e);
	CHECK_INT(bad_edge, 0);
	CHECK_INT(loop_edges, p->nlv);
	return ok && bad_edge == 0;
}

static size_t nholes(const struct poly *p)
{
	size_t h = 0;
	for (size_t l = 0; l < p->nl; l++)
		h += fct_polytri_loop_area2(p->xy, p->lv + p->lstart[l], p->lstart[l + 1] - p->lstart[l]) < 0;
	return h;
}

static int run(const struct poly *p, enum fct_polytri_method m, uint32_t **t, size_t *nt,
               struct fct_polytri_stats *st)
{
	struct fct_err err;
	err.msg[0] = 0;
	int rc = fct_polytri(t, nt, p->xy, p->np, p->lstart, p->nl, p->lv, m, st, &err);
	CHECK_MSG(rc == 0, "fct_polytri: %d: %s", rc, err.msg);
	return rc;
}

/* Unconstrained inner edges are locally Delaunay (hence the whole is the
 * constrained Delaunay triangulation). */
static size_t cdt_violations(const struct poly *p, const uint32_t *t, size_t nt)
{
	size_t bad = 0;
	for (size_t i = 0; i < nt; i++)
		for (int q = 0; q < 3; q++) {
			uint32_t a = t[3 * i + q], b = t[3 * i + (q + 1) % 3], c = t[3 * i + (q + 2) % 3];
			if (is_loop_edge(p, a, b) || is_loop_edge(p, b, a))
				continue;
			for (size_t j = 0; j < nt; j++)
				for (int r = 0; r < 3; r++)
					if (t[3 * j + r] == b && t[3 * j + (r + 1) % 3] == a) {
						uint32_t d = t[3 * j + (r + 2) % 3];
						bad += fct_incircle(&p->xy[2 * a], &p->xy[2 * b], &p->xy[2 * c], &p->xy[2 * d]) > 0;
					}
		}
	return bad;
}

/* The paper's pseudo-code, literally: every segment, minus those that
 * intersect the polygon or whose midpoint is outside, sorted by length
 * (ties by lower, then higher index), each added unless it crosses one
 * already taken.  Returns the n x n matrix of diagonals taken. */
static int proper_cross(const double *p, const double *q, const double *r, const double *s)
{
	double o1 = fct_orient2d(p, q, r), o2 = fct_orient2d(p, q, s);
	double o3 = fct_orient2d(r, s, p), o4 = fct_orient2d(r, s, q);
	return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

struct cand {
	double d2;
	uint32_t a, b;
};

static int cand_cmp(const void *x, const void *y)
{
	const struct cand *p = x, *q = y;
	if (p->d2 != q->d2)
		return p->d2 < q->d2 ? -1 : 1;
	if (p->a != q->a)
		return p->a < q->a ? -1 : 1;
	return (p->b > q->b) - (p->b < q->b);
}

static uint8_t *brute_greedy(const struct poly *p)
{
	size_t n = p->np;
	uint8_t *taken = calloc(n * n, 1);
	struct cand *c = malloc(n * n * sizeof *c);
	size_t nc = 0;
	for (uint32_t i = 0; i < n; i++)
		for (uint32_t j = i + 1; j < n; j++) {
			if (is_loop_edge(p, i, j) || is_loop_edge(p, j, i))
				continue;
			const double *a = &p->xy[2 * i], *b = &p->xy[2 * j];
			int ok = 1;
			for (size_t l = 0; l < p->nl && ok; l++) {
				size_t s = p->lstart[l], m = p->lstart[l + 1] - s;
				for (size_t k = 0; k < m && ok; k++) {
					uint32_t u = p->lv[s + k], v = p->lv[s + (k + 1) % m];
					if (u != i && u != j && v != i && v != j &&
					    proper_cross(a, b, &p->xy[2 * u], &p->xy[2 * v]))
						ok = 0;
				}
			}
			for (uint32_t k = 0; k < n && ok; k++) {
				if (k == i || k == j)
					continue;
				const double *q = &p->xy[2 * k];
				if (fct_orient2d(a, b, q) == 0 && (q[0] - a[0]) * (q[0] - b[0]) + (q[1] - a[1]) * (q[1] - b[1]) < 0)
					ok = 0;
			}
			double mid[2] = { (a[0] + b[0]) / 2, (a[1] + b[1]) / 2 };
			if (ok && in_region(p, mid)) {
				double dx = a[0] - b[0], dy = a[1] - b[1];
				c[nc++] = (struct cand){ dx * dx + dy * dy, i, j };
			}
		}
	qsort(c, nc, sizeof *c, cand_cmp);
	uint32_t *acc = malloc(2 * (nc + 1) * sizeof *acc);
	size_t na = 0;
	for (size_t k = 0; k < nc; k++) {
		const double *a = &p->xy[2 * c[k].a], *b = &p->xy[2 * c[k].b];
		int ok = 1;
		for (size_t q = 0; q < na && ok; q++)
			if (acc[2 * q] != c[k].a && acc[2 * q] != c[k].b && acc[2 * q + 1] != c[k].a && acc[2 * q + 1] != c[k].b &&
			    proper_cross(a, b, &p->xy[2 * acc[2 * q]], &p->xy[2 * acc[2 * q + 1]]))
				ok = 0;
		if (ok) {
			acc[2 * na] = c[k].a, acc[2 * na + 1] = c[k].b, na++;
			taken[c[k].a * n + c[k].b] = taken[c[k].b * n + c[k].a] = 1;
		}
	}
	free(c), free(acc);
	return taken;
}

/* The diagonals of a triangulation as an n x n matrix. */
static uint8_t *diagonals(const struct poly *p, const uint32_t *t, size_t nt)
{
	size_t n = p->np;
	uint8_t *d = calloc(n * n, 1);
	for (size_t k = 0; k < nt; k++)
		for (int q = 0; q < 3; q++) {
			uint32_t a = t[3 * k + q], b = t[3 * k + (q + 1) % 3];
			if (!is_loop_edge(p, a, b) && !is_loop_edge(p, b, a))
				d[a * n + b] = d[b * n + a] = 1;
		}
	return d;
}

static int has_edge(const uint32_t *t, size_t nt, uint32_t a, uint32_t b)
{
	for (size_t k = 0; k < nt; k++)
		for (int q = 0; q < 3; q++) {
			uint32_t x = t[3 * k + q], y = t[3 * k + (q + 1) % 3];
			if ((x == a && y == b) || (x == b && y == a))
				return 1;
		}
	return 0;
}

/* A convex quadrilateral whose shorter diagonal (a-b, 2) is not the
 * Delaunay one (x-w, 2.11): greedy takes a-b, CDT x-w. */
static void test_quad(void)
{
	struct poly p;
	poly_init(&p);
	static const double c[] = { -1, 0, 0, -2.1, 1, 0, 0, 0.01 };
	loop_pts(&p, c, 4);
	uint32_t *t;
	size_t nt;
	if (!run(&p, FCT_POLYTRI_GREEDY, &t, &nt, NULL)) {
		check_valid(&p, t, nt, 2);
		CHECK(has_edge(t, nt, 0, 2));
		CHECK(!has_edge(t, nt, 1, 3));
		free(t);
	}
	if (!run(&p, FCT_POLYTRI_CDT, &t, &nt, NULL)) {
		check_valid(&p, t, nt, 2);
		CHECK(has_edge(t, nt, 1, 3));
		CHECK_INT(cdt_violations(&p, t, nt), 0);
		free(t);
	}
	/* A plain rectangle 4 x 1 with a point pulled in: the shorter of the two
	 * diagonals of a convex quad is the greedy's first choice. */
	poly_free(&p);
	poly_init(&p);
	static const double r[] = { 0, 0, 4, 0, 4.5, 1, 0, 1.5 };
	loop_pts(&p, r, 4);
	/* diagonals: 0-2 = sqrt(20.25 + 1) = 4.61, 1-3 = sqrt(16 + 2.25) = 4.27 */
	if (!run(&p, FCT_POLYTRI_GREEDY, &t, &nt, NULL)) {
		CHECK(has_edge(t, nt, 1, 3));
		free(t);
	}
	poly_free(&p);
}

/* Square with square holes, L-shape, a hole touching the outer boundary. */
static void test_hand(void)
{
	static const double outer[] = { 0, 0, 10, 0, 10, 10, 0, 10 };
	static const double hole1[] = { 2, 2, 2, 4, 4, 4, 4, 2 };      /* clockwise */
	static const double hole2[] = { 6, 6, 6, 8, 8, 8, 8, 6 };
	for (int m = 0; m < 2; m++) {
		struct poly p;
		uint32_t *t;
		size_t nt;
		poly_init(&p);
		loop_pts(&p, outer, 4);
		loop_pts(&p, hole1, 4);
		CHECK_INT(nholes(&p), 1);
		if (!run(&p, m, &t, &nt, NULL)) {
			check_valid(&p, t, nt, 8 + 2 * 1 - 2);
			double a = 0;
			for (size_t k = 0; k < nt; k++)
				a += fct_polytri_loop_area2(p.xy, t + 3 * k, 3) / 2;
			CHECK(a == 96);   /* 100 - 4, exact in binary */
			free(t);
		}
		loop_pts(&p, hole2, 4);
		if (!run(&p, m, &t, &nt, NULL)) {
			check_valid(&p, t, nt, 12 + 2 * 2 - 2);
			double a = 0;
			for (size_t k = 0; k < nt; k++)
				a += fct_polytri_loop_area2(p.xy, t + 3 * k, 3) / 2;
			CHECK(a == 92);
			if (m == FCT_POLYTRI_CDT)
				CHECK_INT(cdt_violations(&p, t, nt), 0);
			free(t);
		}
		poly_free(&p);

		/* L: 6 corners, 4 triangles of total area 3. */
		static const double L[] = { 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2 };
		poly_init(&p);
		loop_pts(&p, L, 6);
		if (!run(&p, m, &t, &nt, NULL)) {
			check_valid(&p, t, nt, 4);
			free(t);
		}
		poly_free(&p);

		/* A triangular hole touching the square's corner (4,4): 7 corners,
		 * one shared, 5 triangles, area 16 - 1.5. */
		poly_init(&p);
		uint32_t a = pt(&p, 0, 0), b = pt(&p, 4, 0), c = pt(&p, 4, 4), d = pt(&p, 0, 4);
		uint32_t e = pt(&p, 3, 2), f = pt(&p, 2, 3);
		lvadd(&p, a), lvadd(&p, b), lvadd(&p, c), lvadd(&p, d), endloop(&p);
		lvadd(&p, c), lvadd(&p, e), lvadd(&p, f), endloop(&p);
		if (!run(&p, m, &t, &nt, NULL)) {
			check_valid(&p, t, nt, 5);
			free(t);
		}
		poly_free(&p);
	}
}

/* A star-shaped outer loop and two star-shaped holes, random. */
static void random_poly(struct poly *p, struct fct_rng *r, size_t n_out, size_t n_hole, int holes)
{
	poly_init(p);
	for (size_t k = 0; k < n_out; k++) {
		double th = 2 * M_PI * (k + 0.8 * fct_rng_uniform(r)) / n_out;
		double rad = 6 + 4 * fct_rng_uniform(r);
		lvadd(p, pt(p, rad * cos(th), rad * sin(th)));
	}
	endloop(p);
	for (int h = 0; h < holes; h++) {
		double cx = h ? 2.5 : -2.5, cy = h ? 0.5 : -0.5;
		for (size_t k = 0; k < n_hole; k++) {
			double th = -2 * M_PI * (k + 0.8 * fct_rng_uniform(r)) / n_hole;
			double rad = 0.5 + fct_rng_uniform(r);
			lvadd(p, pt(p, cx + rad * cos(th), cy + rad * sin(th)));
		}
		endloop(p);
	}
}

static void test_random_brute(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 42);
	size_t same = 0, runs = 0, cdt_bad = 0;
	for (int it = 0; it < 60; it++) {
		struct poly p;
		size_t no = 12 + fct_rng_below(&r, 33), nh = 3 + fct_rng_below(&r, 8);
		int holes = (int)fct_rng_below(&r, 3);
		random_poly(&p, &r, no, nh, holes);
		uint32_t *t;
		size_t nt;
		size_t want = p.nlv + 2 * (size_t)holes - 2;
		if (!run(&p, FCT_POLYTRI_GREEDY, &t, &nt, NULL)) {
			check_valid(&p, t, nt, want);
			uint8_t *a = diagonals(&p, t, nt), *b = brute_greedy(&p);
			same += !memcmp(a, b, p.np * p.np);
			runs++;
			free(a), free(b), free(t);
		}
		if (!run(&p, FCT_POLYTRI_CDT, &t, &nt, NULL)) {
			check_valid(&p, t, nt, want);
			cdt_bad += cdt_violations(&p, t, nt);
			free(t);
		}
		poly_free(&p);
	}
	CHECK_INT(runs, 60);
	CHECK_INT(same, runs);
	CHECK_INT(cdt_bad, 0);
}

/* Long boundaries: the result is complete and valid, and the greedy run
 * stays well inside its candidate budget (memory O(n)). */
static void test_long(void)
{
	struct poly p;
	uint32_t *t;
	size_t nt;
	struct fct_polytri_stats st;
	/* A strip 10000 long whose both sides zig-zag: 20000 vertices. */
	size_t m = 10000;
	poly_init(&p);
	for (size_t i = 0; i < m; i++)
		lvadd(&p, pt(&p, (double)i, (i % 2) * 0.3));
	for (size_t i = m; i-- > 0;)
		lvadd(&p, pt(&p, (double)i + 0.25, 2 + (i % 2) * 0.3));
	endloop(&p);
	for (int meth = 0; meth < 2; meth++) {
		memset(&st, 0, sizeof st);
		if (!run(&p, meth, &t, &nt, &st)) {
			check_valid(&p, t, nt, 2 * m - 2);
			free(t);
		}
		CHECK_INT(st.budget_hits, 0);
		if (meth == FCT_POLYTRI_GREEDY)
			CHECK_MSG(st.candidates < 20 * 2 * m, "%zu candidates for %zu vertices", st.candidates, 2 * m);
	}
	poly_free(&p);

	/* A comb: 2000 teeth 10 high and 0.5 wide, 0.5 apart: points across a
	 * gap are close but outside. */
	poly_init(&p);
	size_t teeth = 2000;
	lvadd(&p, pt(&p, 0, 0));
	lvadd(&p, pt(&p, (double)teeth, 0));
	for (size_t i = teeth; i-- > 0;) {
		lvadd(&p, pt(&p, i + 0.5, 1));
		lvadd(&p, pt(&p, i + 0.5, 11));
		lvadd(&p, pt(&p, (double)i, 11));
		if (i)
			lvadd(&p, pt(&p, (double)i, 1));
	}
	endloop(&p);
	for (int meth = 0; meth < 2; meth++) {
		memset(&st, 0, sizeof st);
		if (!run(&p, meth, &t, &nt, &st)) {
			check_valid(&p, t, nt, p.nlv - 2);
			free(t);
		}
		CHECK_INT(st.budget_hits, 0);
	}
	poly_free(&p);

	/* A circle of 20000 vertices: the greedy's long diagonals need many
	 * candidates, O(n log n). */
	poly_init(&p);
	for (size_t i = 0; i < 20000; i++)
		lvadd(&p, pt(&p, 1000 * cos(2 * M_PI * i / 20000), 1000 * sin(2 * M_PI * i / 20000)));
	endloop(&p);
	memset(&st, 0, sizeof st);
	if (!run(&p, FCT_POLYTRI_GREEDY, &t, &nt, &st)) {
		check_valid(&p, t, nt, 20000 - 2);
		free(t);
	}
	CHECK_INT(st.budget_hits, 0);
	poly_free(&p);
}

/* Loops polytri must refuse, and the ear-cutting repair. */
static void test_refuse(void)
{
	struct fct_err err;
	uint32_t *t;
	size_t nt;
	struct poly p;
	/* a bow tie */
	static const double bow[] = { 0, 0, 2, 2, 2, 0, 0, 2 };
	poly_init(&p);
	loop_pts(&p, bow, 4);
	for (int m = 0; m < 2; m++) {
		CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, m, NULL, &err), 1);
		CHECK(t == NULL);
	}
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, NULL, &err), 1);
	poly_free(&p);
	/* a clockwise square alone: wrong orientation */
	static const double cw[] = { 0, 0, 0, 1, 1, 1, 1, 0 };
	poly_init(&p);
	loop_pts(&p, cw, 4);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	poly_free(&p);
	/* a hole crossing the outer boundary: refused; repaired into
	 * 4 + 4 + 2 - 2 = 8 triangles */
	static const double sq[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
	static const double h[] = { 3, 1, 3, 3, 5, 3, 5, 1 };
	poly_init(&p);
	loop_pts(&p, sq, 4);
	loop_pts(&p, h, 4);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	struct fct_polytri_stats st;
	memset(&st, 0, sizeof st);
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, &st, &err), 0);
	CHECK_INT(nt, 8);
	free(t);
	poly_free(&p);
	/* a vertex on another loop's edge, two loop vertices at one point, a
	 * loop of two vertices, all on a line */
	static const double touch_o[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
	static const double touch_h[] = { 4, 2, 3, 1, 3, 3 };
	poly_init(&p);
	loop_pts(&p, touch_o, 4);
	loop_pts(&p, touch_h, 3);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	poly_free(&p);
	static const double dup[] = { 0, 0, 4, 0, 4, 4, 4, 0, 0, 4 };
	poly_init(&p);
	loop_pts(&p, dup, 5);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	poly_free(&p);
	static const double line[] = { 0, 0, 1, 1, 2, 2 };
	poly_init(&p);
	loop_pts(&p, line, 3);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	/* an index out of range is an error, not a refusal */
	p.lv[1] = 99;
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), -1);
	poly_free(&p);
}

/* tripatch ---------------------------------------------------------------- */

/* A wireframe: vertices (x y z, then s t when w is 5), edges (v1 v2 p1
 * p2), planes (nx ny nz d); s t are written when st is set. */
static void wire_w(struct fct_mesh *m, const double *v, size_t w, size_t nv, int st, const int *e,
                   size_t ne, const double *pl, size_t npl)
{
	struct fct_err err;
	fct_mesh_init(m);
	for (size_t i = 0; i < nv; i++)
		fct_mesh_add_vertex(m, v[w * i], v[w * i + 1], v[w * i + 2], &err);
	if (st) {
		fct_elem_add_scalar(&m->vertex, "s", FCT_FLOAT32, &err);
		fct_elem_add_scalar(&m->vertex, "t", FCT_FLOAT32, &err);
		for (size_t i = 0; i < nv; i++) {
			fct_prop_set(fct_elem_find(&m->vertex, "s"), i, v[w * i + 3]);
			fct_prop_set(fct_elem_find(&m->vertex, "t"), i, v[w * i + 4]);
		}
	}
	struct fct_elem *el = fct_mesh_add_elem(m, "edge", ne, &err);
	static const char *const names[] = { "vertex1", "vertex2", "patch1", "patch2" };
	for (int k = 0; k < 4; k++)
		fct_elem_add_scalar(el, names[k], FCT_INT32, &err);
	for (int k = 0; k < 4; k++)
		for (size_t i = 0; i < ne; i++)
			fct_prop_set(fct_elem_find(el, names[k]), i, e[4 * i + k]);
	if (pl) {
		struct fct_plane *p = calloc(npl, sizeof *p);
		for (size_t i = 0; i < npl; i++)
			memcpy(p[i].n, pl + 4 * i, 3 * sizeof(double)), p[i].d = pl[4 * i + 3];
		fct_planes_set(m, p, npl, &err);
		free(p);
	}
}

static void wire(struct fct_mesh *m, const double *v, size_t nv, int st, const int *e, size_t ne,
                 const double *pl, size_t npl)
{
	wire_w(m, v, st ? 5 : 3, nv, st, e, ne, pl, npl);
}

/* Sum over faces of patch p of (b - a) x (c - a) . n, and the area. */
static double patch_dot(const struct fct_mesh *m, int patch, const double n[3], double *area)
{
	const struct fct_prop *pp = fct_elem_find(&m->face, "patch");
	double s = 0;
	*area = 0;
	for (size_t f = 0; f < m->nf; f++) {
		if (fct_prop_get(pp, f) != patch)
			continue;
		const double *a = &m->xyz[3 * m->fvert[3 * f]], *b = &m->xyz[3 * m->fvert[3 * f + 1]],
		             *c = &m->xyz[3 * m->fvert[3 * f + 2]];
		double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
		double x[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
		double d = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
		s += d;
		*area += sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / 2;
		if (d <= 0)
			s -= 1e300;   /* one face against the normal spoils the sum */
	}
	return s;
}

static void test_wire_hole(void)
{
	/* The 4 x 4 square (patch 0) around the 2 x 2 square (patch 1) in the
	 * plane x = 1, normal +x, the inner square with s t seen mirrored. */
	static const double v[] = {
		1, 0, 0, 0.0, 1.0,  1, 4, 0, 1.0, 1.0,  1, 4, 4, 1.0, 0.0,  1, 0, 4, 0.0, 0.0,
		1, 1, 1, 0.25, 0.75, 1, 3, 1, 0.75, 0.75, 1, 3, 3, 0.75, 0.25, 1, 1, 3, 0.25, 0.25,
	};
	/* (y, z) counter-clockwise seen from +x: (0,0) (4,0) (4,4) (0,4) */
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1,
	                         4, 5, 1, 0, 5, 6, 1, 0, 6, 7, 1, 0, 7, 4, 1, 0 };
	static const double pl[] = { 1, 0, 0, -1, 1, 0, 0, -1 };
	for (int method = 0; method < 2; method++)
		for (int st = 0; st < 2; st++) {
			struct fct_mesh m;
			struct fct_err err;
			struct fct_tripatch_params p;
			struct fct_tripatch_stats s;
			wire_w(&m, v, 5, 8, st, e, 8, pl, 2);
			fct_tripatch_params_default(&p);
			p.method = method;
			CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
			CHECK_INT(m.nf, 10);
			CHECK_INT(s.triangles, 10);
			CHECK_INT(s.patches, 2);
			CHECK_INT(s.polygons, 2);
			CHECK_INT(s.holes, 1);
			CHECK_INT(s.in_st, st ? 2 : 0);
			CHECK_INT(s.in_plane, st ? 0 : 2);
			CHECK_INT(s.failures + s.repairs + s.fallbacks + s.reversed, 0);
			CHECK(fct_mesh_find_elem(&m, "edge") == NULL);
			CHECK(fct_mesh_find_elem(&m, "plane") != NULL);
			CHECK_INT(m.nv, 8);
			if (st)
				CHECK(fct_elem_find(&m.vertex, "s") != NULL);
			double area, n[3] = { 1, 0, 0 };
			CHECK(patch_dot(&m, 0, n, &area) > 0);
			CHECK(area == 12);
			CHECK(patch_dot(&m, 1, n, &area) > 0);
			CHECK(area == 4);
			fct_mesh_free(&m);
		}
}

/* One square patch in z = 0 seen from -z (normal -z, edges clockwise in
 * x, y), whose s t make a bow tie: s t refused, the plane used. */
static void test_wire_fallback(void)
{
	static const double v[] = {
		0, 0, 0, 0, 0,  0, 2, 0, 1, 1,  2, 2, 0, 1, 0,  2, 0, 0, 0, 1,
	};
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
	static const double pl[] = { 0, 0, -1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v, 4, 1, e, 4, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.fallbacks, 1);
	CHECK_INT(s.in_plane, 1);
	CHECK_INT(s.in_st, 0);
	CHECK_INT(m.nf, 2);
	double area, n[3] = { 0, 0, -1 };
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	CHECK(area == 4);
	fct_mesh_free(&m);

	/* The same with a plane normal of +z (against the edges): the patch is
	 * reversed to agree with the plane. */
	static const double up[] = { 0, 0, 1, 0 };
	wire_w(&m, v, 5, 4, 0, e, 4, up, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.reversed, 1);
	double n2[3] = { 0, 0, 1 };
	CHECK(patch_dot(&m, 0, n2, &area) > 0);
	fct_mesh_free(&m);

	/* No plane element: the Newell normal of the edges decides. */
	wire_w(&m, v, 5, 4, 0, e, 4, NULL, 0);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 2);
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	fct_mesh_free(&m);
}

/* Patch 0 is two squares meeting at the vertex (1,1) (a bow-tie-shaped
 * patch touching itself); patch 1 fills the rest of the 2 x 2 square as
 * two squares too.  Plus an open chain and a slit. */
static void test_wire_touch(void)
{
	/* 0 (0,0) 1 (1,0) 2 (2,0) 3 (0,1) 4 (1,1) 5 (2,1) 6 (0,2) 7 (1,2) 8 (2,2) */
	static const double v[] = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 0, 2, 0, 1, 2, 0, 2, 2, 0 };
	static const int e[] = {
		0, 1, 0, -1, 1, 4, 0, 1, 4, 3, 0, 1, 3, 0, 0, -1,     /* patch 0: lower left */
		4, 5, 0, 1, 5, 8, 0, -1, 8, 7, 0, -1, 7, 4, 0, 1,     /* patch 0: upper right */
		1, 2, 1, -1, 2, 5, 1, -1, 7, 6, 1, -1, 6, 3, 1, -1,   /* patch 1's border edges */
	};
	static const double pl[] = { 0, 0, 1, 0, 0, 0, 1, 0 };
	for (int method = 0; method < 2; method++) {
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, 9, 0, e, 12, pl, 2);
		fct_tripatch_params_default(&p);
		p.method = method;
		CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
		CHECK_INT(s.polygons, 4);
		CHECK_INT(s.holes, 0);
		CHECK_INT(m.nf, 8);
		CHECK_INT(s.failures + s.repairs + s.open_edges, 0);
		double area, n[3] = { 0, 0, 1 };
		CHECK(patch_dot(&m, 0, n, &area) > 0);
		CHECK(area == 2);
		CHECK(patch_dot(&m, 1, n, &area) > 0);
		CHECK(area == 2);
		fct_mesh_free(&m);
	}

	/* A square with a dangling edge and a slit (an edge with patch 0 on
	 * both sides) into its middle. */
	static const double v2[] = { 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 1, 0, 3, 3, 0 };
	static const int e2[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1,
	                          2, 4, 0, 0, 2, 5, 0, -1 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v2, 6, 0, e2, 6, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.open_edges, 1);
	CHECK_INT(s.slits, 1);
	CHECK_INT(m.nf, 2);
	fct_mesh_free(&m);

	/* Only a dangling edge: the patch fails, clearly counted. */
	static const int e3[] = { 0, 1, 0, -1 };
	wire(&m, v2, 6, 0, e3, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.failures, 1);
	CHECK_INT(s.first_failure, 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);

	/* A closed triangle whose corners projection put on one point and a
	 * line (two copies at one position, as on the TUM frame): no area in
	 * either frame, so a degenerate loop, not a failure. */
	static const double v4[] = { 0, 0, 0, 0, 0, 0, 1, 0, 0 };
	static const int e4[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 0, 0, -1 };
	wire(&m, v4, 3, 0, e4, 3, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.failures, 0);
	CHECK_INT(s.degenerate, 1);
	CHECK_INT(s.open_edges, 0);
	CHECK_INT(m.nf, 0);
	fct_mesh_free(&m);
}

/* A B C on one line in space but not in the image (B a little below A-C
 * there), D far above: the greedy method cuts the short diagonal A-C, so
 * A-B-C is a triangle of no area in space; its longest edge A-C is flipped
 * with A-C-D into A-B-D and B-C-D, of area 2.5 each. */
static void test_wire_sliver(void)
{
	static const double v[] = { 0, 0, 0, 0, 0, 1, 0, 0, 1, -0.01, 2, 0, 0, 2, 0, 1, 5, 0, 1, 5 };
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
	static const double pl[] = { 0, 0, 1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire(&m, v, 4, 1, e, 4, pl, 1);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.in_st, 1);
	CHECK_INT(s.slivers_flipped, 1);
	CHECK_INT(m.nf, 2);
	double area, n[3] = { 0, 0, 1 };
	CHECK(patch_dot(&m, 0, n, &area) > 0);
	CHECK_NEAR(area, 5, 1e-12);
	for (size_t f = 0; f < m.nf; f++) {
		int has_b = 0;
		for (int q = 0; q < 3; q++)
			has_b |= m.fvert[3 * f + q] == 1;
		CHECK(has_b);   /* both faces use B: the diagonal is B-D */
	}
	fct_mesh_free(&m);
}

/* Three boundary vertices on one image line at pixel centres (as dm2mesh
 * makes them), stored as float s t of a 640 x 480 camera: snapped to the
 * centres they are exactly collinear, so the greedy method cannot cut the
 * zero-area ear A-B-C through the short A-C and takes B-D instead (without
 * the snap, 17 of these 40 placements came out as slivers). */
static void test_wire_snap(void)
{
	size_t good = 0, runs = 0;
	for (int k = 0; k < 40; k++) {
		/* the same shape moved by k pixels: the float rounding differs */
		double px[] = { 100.5, 461.5, 101.5, 460.5, 102.5, 459.5, 102.5, 500.5 };
		double v[20];
		for (int i = 0; i < 4; i++) {
			px[2 * i] += 7 * k, px[2 * i + 1] -= 9 * k;
			v[5 * i] = px[2 * i] / 100, v[5 * i + 1] = px[2 * i + 1] / 100, v[5 * i + 2] = 1;
			v[5 * i + 3] = (float)(px[2 * i] / 640), v[5 * i + 4] = (float)(px[2 * i + 1] / 480);
		}
		static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 3, 0, -1, 3, 0, 0, -1 };
		static const double pl[] = { 0, 0, 1, -1 };
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, 4, 1, e, 4, pl, 1);
		fct_mesh_add_comment(&m, "camera pinhole 640 480 500 500 319.5 239.5", 0, &err);
		fct_tripatch_params_default(&p);
		if (fct_tripatch(&m, &p, &s, &err) == 0 && s.in_st == 1 && m.nf == 2) {
			size_t withd = 0;
			for (size_t f = 0; f < m.nf; f++)
				withd += m.fvert[3 * f] == 3 || m.fvert[3 * f + 1] == 3 || m.fvert[3 * f + 2] == 3;
			good += withd == 2;
		}
		runs++;
		fct_mesh_free(&m);
	}
	CHECK_INT(good, runs);
}

static void test_wire_bad(void)
{
	static const double v[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0 };
	static const int e[] = { 0, 1, 0, -1, 1, 2, 0, -1, 2, 0, 0, -1 };
	static const double pl[] = { 0, 0, 1, 0 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	fct_tripatch_params_default(&p);
	/* no edge element */
	fct_mesh_init(&m);
	fct_mesh_add_vertex(&m, 0, 0, 0, &err);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	CHECK(strstr(err.msg, "no edge element") != NULL);
	fct_mesh_free(&m);
	/* a patch that is not a plane */
	static const int e1[] = { 0, 1, 3, -1 };
	wire(&m, v, 3, 0, e1, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	CHECK(strstr(err.msg, "edge 0: patch 3") != NULL);
	fct_mesh_free(&m);
	/* a vertex out of range, equal ends, no patch */
	static const int e2[] = { 0, 7, 0, -1 }, e3[] = { 1, 1, 0, -1 }, e4[] = { 0, 1, -1, -1 };
	wire(&m, v, 3, 0, e2, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	wire(&m, v, 3, 0, e3, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	wire(&m, v, 3, 0, e4, 1, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, NULL, &err), -1);
	fct_mesh_free(&m);
	/* empty: no vertices, no edges */
	wire(&m, v, 0, 0, e, 0, pl, 1);
	struct fct_tripatch_stats s;
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 0);
	CHECK(m.has_faces);
	fct_mesh_free(&m);
	/* the good triangle */
	wire(&m, v, 3, 0, e, 3, pl, 1);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(m.nf, 1);
	CHECK_INT(m.fvert[0], 0);
	CHECK_INT(m.fvert[1], 1);
	CHECK_INT(m.fvert[2], 2);
	fct_mesh_free(&m);
}

/* Random edge soups (crossing, open, duplicated, random s t) and random
 * loops of a few patches: tripatch never fails on them, every face uses
 * existing vertices and no face repeats a vertex; closed random loops are
 * triangulated (repaired when they cross) with n - 2 triangles each. */
static void test_wire_random(void)
{
	struct fct_rng r;
	fct_rng_seed(&r, 7);
	size_t bad = 0, faces = 0, repairs = 0, earclipped = 0, loops_ok = 0;
	for (int it = 0; it < 300; it++) {
		size_t nv = 3 + fct_rng_below(&r, 30), ne = 1 + fct_rng_below(&r, 40);
		int closed = it % 2;
		double *v = malloc(5 * nv * sizeof *v);
		int *e = malloc(4 * (ne + nv) * sizeof *e);
		for (size_t i = 0; i < nv; i++) {
			v[5 * i] = fct_rng_uniform(&r), v[5 * i + 1] = fct_rng_uniform(&r);
			v[5 * i + 2] = 0.1 * fct_rng_uniform(&r);
			v[5 * i + 3] = fct_rng_uniform(&r), v[5 * i + 4] = fct_rng_uniform(&r);
		}
		if (closed) {
			/* one random (usually self-crossing) loop through all vertices */
			ne = nv;
			for (size_t i = 0; i < nv; i++) {
				e[4 * i] = (int)i, e[4 * i + 1] = (int)((i + 1) % nv);
				e[4 * i + 2] = 0, e[4 * i + 3] = -1;
			}
		} else {
			for (size_t i = 0; i < ne; i++) {
				e[4 * i] = (int)fct_rng_below(&r, nv);
				e[4 * i + 1] = (int)((e[4 * i] + 1 + fct_rng_below(&r, nv - 1)) % nv);
				e[4 * i + 2] = (int)fct_rng_below(&r, 3);
				e[4 * i + 3] = (int)fct_rng_below(&r, 4) - 1;
			}
		}
		static const double pl[] = { 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0 };
		struct fct_mesh m;
		struct fct_err err;
		struct fct_tripatch_params p;
		struct fct_tripatch_stats s;
		wire(&m, v, nv, (int)fct_rng_below(&r, 2), e, ne, pl, 3);
		fct_tripatch_params_default(&p);
		p.method = (int)fct_rng_below(&r, 2);
		int rc = fct_tripatch(&m, &p, &s, &err);
		bad += rc != 0;
		if (rc == 0) {
			for (size_t f = 0; f < m.nf; f++) {
				const uint32_t *t = &m.fvert[3 * f];
				bad += t[0] >= nv || t[1] >= nv || t[2] >= nv || t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
			}
			faces += m.nf, repairs += s.repairs, earclipped += s.earclipped;
			loops_ok += closed && m.nf == nv - 2;
		}
		fct_mesh_free(&m);
		free(v), free(e);
	}
	CHECK_INT(bad, 0);
	CHECK(faces > 0);
	CHECK(repairs > 0);
	CHECK(earclipped > 0);
	CHECK_INT(loops_ok, 150);
}

/* A ceiling seen by a cylindrical panorama (64 x 16, f = 64 / 2 pi, the
 * seam at +x, the ceiling 1 above the camera, y down): the room's corners
 * (the outer loop, in s t a simple sliver between rows 4.66 and 4.67)
 * and the panorama's top row (the hole: the disc overhead that no row
 * sees, in s t a line without area) both go round the camera, so in s t
 * neither is the polygon it is on the ceiling.  The 2048 x 512 room's
 * ceiling came out in s t as the corners' sliver without its hole: two
 * triangles over the zenith, which no planar view holds (cyl2planar
 * failed).  Triangulated in its plane it keeps the hole: 4 + 8 corners,
 * 12 triangles. */
static void test_wire_cylinder(void)
{
	const double W = 64, H = 16, f = W / (2 * M_PI), cy = 7.5;
	static const double corner[4][2] = { { 3, -2 }, { 3, 2 }, { -2.9, 2.1 }, { -2.9, -2.1 } };
	double v[12 * 5];
	for (int i = 0; i < 12; i++) {
		double x, z;
		if (i < 4) {
			x = corner[i][0], z = corner[i][1];
		} else {
			/* the top row's pixel edge: h = (-0.5 - cy) / f */
			double rho = -1 / ((-0.5 - cy) / f), th = 2 * M_PI * ((i - 4) * 8 + 0.5) / W;
			x = rho * sin(th), z = rho * cos(th);
		}
		double th = atan2(x, z), rho = hypot(x, z);
		double u = (th - M_PI / 2) * W / (2 * M_PI), row = cy + f * -1 / rho;
		u -= W * floor((u + 0.5) / W);
		v[5 * i] = x, v[5 * i + 1] = -1, v[5 * i + 2] = z;
		v[5 * i + 3] = (u + 0.5) / W, v[5 * i + 4] = 1 - (row + 0.5) / H;
	}
	/* outer: the corners in turn, clockwise in (x, z); hole: the octagon
	 * the other way round */
	int e[12 * 4], ne = 0;
	for (int i = 0; i < 4; i++) {
		int a[4] = { i, (i + 1) % 4, 0, -1 };
		memcpy(e + 4 * ne++, a, sizeof a);
	}
	for (int i = 0; i < 8; i++) {
		int a[4] = { 4 + i, 4 + (i + 1) % 8, 0, -1 };
		memcpy(e + 4 * ne++, a, sizeof a);
	}
	static const double pl[] = { 0, 1, 0, 1 };
	struct fct_mesh m;
	struct fct_err err;
	struct fct_tripatch_params p;
	struct fct_tripatch_stats s;
	wire_w(&m, v, 5, 12, 1, e, (size_t)ne, pl, 1);
	fct_mesh_add_comment(&m, "camera cylindrical 64 16 10.185916357881302 7.5 1.5707963267948966", 0, &err);
	fct_tripatch_params_default(&p);
	CHECK_INT(fct_tripatch(&m, &p, &s, &err), 0);
	CHECK_INT(s.holes, 1);
	CHECK_INT(s.in_plane, 1);
	CHECK_INT(m.nf, 12);
	double area, n[3] = { 0, 1, 0 };
	double rho = -1 / ((-0.5 - cy) / f);
	double octagon = 8 * 0.5 * rho * rho * sin(M_PI / 4), room = 0;
	for (int i = 0; i < 4; i++)
		room += corner[i][0] * corner[(i + 1) % 4][1] - corner[(i + 1) % 4][0] * corner[i][1];
	patch_dot(&m, 0, n, &area);
	CHECK_NEAR(area, fabs(room) / 2 - octagon, 1e-9);
	fct_mesh_free(&m);
}

int main(void)
{
	test_quad();
	test_hand();
	test_random_brute();
	test_long();
	test_refuse();
	test_wire_hole();
	test_wire_fallback();
	test_wire_touch();
	test_wire_bad();
	test_wire_random();
	test_wire_snap();
	test_wire_sliver();
	test_wire_cylinder();
	CHECK_DONE();
}
