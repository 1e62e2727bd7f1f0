/* test_polytri - the triangulation of polygons with holes (polytri.c), by
 * both methods, against hand-computed answers and independent checks.
 *
 * Hand cases: a square (greedy: the tie between its two diagonals goes to
 * the lower indices, 0-2), an L (greedy: its three diagonals of length
 * sqrt 2, the four triangles listed), a convex quadrilateral whose shorter
 * diagonal is not the Delaunay one, a square with a square hole (greedy:
 * the eight diagonals worked out by hand), with two holes, a hole touching
 * the outer boundary at a vertex, an island in a hole, a comb, collinear
 * runs along the edges; every result also checked for n + 2h - 2
 * triangles (n + 2h - 2k with k outer loops), all counter-clockwise, areas
 * summing to the loops' area, every loop vertex used, no centroid outside
 * the region or in a hole, every edge used once per side with loop edges
 * on the region's side only.  The greedy result equals, edge for edge, a
 * brute-force run of the paper's pseudo-code (all O(n^2) segments, sorted,
 * each added unless it crosses one taken) on random star-shaped polygons
 * with holes; CDT edges are locally Delaunay (empty circle across every
 * unconstrained edge); long boundaries (20000-vertex zig-zag strip, comb,
 * circle) stay within the candidate budget.  Loops it must refuse (bow
 * tie, wrong orientation, crossing or touching loops, repeated points, a
 * line, no loops, a short loop, a coordinate that is not finite) return 1
 * and the malformed calls -1; the repair of last resort
 * (fct_polytri_earclip) keeps the loops' signed area and topology; the
 * nesting of loops (fct_polytri_nest) and the loop area by hand. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "geom/polytri.h"
#include "geom/predicates.h"
#include "core/rng.h"

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
	/* Every loop vertex is a corner of some triangle, and no corner is
	 * another point. */
	uint8_t *used = calloc(p->np + 1, 1);
	size_t bad_index = 0, unused = 0;
	for (size_t k = 0; k < 3 * nt; k++) {
		if (t[k] < p->np)
			used[t[k]] = 1;
		else
			bad_index++;
	}
	for (size_t k = 0; k < p->nlv; k++)
		unused += !used[p->lv[k]];
	free(used);
	CHECK_INT(bad_index, 0);
	CHECK_INT(unused, 0);
	return ok && bad_edge == 0 && bad_index == 0 && unused == 0;
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

/* Hand-computed cases ----------------------------------------------------- */

/* Is (a, b, c) a triangle of t, in that cyclic order? */
static int has_tri(const uint32_t *t, size_t nt, uint32_t a, uint32_t b, uint32_t c)
{
	for (size_t k = 0; k < nt; k++)
		for (int r = 0; r < 3; r++)
			if (t[3 * k + r] == a && t[3 * k + (r + 1) % 3] == b && t[3 * k + (r + 2) % 3] == c)
				return 1;
	return 0;
}

/* The triangles' total signed area, from their corners (not from polytri). */
static double tri_area(const struct poly *p, const uint32_t *t, size_t nt)
{
	double s = 0;
	for (size_t k = 0; k < nt; k++) {
		const double *a = &p->xy[2 * (size_t)t[3 * k]], *b = &p->xy[2 * (size_t)t[3 * k + 1]],
		             *c = &p->xy[2 * (size_t)t[3 * k + 2]];
		s += ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
	}
	return s;
}

/* Triangulate p by method m and check the result: valid with want
 * triangles, their area exactly area (every case here is exact in binary),
 * and for the CDT locally Delaunay.  The triangles (free()), or NULL when
 * the call failed. */
static uint32_t *triangulate(const struct poly *p, enum fct_polytri_method m, size_t want, double area,
                             size_t *nt)
{
	uint32_t *t;
	if (run(p, m, &t, nt, NULL))
		return NULL;
	check_valid(p, t, *nt, want);
	CHECK_MSG(tri_area(p, t, *nt) == area, "area %.17g, want %.17g", tri_area(p, t, *nt), area);
	if (m == FCT_POLYTRI_CDT)
		CHECK_INT(cdt_violations(p, t, *nt), 0);
	return t;
}

/* Each of the n diagonals d[k] is an edge of t (present) or is not. */
static void check_diagonals(const uint32_t *t, size_t nt, const uint32_t (*d)[2], size_t n, int present)
{
	for (size_t k = 0; k < n; k++)
		CHECK_MSG(has_edge(t, nt, d[k][0], d[k][1]) == present, "diagonal %u-%u %s", d[k][0], d[k][1],
		          present ? "missing" : "taken");
}

/* The unit square: two triangles of area 1/2.  Its diagonals are equally
 * long; the greedy order breaks the tie by the lower index, so 0-2. */
static void test_square(void)
{
	static const double sq[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	loop_pts(&p, sq, 4);
	CHECK(fct_polytri_loop_area2(p.xy, p.lv, 4) == 2);
	if ((t = triangulate(&p, FCT_POLYTRI_GREEDY, 2, 1, &nt))) {
		CHECK(has_tri(t, nt, 0, 1, 2));
		CHECK(has_tri(t, nt, 0, 2, 3));
		free(t);
	}
	free(triangulate(&p, FCT_POLYTRI_CDT, 2, 1, &nt));
	poly_free(&p);
}

/* The L (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), area 3.  Its valid diagonals
 * by squared length: 0-3, 1-3, 3-5 (2), 0-2, 0-4 (5); 1-4, 2-5 and 2-4 leave
 * the region and 1-5 passes through vertex 3.  Greedy takes the three of
 * length sqrt 2: triangles 0 1 3 (area 1), 1 2 3 (1/2), 3 4 5 (1/2),
 * 0 3 5 (1). */
static void test_L(void)
{
	static const double L[] = { 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2 };
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	loop_pts(&p, L, 6);
	if ((t = triangulate(&p, FCT_POLYTRI_GREEDY, 4, 3, &nt))) {
		CHECK(has_tri(t, nt, 0, 1, 3));
		CHECK(has_tri(t, nt, 1, 2, 3));
		CHECK(has_tri(t, nt, 3, 4, 5));
		CHECK(has_tri(t, nt, 0, 3, 5));
		free(t);
	}
	free(triangulate(&p, FCT_POLYTRI_CDT, 4, 3, &nt));
	poly_free(&p);
}

/* The square 0..4 (vertices 0-3) around the square hole 1..3 (vertices
 * 4-7, clockwise: (1,1) (1,3) (3,3) (3,1)): 8 + 2 - 2 = 8 triangles, area
 * 16 - 4 = 12.  Greedy: first each outer corner to the hole corner facing
 * it (squared length 2: 0-4, 1-7, 2-6, 3-5); then of the pairs of squared
 * length 10, in the order 0-5, 0-7, 1-4, 1-6, 2-5, 2-7, 3-4, 3-6, those
 * that cross none taken: 0-5, 0-7, 1-6, 2-5. */
static void test_hole(void)
{
	static const double outer[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
	static const double hole[] = { 1, 1, 1, 3, 3, 3, 3, 1 };
	static const uint32_t taken[][2] = { { 0, 4 }, { 1, 7 }, { 2, 6 }, { 3, 5 },
	                                     { 0, 5 }, { 0, 7 }, { 1, 6 }, { 2, 5 } };
	static const uint32_t crossing[][2] = { { 1, 4 }, { 2, 7 }, { 3, 4 }, { 3, 6 } };
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	loop_pts(&p, outer, 4);
	loop_pts(&p, hole, 4);
	CHECK(fct_polytri_loop_area2(p.xy, p.lv + 4, 4) == -8);
	if ((t = triangulate(&p, FCT_POLYTRI_GREEDY, 8, 12, &nt))) {
		check_diagonals(t, nt, taken, 8, 1);
		check_diagonals(t, nt, crossing, 4, 0);
		free(t);
	}
	free(triangulate(&p, FCT_POLYTRI_CDT, 8, 12, &nt));
	poly_free(&p);
}

/* An island in a hole: the square 0..10, the hole 2..8, the square 3..7
 * inside it: two outer loops, so 12 + 2 - 2 * 2 = 10 triangles (8 in the
 * frame, 2 in the island), area 100 - 36 + 16 = 80. */
static void test_island(void)
{
	static const double outer[] = { 0, 0, 10, 0, 10, 10, 0, 10 };
	static const double hole[] = { 2, 2, 2, 8, 8, 8, 8, 2 };
	static const double island[] = { 3, 3, 7, 3, 7, 7, 3, 7 };
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	loop_pts(&p, outer, 4);
	loop_pts(&p, hole, 4);
	loop_pts(&p, island, 4);
	for (int m = 0; m < 2; m++)
		if ((t = triangulate(&p, m, 10, 80, &nt))) {
			/* the island's two triangles use only its corners */
			size_t in_island = 0;
			for (size_t k = 0; k < nt; k++)
				in_island += t[3 * k] >= 8 && t[3 * k + 1] >= 8 && t[3 * k + 2] >= 8;
			CHECK_INT(in_island, 2);
			free(t);
		}
	poly_free(&p);
}

/* A comb of three teeth 0.5 wide and 10 high on a base 3 x 1: 14 corners,
 * 12 triangles, area 3 + 3 * 5 = 18.  Corners across a gap are close (0.5)
 * but the segment between them is outside. */
static void test_comb(void)
{
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	lvadd(&p, pt(&p, 0, 0));
	lvadd(&p, pt(&p, 3, 0));
	lvadd(&p, pt(&p, 3, 1));
	for (size_t i = 3; i-- > 0;) {
		lvadd(&p, pt(&p, i + 0.5, 1));
		lvadd(&p, pt(&p, i + 0.5, 11));
		lvadd(&p, pt(&p, (double)i, 11));
		if (i)
			lvadd(&p, pt(&p, (double)i, 1));
	}
	endloop(&p);
	CHECK_INT(p.nlv, 14);
	for (int m = 0; m < 2; m++)
		if ((t = triangulate(&p, m, 12, 18, &nt))) {
			/* no edge joins two teeth: above the base, the corners of an
			 * edge are at most a tooth's width apart */
			size_t across = 0;
			for (size_t k = 0; k < 3 * nt; k++) {
				const double *a = &p.xy[2 * (size_t)t[k]], *b = &p.xy[2 * (size_t)t[k - k % 3 + (k + 1) % 3]];
				across += a[1] > 1 && b[1] > 1 && fabs(a[0] - b[0]) > 0.5;
			}
			CHECK_INT(across, 0);
			free(t);
		}
	poly_free(&p);
}

/* Collinear runs along the edges.  The rectangle 3 x 1 with a vertex at
 * every unit: (0,0) (1,0) (2,0) (3,0) (3,1) (2,1) (1,1) (0,1), 6 triangles
 * of area 1/2.  Greedy takes the two inner uprights (1-6, 2-5; length 1),
 * then in each unit square the diagonal of lower indices (0-6, 1-5, 2-4).
 * A triangle with a vertex in the middle of its base, (0,0) (2,0) (4,0)
 * (2,2): the only diagonal is 1-3. */
static void test_collinear(void)
{
	static const double run3[] = { 0, 0, 1, 0, 2, 0, 3, 0, 3, 1, 2, 1, 1, 1, 0, 1 };
	static const uint32_t taken[][2] = { { 1, 6 }, { 2, 5 }, { 0, 6 }, { 1, 5 }, { 2, 4 } };
	static const uint32_t other[][2] = { { 1, 7 }, { 2, 6 }, { 3, 5 } };
	struct poly p;
	uint32_t *t;
	size_t nt;
	poly_init(&p);
	loop_pts(&p, run3, 8);
	if ((t = triangulate(&p, FCT_POLYTRI_GREEDY, 6, 3, &nt))) {
		check_diagonals(t, nt, taken, 5, 1);
		check_diagonals(t, nt, other, 3, 0);
		free(t);
	}
	free(triangulate(&p, FCT_POLYTRI_CDT, 6, 3, &nt));
	poly_free(&p);
	static const double base[] = { 0, 0, 2, 0, 4, 0, 2, 2 };
	poly_init(&p);
	loop_pts(&p, base, 4);
	for (int m = 0; m < 2; m++)
		if ((t = triangulate(&p, m, 2, 4, &nt))) {
			CHECK(has_tri(t, nt, 0, 1, 3));
			CHECK(has_tri(t, nt, 1, 2, 3));
			free(t);
		}
	poly_free(&p);
}

/* Refusals not covered above, with their messages, and malformed calls. */
static void test_refuse_more(void)
{
	struct fct_err err;
	uint32_t *t = NULL;
	size_t nt = 7;
	struct poly p;
	static const double sq[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
	poly_init(&p);
	loop_pts(&p, sq, 4);
	/* no loops */
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, 0, p.lv, 0, NULL, &err), 1);
	CHECK(t == NULL && nt == 0);
	CHECK_STR(err.msg, "no loops");
	/* a loop of two vertices */
	uint32_t ls2[2] = { 0, 2 };
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, ls2, 1, p.lv, 0, NULL, &err), 1);
	CHECK_STR(err.msg, "loop 0 has 2 vertices");
	/* loop 0 not starting at 0, a loop of negative length: malformed */
	uint32_t ls_bad[2] = { 1, 4 };
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, ls_bad, 1, p.lv, 0, NULL, &err), -1);
	uint32_t ls_neg[3] = { 0, 4, 3 };
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, ls_neg, 2, p.lv, 0, NULL, &err), -1);
	/* a vertex twice in a row */
	uint32_t rep[5] = { 0, 1, 1, 2, 3 };
	uint32_t ls5[2] = { 0, 5 };
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, ls5, 1, rep, 0, NULL, &err), 1);
	CHECK_STR(err.msg, "loop 0: vertex 1 twice in a row");
	/* a coordinate that is not finite: refused (1), like the other bad loops */
	p.xy[5] = NAN;
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	CHECK_STR(err.msg, "point 2: coordinate is not finite");
	p.xy[5] = HUGE_VAL;
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 1, NULL, &err), 1);
	CHECK(t == NULL);
	poly_free(&p);
	/* a bow tie: its edges cross */
	static const double bow[] = { 0, 0, 2, 2, 2, 0, 0, 2 };
	poly_init(&p);
	loop_pts(&p, bow, 4);
	for (int m = 0; m < 2; m++) {
		err.msg[0] = 0;
		CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, m, NULL, &err), 1);
		CHECK_MSG(strstr(err.msg, "crosses") || strstr(err.msg, "do not bound"), "bow tie: %s", err.msg);
	}
	poly_free(&p);
	/* a hole outside the outer loop: the flood leaves the region */
	static const double far_hole[] = { 6, 1, 6, 3, 8, 3, 8, 1 };
	poly_init(&p);
	loop_pts(&p, sq, 4);
	loop_pts(&p, far_hole, 4);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	CHECK_STR(err.msg, "the loops do not bound a region (wrong orientation or nesting)");
	poly_free(&p);
}

/* The repair of last resort: ears cut from each outer loop joined to its
 * holes by bridges.  The triangles keep the loops' signed area exactly (an
 * ear's removal takes its own signed area from the sequence's; bridges are
 * walked both ways), n + 2h - 2 of them per outer loop. */
static void test_earclip(void)
{
	struct fct_err err;
	struct fct_polytri_stats st;
	uint32_t *t;
	size_t nt;
	struct poly p;
	/* a simple polygon: a valid triangulation, no forced ear */
	static const double L[] = { 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2 };
	poly_init(&p);
	loop_pts(&p, L, 6);
	memset(&st, 0, sizeof st);
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, &st, &err), 0);
	if (t) {
		check_valid(&p, t, nt, 4);
		CHECK(tri_area(&p, t, nt) == 3);
		free(t);
	}
	CHECK_INT(st.forced_ears, 0);
	poly_free(&p);
	/* a hole crossing the outer boundary (refused by fct_polytri):
	 * 4 + 4 + 2 - 2 = 8 triangles of signed area 16 - 4 */
	static const double sq[] = { 0, 0, 4, 0, 4, 4, 0, 4 };
	static const double h[] = { 3, 1, 3, 3, 5, 3, 5, 1 };
	poly_init(&p);
	loop_pts(&p, sq, 4);
	loop_pts(&p, h, 4);
	CHECK_INT(fct_polytri(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, 0, NULL, &err), 1);
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, NULL, &err), 0);
	if (t) {
		CHECK_INT(nt, 8);
		CHECK(tri_area(&p, t, nt) == 12);
		uint8_t used[8] = { 0 };
		size_t bad_index = 0;
		for (size_t k = 0; k < 3 * nt; k++) {
			if (t[k] < 8)
				used[t[k]] = 1;
			else
				bad_index++;
		}
		CHECK_INT(bad_index, 0);
		CHECK(memchr(used, 0, 8) == NULL);
		free(t);
	}
	poly_free(&p);
	/* two outer loops apart: each cut alone, 2 + 2 triangles, area 1 + 4 */
	static const double a[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
	static const double b[] = { 5, 0, 7, 0, 7, 2, 5, 2 };
	poly_init(&p);
	loop_pts(&p, a, 4);
	loop_pts(&p, b, 4);
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, NULL, &err), 0);
	if (t) {
		check_valid(&p, t, nt, 4);
		CHECK(tri_area(&p, t, nt) == 5);
		free(t);
	}
	/* an index out of range: -1 */
	p.lv[6] = 8;
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, NULL, &err), -1);
	CHECK(t == NULL);
	poly_free(&p);
	/* only clockwise loops: nothing to cut (1) */
	static const double cw[] = { 0, 0, 0, 1, 1, 1, 1, 0 };
	poly_init(&p);
	loop_pts(&p, cw, 4);
	CHECK_INT(fct_polytri_earclip(&t, &nt, p.xy, p.np, p.lstart, p.nl, p.lv, NULL, &err), 1);
	CHECK_STR(err.msg, "no loop of positive area");
	poly_free(&p);
}

/* Which outer loop each hole belongs to: the smallest that contains its
 * first vertex, else the largest. */
static void test_nest(void)
{
	static const double A[] = { 0, 0, 10, 0, 10, 10, 0, 10 };     /* outer, area 100 */
	static const double hA[] = { 2, 2, 2, 8, 8, 8, 8, 2 };       /* hole in A */
	static const double B[] = { 3, 3, 7, 3, 7, 7, 3, 7 };        /* outer, in hA */
	static const double hB[] = { 4, 4, 4, 6, 6, 6, 6, 4 };       /* hole in B (and in A) */
	static const double C[] = { 20, 0, 22, 0, 22, 2, 20, 2 };    /* outer, apart */
	static const double hC[] = { 20.5, 0.5, 20.5, 1.5, 21.5, 1.5, 21.5, 0.5 };
	static const double hX[] = { 30, 0, 30, 1, 31, 1, 31, 0 };   /* in no outer loop */
	struct poly p;
	poly_init(&p);
	loop_pts(&p, A, 4);
	loop_pts(&p, hA, 4);
	loop_pts(&p, B, 4);
	loop_pts(&p, hB, 4);
	loop_pts(&p, C, 4);
	loop_pts(&p, hC, 4);
	loop_pts(&p, hX, 4);
	long owner[7];
	CHECK_INT(fct_polytri_nest(owner, p.xy, p.lstart, p.nl, p.lv), 0);
	static const long want[7] = { 0, 0, 2, 2, 4, 4, 0 };
	for (int l = 0; l < 7; l++)
		CHECK_MSG(owner[l] == want[l], "loop %d: owner %ld, want %ld", l, owner[l], want[l]);
	poly_free(&p);
	/* holes only */
	poly_init(&p);
	loop_pts(&p, hA, 4);
	loop_pts(&p, hB, 4);
	CHECK_INT(fct_polytri_nest(owner, p.xy, p.lstart, p.nl, p.lv), 1);
	CHECK(owner[0] == -1 && owner[1] == -1);
	poly_free(&p);
}

/* Twice the signed area, by hand. */
static void test_loop_area(void)
{
	static const double xy[] = { 1, 1, 4, 1, 4, 3, 1, 3, 2, 2 };
	static const uint32_t ccw[] = { 0, 1, 2, 3 }, cw[] = { 3, 2, 1, 0 }, tri[] = { 0, 1, 4 };
	CHECK(fct_polytri_loop_area2(xy, ccw, 4) == 12);
	CHECK(fct_polytri_loop_area2(xy, cw, 4) == -12);
	CHECK(fct_polytri_loop_area2(xy, tri, 3) == 3);
	CHECK(fct_polytri_loop_area2(xy, ccw, 2) == 0);
}

int main(void)
{
	test_square();
	test_L();
	test_quad();
	test_hole();
	test_hand();
	test_island();
	test_comb();
	test_collinear();
	test_random_brute();
	test_long();
	test_refuse();
	test_refuse_more();
	test_earclip();
	test_nest();
	test_loop_area();
	CHECK_DONE();
}
